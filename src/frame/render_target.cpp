#include "sss/render_target.h"

#include "gl/framebuffer.h"
#include "gl/texture.h"
#include "sss/error.h"

#include <algorithm>
#include <string>

namespace sss {

struct RenderTarget::Impl {
    int width = 0, height = 0;
    gl::Texture color, depth;
    gl::Framebuffer framebuffer;
};

RenderTarget::RenderTarget(int width, int height) : m_impl(std::make_unique<Impl>()) {
    if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
        throw Error(ErrorKind::InvalidArgument, "RenderTarget: size must be in 1..16384 on each side, got " +
                                                    std::to_string(width) + "x" + std::to_string(height));
    m_impl->width = width;
    m_impl->height = height;
    m_impl->color = gl::Texture::create2D(GL_RGBA32F, width, height, "RenderTarget colour");
    m_impl->color.setFilter(GL_NEAREST, GL_NEAREST);
    m_impl->depth = gl::Texture::create2D(GL_DEPTH_COMPONENT32F, width, height, "RenderTarget depth");
    m_impl->depth.setFilter(GL_NEAREST, GL_NEAREST);
    m_impl->framebuffer = gl::Framebuffer::create();
    m_impl->framebuffer.attach(GL_COLOR_ATTACHMENT0, m_impl->color);
    m_impl->framebuffer.attach(GL_DEPTH_ATTACHMENT, m_impl->depth);
    m_impl->framebuffer.checkComplete("RenderTarget");
}

RenderTarget::~RenderTarget() = default;
RenderTarget::RenderTarget(RenderTarget&&) noexcept = default;
RenderTarget& RenderTarget::operator=(RenderTarget&&) noexcept = default;

int RenderTarget::width() const { return m_impl->width; }
int RenderTarget::height() const { return m_impl->height; }

void RenderTarget::clear(glm::vec4 color) {
    glClearNamedFramebufferfv(m_impl->framebuffer.id(), GL_COLOR, 0, &color[0]);
    const float one = 1.0f;
    glClearNamedFramebufferfv(m_impl->framebuffer.id(), GL_DEPTH, 0, &one);
}

Image RenderTarget::readColor() const {
    Image image(m_impl->width, m_impl->height);
    glGetTextureImage(m_impl->color.id(), 0, GL_RGBA, GL_FLOAT,
                      static_cast<GLsizei>(image.data().size() * sizeof(float)), image.data().data());
    return image.flippedVertically();  // GL rows start at the bottom
}

std::vector<float> RenderTarget::readDepth() const {
    const size_t w = static_cast<size_t>(m_impl->width), h = static_cast<size_t>(m_impl->height);
    std::vector<float> bottomUp(w * h), topDown(w * h);
    glGetTextureImage(m_impl->depth.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                      static_cast<GLsizei>(bottomUp.size() * sizeof(float)), bottomUp.data());
    for (size_t y = 0; y < h; ++y)
        std::copy_n(bottomUp.begin() + static_cast<std::ptrdiff_t>((h - 1 - y) * w), w,
                    topDown.begin() + static_cast<std::ptrdiff_t>(y * w));
    return topDown;
}

std::uint32_t RenderTarget::framebufferId() const { return m_impl->framebuffer.id(); }
std::uint32_t RenderTarget::colorTextureId() const { return m_impl->color.id(); }
std::uint32_t RenderTarget::depthTextureId() const { return m_impl->depth.id(); }

void RenderTarget::bindForDrawing() const {
    m_impl->framebuffer.bind();
    glViewport(0, 0, m_impl->width, m_impl->height);
}

}  // namespace sss
