#include "sss/context.h"

#include "gl/allocation.h"
#include "gl/device.h"
#include "gl/gl.h"
#include "sss/error.h"
#include "sss/log.h"

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>

namespace sss {

struct GlContext::DebugState {
    std::atomic<std::uint64_t> errors{0}, warnings{0}, other{0};
    std::mutex mutex;
    std::string lastError;
};

namespace {

const char* debugSourceName(GLenum source) {
    switch (source) {
        case GL_DEBUG_SOURCE_API: return "api";
        case GL_DEBUG_SOURCE_WINDOW_SYSTEM: return "window system";
        case GL_DEBUG_SOURCE_SHADER_COMPILER: return "shader compiler";
        case GL_DEBUG_SOURCE_THIRD_PARTY: return "third party";
        case GL_DEBUG_SOURCE_APPLICATION: return "application";
        default: return "other";
    }
}

const char* debugTypeName(GLenum type) {
    switch (type) {
        case GL_DEBUG_TYPE_ERROR: return "error";
        case GL_DEBUG_TYPE_DEPRECATED_BEHAVIOR: return "deprecated";
        case GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR: return "undefined behaviour";
        case GL_DEBUG_TYPE_PORTABILITY: return "portability";
        case GL_DEBUG_TYPE_PERFORMANCE: return "performance";
        default: return "other";
    }
}

void GLAD_API_PTR onDebugMessage(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei,
                                 const GLchar* message, const void* user) {
    auto* state = static_cast<GlContext::DebugState*>(const_cast<void*>(user));
    std::string text = std::string("GL ") + debugTypeName(type) + " (" + debugSourceName(source) +
                       ", id " + std::to_string(id) + "): " + message;
    LogLevel level = LogLevel::Debug;
    // Inside a checked allocation, out-of-memory is an answer libsss handles (gl/allocation.h).
    if (type == GL_DEBUG_TYPE_ERROR && source == GL_DEBUG_SOURCE_API && gl::deferAllocationError(text)) {
        ++state->other;
        return;
    }
    // Compile and link failures also arrive here; they are reported, with file:line locations,
    // by the Error the shader code throws, so they are not counted as GL errors.
    if (type == GL_DEBUG_TYPE_ERROR && source != GL_DEBUG_SOURCE_SHADER_COMPILER) {
        ++state->errors;
        level = LogLevel::Error;
        std::lock_guard lock(state->mutex);
        state->lastError = text;
    } else if ((type == GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR || type == GL_DEBUG_TYPE_DEPRECATED_BEHAVIOR) &&
               severity != GL_DEBUG_SEVERITY_NOTIFICATION) {
        ++state->warnings;
        level = LogLevel::Warning;
    } else {
        ++state->other;
    }
    log(level, text);
}

std::string glString(GLenum name) {
    const GLubyte* s = glGetString(name);
    return s ? reinterpret_cast<const char*>(s) : "";
}

}  // namespace

void GlContext::initializeGl(const GlProcLoader& getProcAddress, bool debug, std::string backend) {
    const auto load = [](void* loader, const char* name) -> GLADapiproc {
        return (*static_cast<const GlProcLoader*>(loader))(name);
    };
    int version = gladLoadGLUserPtr(load, const_cast<GlProcLoader*>(&getProcAddress));
    if (version == 0)
        throw Error(ErrorKind::Gl, "GlContext: could not load OpenGL entry points (" + backend + ")");
    m_info.vendor = glString(GL_VENDOR);
    m_info.renderer = glString(GL_RENDERER);
    m_info.version = glString(GL_VERSION);
    m_info.backend = std::move(backend);
    GLint major = 0, minor = 0, profile = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    if (major * 10 + minor < 45 || !(profile & GL_CONTEXT_CORE_PROFILE_BIT))
        throw Error(ErrorKind::Gl, "GlContext: libsss needs OpenGL 4.5 core, but " + m_info.backend +
                                       " gave \"" + m_info.version + "\" on " + m_info.renderer);
    m_info.software = gl::isSoftwareRendererName(m_info.renderer);

    // The backends that make their own contexts also switch this on for SSS_GL_DEBUG=1; an
    // adopted host context only when asked (HostContextOptions::debug).
    if (debug) {
        m_debug = std::make_shared<DebugState>();
        glEnable(GL_DEBUG_OUTPUT);
        // Synchronous, so a message is delivered inside the call that caused it.
        glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
        glDebugMessageCallback(onDebugMessage, m_debug.get());
        glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
        m_info.debug = true;
    }
    log(LogLevel::Info, "GL context: " + m_info.renderer + ", " + m_info.version + " via " + m_info.backend);
}

DebugMessageCounts GlContext::debugMessages() const {
    if (!m_debug) return {};
    return {m_debug->errors.load(), m_debug->warnings.load(), m_debug->other.load()};
}

void GlContext::resetDebugMessages() {
    if (!m_debug) return;
    m_debug->errors = m_debug->warnings = m_debug->other = 0;
    std::lock_guard lock(m_debug->mutex);
    m_debug->lastError.clear();
}

std::string GlContext::lastDebugError() const {
    if (!m_debug) return {};
    std::lock_guard lock(m_debug->mutex);
    return m_debug->lastError;
}

}  // namespace sss
