#include "sss/glfw_context.h"

#include "sss/error.h"

#include <GLFW/glfw3.h>

#include <cstdlib>
#include <mutex>
#include <string>

namespace sss {
namespace {

// GLFW is process-global: initialise with the first window, terminate after the last.
std::mutex g_glfwMutex;
int g_windows = 0;
std::string g_lastGlfwError;

void onGlfwError(int code, const char* description) {
    g_lastGlfwError = "GLFW error " + std::to_string(code) + ": " + (description ? description : "");
}

}  // namespace

struct GlfwContext::Native {
    GLFWwindow* window = nullptr;
};

std::unique_ptr<GlfwContext> GlfwContext::create(const GlfwContextOptions& options) {
    if (options.width <= 0 || options.height <= 0)
        throw Error(ErrorKind::InvalidArgument, "GlfwContextOptions: width and height must be > 0");
    std::lock_guard lock(g_glfwMutex);
    glfwSetErrorCallback(onGlfwError);
    if (g_windows == 0 && !glfwInit())
        throw Error(ErrorKind::Gl, "GlfwContext: glfwInit failed (" + g_lastGlfwError +
                                       "); a window needs a display: run under X11 or xvfb-run");
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    const char* env = std::getenv("SSS_GL_DEBUG");
    const bool debug = options.debug || (env && *env && std::string(env) != "0");
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, debug ? GLFW_TRUE : GLFW_FALSE);
    glfwWindowHint(GLFW_VISIBLE, options.visible ? GLFW_TRUE : GLFW_FALSE);
    GLFWwindow* window = glfwCreateWindow(options.width, options.height, options.title.c_str(), nullptr, nullptr);
    if (!window) {
        if (g_windows == 0) glfwTerminate();
        throw Error(ErrorKind::Gl, "GlfwContext: cannot create a window with an OpenGL 4.5 core context (" +
                                       g_lastGlfwError + ")");
    }
    ++g_windows;
    std::unique_ptr<GlfwContext> context(new GlfwContext());
    context->m_native = std::make_unique<Native>();
    context->m_native->window = window;
    glfwMakeContextCurrent(window);
    glfwSwapInterval(options.vsync ? 1 : 0);
    context->initializeGl(glfwGetProcAddress, debug,
                          "GLFW window (" + std::string(glfwGetVersionString()) + ")");
    return context;
}

GlfwContext::~GlfwContext() {
    if (!m_native) return;
    std::lock_guard lock(g_glfwMutex);
    glfwDestroyWindow(m_native->window);
    if (--g_windows == 0) glfwTerminate();
}

void GlfwContext::makeCurrent() { glfwMakeContextCurrent(m_native->window); }
void GlfwContext::swapBuffers() { glfwSwapBuffers(m_native->window); }
void* GlfwContext::nativeWindow() const { return m_native->window; }
bool GlfwContext::shouldClose() const { return glfwWindowShouldClose(m_native->window); }
void GlfwContext::pollEvents() const { glfwPollEvents(); }

glm::ivec2 GlfwContext::framebufferSize() const {
    glm::ivec2 size;
    glfwGetFramebufferSize(m_native->window, &size.x, &size.y);
    return size;
}

}  // namespace sss
