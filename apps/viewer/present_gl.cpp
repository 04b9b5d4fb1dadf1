#include "present_gl.h"

#include <sss/error.h>

#include <GLFW/glfw3.h>

#include <string>

namespace viewer {
namespace {

// The few GL enums used here (values from the OpenGL 4.5 core specification).
constexpr unsigned kFramebuffer = 0x8D40;
constexpr unsigned kReadFramebuffer = 0x8CA8;
constexpr unsigned kColorBufferBit = 0x4000;
constexpr unsigned kNearest = 0x2600;
constexpr unsigned kBack = 0x0405;
constexpr unsigned kPackAlignment = 0x0D05;
constexpr unsigned kRgba = 0x1908;
constexpr unsigned kUnsignedByte = 0x1401;

template <typename Fn>
void load(Fn& fn, const char* name) {
    GLFWglproc proc = glfwGetProcAddress(name);
    if (!proc) throw sss::Error(sss::ErrorKind::Gl, std::string("sss-viewer: the GL context lacks ") + name);
    fn = reinterpret_cast<Fn>(proc);
}

}  // namespace

PresentGl::PresentGl() {
    load(m_bindFramebuffer, "glBindFramebuffer");
    load(m_blitNamedFramebuffer, "glBlitNamedFramebuffer");
    load(m_viewport, "glViewport");
    load(m_clearColor, "glClearColor");
    load(m_clear, "glClear");
    load(m_readBuffer, "glReadBuffer");
    load(m_pixelStorei, "glPixelStorei");
    load(m_readPixels, "glReadPixels");
}

void PresentGl::present(std::uint32_t source, int width, int height, int fbWidth, int fbHeight) const {
    m_bindFramebuffer(kFramebuffer, 0);
    m_viewport(0, 0, fbWidth, fbHeight);
    m_clearColor(0.0f, 0.0f, 0.0f, 1.0f);
    m_clear(kColorBufferBit);
    m_blitNamedFramebuffer(source, 0, 0, 0, width, height, 0, 0, width, height, kColorBufferBit, kNearest);
}

sss::Image8 PresentGl::readBackBuffer(int width, int height) const {
    sss::Image8 image(width, height);
    m_bindFramebuffer(kReadFramebuffer, 0);
    m_readBuffer(kBack);
    m_pixelStorei(kPackAlignment, 1);
    m_readPixels(0, 0, width, height, kRgba, kUnsignedByte, image.data().data());
    m_pixelStorei(kPackAlignment, 4);  // the GL default, which other code may assume
    // GL returns the bottom row first; the window has no meaningful alpha.
    sss::Image8 flipped = image.flippedVertically();
    for (std::size_t i = 3; i < flipped.data().size(); i += 4) flipped.data()[i] = 255;
    return flipped;
}

}  // namespace viewer
