#include "sss/frame_accumulator.h"

#include "gl/fullscreen.h"
#include "gl/gl.h"
#include "gl/program.h"
#include "gl/vertex_array.h"
#include "sss/error.h"

#include <string>

namespace sss {
namespace {

double radicalInverse(int index, int base) {
    double result = 0.0, digit = 1.0 / base;
    for (int i = index; i > 0; i /= base, digit /= base) result += (i % base) * digit;
    return result;
}

}  // namespace

struct FrameAccumulator::Impl {
    RenderTarget mean;
    int frames = 0;
    gl::Program program = gl::Program::link({{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                             {GL_FRAGMENT_SHADER, "display/accumulate.frag"}});
    gl::VertexArray emptyVertexArray = gl::VertexArray::create();
    Impl(int width, int height) : mean(width, height) { mean.clear(glm::vec4(0.0f)); }
};

FrameAccumulator::FrameAccumulator(int width, int height) : m_impl(std::make_unique<Impl>(width, height)) {}
FrameAccumulator::~FrameAccumulator() = default;
FrameAccumulator::FrameAccumulator(FrameAccumulator&&) noexcept = default;
FrameAccumulator& FrameAccumulator::operator=(FrameAccumulator&&) noexcept = default;

glm::vec2 FrameAccumulator::subpixelOffset(int index, int width, int height) {
    if (index < 0) throw Error(ErrorKind::InvalidArgument, "FrameAccumulator::subpixelOffset: index must be >= 0, got " + std::to_string(index));
    if (width <= 0 || height <= 0)
        throw Error(ErrorKind::InvalidArgument, "FrameAccumulator::subpixelOffset: width and height must be > 0");
    // Halton point `index` is in [0, 1)^2 with point 0 at the origin; centring it on the pixel
    // (minus 0.5) would put frame 0 at a corner, so the sequence is shifted by its first point.
    const glm::dvec2 point(radicalInverse(index, 2), radicalInverse(index, 3));
    glm::dvec2 pixels = point;  // 0 for index 0
    pixels -= glm::floor(pixels + 0.5);  // wrap into [-0.5, 0.5): the pixel around its centre
    return glm::vec2(pixels * glm::dvec2(2.0 / width, 2.0 / height));
}

void FrameAccumulator::add(const RenderTarget& frame) {
    Impl& r = *m_impl;
    if (frame.width() != r.mean.width() || frame.height() != r.mean.height())
        throw Error(ErrorKind::InvalidArgument, "FrameAccumulator::add: frame is " + std::to_string(frame.width()) + "x" +
                                                    std::to_string(frame.height()) + ", the accumulator " +
                                                    std::to_string(r.mean.width()) + "x" + std::to_string(r.mean.height()));
    if (r.frames == 0)
        glBlitNamedFramebuffer(frame.framebufferId(), r.mean.framebufferId(), 0, 0, frame.width(), frame.height(), 0, 0,
                               frame.width(), frame.height(), GL_DEPTH_BUFFER_BIT, GL_NEAREST);
    // mean_{n+1} = mean_n + (frame - mean_n) / (n + 1): blend with constant alpha 1 / (n + 1).
    r.mean.bindForDrawing();
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendColor(0.0f, 0.0f, 0.0f, 1.0f / static_cast<float>(r.frames + 1));
    glBlendFunc(GL_CONSTANT_ALPHA, GL_ONE_MINUS_CONSTANT_ALPHA);
    r.program.set("frameColor", 0);
    glBindTextureUnit(0, frame.colorTextureId());
    gl::drawFullscreenTriangle(r.program, r.emptyVertexArray);
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    ++r.frames;
}

void FrameAccumulator::reset() {
    m_impl->mean.clear(glm::vec4(0.0f));
    m_impl->frames = 0;
}

int FrameAccumulator::frames() const { return m_impl->frames; }
const RenderTarget& FrameAccumulator::result() const { return m_impl->mean; }

}  // namespace sss
