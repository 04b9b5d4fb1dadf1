#include "sss/render_target.h"

#include "gl/device.h"
#include "gl/framebuffer.h"
#include "gl/program.h"
#include "gl/texture.h"
#include "sss/error.h"

#include <algorithm>
#include <optional>
#include <string>

namespace sss {

struct RenderTarget::Impl {
    int width = 0, height = 0;
    gl::Texture color, depth;
    gl::Framebuffer framebuffer;
    // Hardware GPUs clear colour with a compute dispatch, made on the first clear.
    std::optional<bool> computeClear;
    gl::Program clearProgram;
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
    // Measured side by side (sss-bench --table clear, 1200 x 680): on an H200 a framebuffer or
    // texture clear of the colour took 0.30 ms, a compute dispatch and a texture clear of the
    // depth 0.07 ms; on llvmpipe texture clears took 4.3 ms, framebuffer clears 7.0 ms and the
    // dispatch 13 ms.
    Impl& r = *m_impl;
    if (!r.computeClear) r.computeClear = !gl::currentDeviceIsSoftware();
    if (*r.computeClear) {
        if (!r.clearProgram) r.clearProgram = gl::Program::link({{GL_COMPUTE_SHADER, "frame/clear_color.comp"}});
        r.clearProgram.set("target", 0);
        r.clearProgram.set("color", color);
        r.color.bindImage(0, GL_WRITE_ONLY);
        r.clearProgram.use();
        const glm::ivec3 group = r.clearProgram.workGroupSize();
        glDispatchCompute(static_cast<GLuint>((r.width + group.x - 1) / group.x),
                          static_cast<GLuint>((r.height + group.y - 1) / group.y), 1);
        // Draws, dispatches, copies and read-backs that follow see the cleared colour.
        glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
                        GL_TEXTURE_UPDATE_BARRIER_BIT);
        glUseProgram(0);
        glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    } else {
        glClearTexImage(r.color.id(), 0, GL_RGBA, GL_FLOAT, &color[0]);
    }
    const float one = 1.0f;
    glClearTexImage(r.depth.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, &one);
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
