#include "sss/context.h"
#include "sss/error.h"
#include "sss/log.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace sss {
namespace {

std::string eglErrorName(EGLint code) {
    switch (code) {
        case EGL_SUCCESS: return "EGL_SUCCESS";
        case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
        case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
        case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
        case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
        case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
        case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
        case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
        case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
        case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
        case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
        default: {
            char buf[32];
            std::snprintf(buf, sizeof buf, "EGL error 0x%04x", static_cast<unsigned>(code));
            return buf;
        }
    }
}

bool hasExtension(const char* list, const char* name) {
    if (!list) return false;
    const size_t n = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    return false;
}

bool envFlag(const char* name) {
    const char* v = std::getenv(name);
    return v && *v && std::strcmp(v, "0") != 0;
}

// EGL displays are process-wide and eglTerminate is not reference counted, so contexts that share
// a display count their users and the last one terminates it.
std::mutex g_displayMutex;
std::map<EGLDisplay, int> g_displayUsers;

void retainDisplay(EGLDisplay d) {
    std::lock_guard lock(g_displayMutex);
    ++g_displayUsers[d];
}

void releaseDisplay(EGLDisplay d) {
    std::lock_guard lock(g_displayMutex);
    if (--g_displayUsers[d] == 0) {
        g_displayUsers.erase(d);
        eglTerminate(d);
    }
}

struct DisplayCandidate {
    EglPlatform platform;
    EGLDisplay display;
    std::string description;
};

struct Devices {
    std::vector<EGLDeviceEXT> software, hardware;
};

Devices enumerateDevices(const char* clientExtensions) {
    Devices result;
    if (!hasExtension(clientExtensions, "EGL_EXT_device_enumeration") &&
        !hasExtension(clientExtensions, "EGL_EXT_device_base"))
        return result;
    auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto queryString =
        reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
    if (!queryDevices || !queryString) return result;
    EGLint count = 0;
    if (!queryDevices(0, nullptr, &count) || count <= 0) return result;
    std::vector<EGLDeviceEXT> devices(static_cast<size_t>(count));
    queryDevices(count, devices.data(), &count);
    for (EGLint i = 0; i < count; ++i) {
        const char* ext = queryString(devices[static_cast<size_t>(i)], EGL_EXTENSIONS);
        (hasExtension(ext, "EGL_MESA_device_software") ? result.software : result.hardware)
            .push_back(devices[static_cast<size_t>(i)]);
    }
    return result;
}

}  // namespace

namespace {

// The EGL objects behind one context.
struct EglHandles {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    EGLSurface surface = EGL_NO_SURFACE;
};

// The platforms to try. Surfaceless, device, default display + pbuffer — except that when a
// hardware EGL device exists (an NVIDIA GPU, say) the device goes first: Mesa's surfaceless
// platform would pick llvmpipe on such a machine, and NVIDIA's own surfaceless platform its GPU,
// so only the device list tells hardware and software apart.
std::vector<EglPlatform> platformOrder(EglPlatform asked, const Devices& devices) {
    if (asked != EglPlatform::Auto) return {asked};
    if (!devices.hardware.empty()) return {EglPlatform::Device, EglPlatform::Surfaceless, EglPlatform::DefaultPbuffer};
    return {EglPlatform::Surfaceless, EglPlatform::Device, EglPlatform::DefaultPbuffer};
}

// What EGL needs to look for displays, found once.
struct DisplaySearch {
    const char* clientExtensions;
    PFNEGLGETPLATFORMDISPLAYEXTPROC getPlatformDisplay;
    Devices devices;
    bool preferSoftware;
};

// The display of one platform (EGL_NO_DISPLAY with the reason in `failure` if there is none).
DisplayCandidate findDisplay(EglPlatform platform, const DisplaySearch& search, std::string& failure) {
    DisplayCandidate candidate{platform, EGL_NO_DISPLAY, ""};
    auto extension = [&](const char* name) {
        if (search.getPlatformDisplay && hasExtension(search.clientExtensions, name)) return true;
        failure = candidate.description + ": extension not available";
        return false;
    };
    switch (platform) {
        case EglPlatform::Surfaceless:
            candidate.description = "EGL surfaceless (EGL_MESA_platform_surfaceless)";
            if (!extension("EGL_MESA_platform_surfaceless")) return candidate;
            candidate.display = search.getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
            break;
        case EglPlatform::Device: {
            candidate.description = "EGL device (EGL_EXT_platform_device)";
            if (!extension("EGL_EXT_platform_device")) return candidate;
            const Devices& d = search.devices;
            const auto& first = search.preferSoftware ? d.software : d.hardware;
            const auto& second = search.preferSoftware ? d.hardware : d.software;
            const auto& list = first.empty() ? second : first;
            if (list.empty()) {
                failure = candidate.description + ": no EGL devices found";
                return candidate;
            }
            candidate.description = std::string("EGL device (") + (&list == &d.software ? "software" : "hardware") + ")";
            candidate.display = search.getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, list.front(), nullptr);
            break;
        }
        case EglPlatform::DefaultPbuffer:
        case EglPlatform::Auto:
            candidate.description = "EGL default display + pbuffer";
            candidate.display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
            break;
    }
    if (candidate.display == EGL_NO_DISPLAY)
        failure = candidate.description + ": no display (" + eglErrorName(eglGetError()) + ")";
    return candidate;
}

// An RGBA8 OpenGL config, with pbuffer support where a surface is needed.
std::optional<EGLConfig> chooseConfig(EGLDisplay display, bool needsPbuffer) {
    for (EGLint surfaceType : {EGL_PBUFFER_BIT, 0}) {
        if (needsPbuffer && surfaceType == 0) break;
        const EGLint attribs[] = {EGL_SURFACE_TYPE, surfaceType, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_RED_SIZE, 8,
                                  EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_ALPHA_SIZE, 8, EGL_NONE};
        EGLConfig config = nullptr;
        EGLint count = 0;
        if (eglChooseConfig(display, attribs, &config, 1, &count) && count > 0) return config;
    }
    return std::nullopt;
}

// A current OpenGL 4.5 core context on an initialized display, or nothing with the reason added
// to `failures` (and everything made so far released).
std::optional<EglHandles> makeCurrentContext(const DisplayCandidate& candidate, bool debug,
                                             std::vector<std::string>& failures) {
    EglHandles handles;
    handles.display = candidate.display;
    auto fail = [&](const std::string& what) -> std::optional<EglHandles> {
        failures.push_back(candidate.description + ": " + what + " (" + eglErrorName(eglGetError()) + ")");
        if (handles.surface != EGL_NO_SURFACE) eglDestroySurface(handles.display, handles.surface);
        if (handles.context != EGL_NO_CONTEXT) eglDestroyContext(handles.display, handles.context);
        releaseDisplay(handles.display);
        return std::nullopt;
    };
    if (!eglBindAPI(EGL_OPENGL_API)) return fail("eglBindAPI(EGL_OPENGL_API) failed");
    const bool needsPbuffer = candidate.platform == EglPlatform::DefaultPbuffer ||
                              !hasExtension(eglQueryString(handles.display, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context");
    const std::optional<EGLConfig> config = chooseConfig(handles.display, needsPbuffer);
    if (!config) return fail("no EGL config with OpenGL and RGBA8");
    const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                     EGL_CONTEXT_OPENGL_DEBUG, debug ? EGL_TRUE : EGL_FALSE, EGL_NONE};
    handles.context = eglCreateContext(handles.display, *config, EGL_NO_CONTEXT, contextAttribs);
    if (handles.context == EGL_NO_CONTEXT) return fail("no OpenGL 4.5 core context");
    if (needsPbuffer) {
        const EGLint pbufferAttribs[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
        handles.surface = eglCreatePbufferSurface(handles.display, *config, pbufferAttribs);
        if (handles.surface == EGL_NO_SURFACE) return fail("eglCreatePbufferSurface failed");
    }
    if (!eglMakeCurrent(handles.display, handles.surface, handles.surface, handles.context))
        return fail("eglMakeCurrent failed");
    return handles;
}

}  // namespace

struct EglContext::Native : EglHandles {};

std::unique_ptr<EglContext> EglContext::create(const EglContextOptions& options) {
    const bool debug = options.debug || envFlag("SSS_GL_DEBUG");
    DisplaySearch search{eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS), nullptr, {},
                         options.preferSoftware || envFlag("SSS_EGL_SOFTWARE")};
    search.getPlatformDisplay =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    search.devices = enumerateDevices(search.clientExtensions);

    std::vector<std::string> failures;
    for (EglPlatform platform : platformOrder(options.platform, search.devices)) {
        std::string failure;
        const DisplayCandidate candidate = findDisplay(platform, search, failure);
        if (candidate.display == EGL_NO_DISPLAY) {
            failures.push_back(failure);
            continue;
        }
        EGLint major = 0, minor = 0;
        if (!eglInitialize(candidate.display, &major, &minor)) {
            failures.push_back(candidate.description + ": eglInitialize failed (" + eglErrorName(eglGetError()) + ")");
            continue;
        }
        retainDisplay(candidate.display);
        const std::optional<EglHandles> handles = makeCurrentContext(candidate, debug, failures);
        if (!handles) continue;
        std::unique_ptr<EglContext> result(new EglContext());
        result->m_native = std::make_unique<Native>(Native{*handles});
        for (const std::string& f : failures) log(LogLevel::Info, "EglContext: skipped " + f);
        result->initializeGl(eglGetProcAddress, debug, candidate.description);
        return result;
    }

    std::string message = "EglContext: could not create a headless OpenGL 4.5 core context:";
    for (const std::string& f : failures) message += "\n  - " + f;
    message += "\n(on Debian, scripts/install-deps.sh installs Mesa's llvmpipe driver, libgl1-mesa-dri)";
    throw Error(ErrorKind::Gl, message);
}

EglContext::~EglContext() {
    if (!m_native) return;
    if (eglGetCurrentContext() == m_native->context)
        eglMakeCurrent(m_native->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (m_native->surface != EGL_NO_SURFACE) eglDestroySurface(m_native->display, m_native->surface);
    eglDestroyContext(m_native->display, m_native->context);
    releaseDisplay(m_native->display);
}

void EglContext::makeCurrent() {
    if (!eglMakeCurrent(m_native->display, m_native->surface, m_native->surface, m_native->context))
        throw Error(ErrorKind::Gl, "EglContext::makeCurrent failed (" + eglErrorName(eglGetError()) + ")");
}

}  // namespace sss
