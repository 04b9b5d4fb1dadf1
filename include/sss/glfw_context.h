#pragma once
/// @file
/// Windowed OpenGL 4.5 core context through GLFW (optional: built with SSS_WITH_GLFW=ON).
/// Needs a display (X11, or Xvfb on headless machines); use EglContext for headless rendering.

#include "sss/api.h"
#include "sss/context.h"

#include <glm/vec2.hpp>

#include <memory>
#include <string>

SSS_BEGIN_API

namespace sss {

struct GlfwContextOptions {
    int width = 1280;               ///< window width in screen coordinates (default: 1280)
    int height = 720;               ///< window height (default: 720)
    std::string title = "libsss";   ///< window title
    bool debug = false;             ///< debug context + KHR_debug to the log (also SSS_GL_DEBUG=1)
    bool visible = true;            ///< show the window (default: on)
    bool vsync = true;              ///< swap interval 1 (default: on)
};

class GlfwContext final : public GlContext {
public:
    /// Throws Error(Gl) with GLFW's reason (e.g. no display) when the window or context fails.
    static std::unique_ptr<GlfwContext> create(const GlfwContextOptions& options = {});
    ~GlfwContext() override;
    void makeCurrent() override;
    void swapBuffers() override;

    /// The GLFWwindow*, for applications that install their own input callbacks or UI.
    void* nativeWindow() const;
    bool shouldClose() const;
    void pollEvents() const;
    /// Size of the default framebuffer in pixels (differs from the window size on HiDPI).
    glm::ivec2 framebufferSize() const;

private:
    GlfwContext() = default;
    struct Native;
    std::unique_ptr<Native> m_native;
};

}  // namespace sss

SSS_END_API
