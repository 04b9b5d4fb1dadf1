// HostContext: the application's current context, adopted (sss/context.h).
#include "sss/context.h"

#include "gl/gl.h"
#include "sss/error.h"

#include <utility>

namespace sss {

std::unique_ptr<HostContext> HostContext::adopt(const HostContextOptions& options) {
    if (!options.getProcAddress)
        throw Error(ErrorKind::InvalidArgument, "HostContextOptions::getProcAddress is required (e.g. glfwGetProcAddress)");
    // Without a current context, the loader finds entry points that fail or crash when called;
    // glGetString through the loader answers null instead.
    const auto getString = reinterpret_cast<const GLubyte* (*)(GLenum)>(options.getProcAddress("glGetString"));
    if (!getString || !getString(GL_VERSION))
        throw Error(ErrorKind::Gl, "HostContext::adopt: no OpenGL context is current on this thread (" +
                                       options.name + "): make the host's context current first");
    std::unique_ptr<HostContext> context(new HostContext());
    context->m_makeCurrent = options.makeCurrent;
    context->initializeGl(options.getProcAddress, options.debug, options.name);
    context->m_ownsDebugCallback = context->info().debug;
    return context;
}

HostContext::~HostContext() {
    // The callback's user pointer dies with this object; the host's context lives on.
    if (m_ownsDebugCallback) glDebugMessageCallback(nullptr, nullptr);
}

void HostContext::makeCurrent() {
    if (m_makeCurrent) m_makeCurrent();
}

}  // namespace sss
