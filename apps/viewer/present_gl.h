#pragma once
// The handful of OpenGL calls sss-viewer makes itself (presenting the scene and reading the
// window back), loaded through glfwGetProcAddress. libsss keeps its GL loader private and Dear
// ImGui's OpenGL 3 backend loads its own, so the viewer has this tiny loader of its own.

#include <sss/image.h>

#include <cstdint>

namespace viewer {

class PresentGl {
public:
    /// Loads the entry points from the current GLFW context.
    /// @throws sss::Error(Gl) naming the first missing function.
    PresentGl();

    /// Copies the colour of framebuffer `source` (width x height) onto the whole default
    /// framebuffer (fbWidth x fbHeight), after clearing it to black, and leaves the default
    /// framebuffer bound for the UI.
    void present(std::uint32_t source, int width, int height, int fbWidth, int fbHeight) const;
    /// Reads the back buffer of the default framebuffer (what the next swap shows), top row first.
    sss::Image8 readBackBuffer(int width, int height) const;

private:
    using BindFramebuffer = void (*)(unsigned target, unsigned framebuffer);
    using BlitNamedFramebuffer = void (*)(unsigned read, unsigned draw, int srcX0, int srcY0, int srcX1, int srcY1,
                                          int dstX0, int dstY0, int dstX1, int dstY1, unsigned mask, unsigned filter);
    using Viewport = void (*)(int x, int y, int width, int height);
    using ClearColor = void (*)(float r, float g, float b, float a);
    using Clear = void (*)(unsigned mask);
    using ReadBuffer = void (*)(unsigned mode);
    using PixelStorei = void (*)(unsigned name, int value);
    using ReadPixels = void (*)(int x, int y, int width, int height, unsigned format, unsigned type, void* data);

    BindFramebuffer m_bindFramebuffer = nullptr;
    BlitNamedFramebuffer m_blitNamedFramebuffer = nullptr;
    Viewport m_viewport = nullptr;
    ClearColor m_clearColor = nullptr;
    Clear m_clear = nullptr;
    ReadBuffer m_readBuffer = nullptr;
    PixelStorei m_pixelStorei = nullptr;
    ReadPixels m_readPixels = nullptr;
};

}  // namespace viewer
