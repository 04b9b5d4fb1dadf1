#include "sss/display.h"

#include "frame/display_uniforms.h"

#include "util/format.h"
#include "gl/fullscreen.h"
#include "gl/framebuffer.h"
#include "gl/program.h"
#include "gl/texture.h"
#include "gl/vertex_array.h"
#include "sss/error.h"
#include "sss/render_target.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace sss {
namespace display {
// The shared text (see its header comment), compiled as C++.
#define SSS_CPP 1
using real = double;
using std::max;
using std::min;
using std::pow;
#include "../../shaders/common/display_transform.glsl"
#undef SSS_CPP
}  // namespace display

namespace {

int toneMapCode(ToneMap t) { return t == ToneMap::Filmic ? 1 : 0; }

}  // namespace

void validate(const DisplayTransform& t) {
    if (!(std::abs(t.exposure) <= 64.0f))
        throw Error(ErrorKind::InvalidArgument,
                    "DisplayTransform::exposure must be finite and within [-64, 64] stops, got " + detail::formatNumber(t.exposure));
    if (t.toneMap != ToneMap::None && t.toneMap != ToneMap::Filmic)
        throw Error(ErrorKind::InvalidArgument, "DisplayTransform::toneMap is not a ToneMap value");
}

glm::vec3 applyDisplayTransform(glm::vec3 linear, const DisplayTransform& t) {
    const float scale = std::exp2(t.exposure);
    const int toneMap = toneMapCode(t.toneMap), srgb = t.srgb ? 1 : 0;
    auto channel = [&](float v) { return static_cast<float>(display::displayChannel(v, scale, toneMap, srgb)); };
    return {channel(linear.x), channel(linear.y), channel(linear.z)};
}

Image8 toDisplay(const Image& linear, const DisplayTransform& t) {
    validate(t);
    Image8 out(linear.width(), linear.height());
    const std::vector<float>& in = linear.data();
    std::vector<uint8_t>& bytes = out.data();
    auto byte = [](float v) {
        if (!(v > 0.0f)) return uint8_t(0);  // also NaN
        return static_cast<uint8_t>(std::lround(std::min(v, 1.0f) * 255.0f));
    };
    for (std::size_t i = 0; i < in.size(); i += 4) {
        const glm::vec3 d = applyDisplayTransform(glm::vec3(in[i], in[i + 1], in[i + 2]), t);
        bytes[i] = byte(d.x);
        bytes[i + 1] = byte(d.y);
        bytes[i + 2] = byte(d.z);
        bytes[i + 3] = byte(in[i + 3]);
    }
    return out;
}

ToneMap parseToneMap(std::string_view name) {
    if (name == "none") return ToneMap::None;
    if (name == "filmic") return ToneMap::Filmic;
    throw Error(ErrorKind::InvalidArgument, "unknown tone mapping \"" + std::string(name) + "\" (none, filmic)");
}

const char* toneMapName(ToneMap toneMap) { return toneMap == ToneMap::Filmic ? "filmic" : "none"; }

struct DisplayEncoder::Impl {
    gl::Program program = gl::Program::link({{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                             {GL_FRAGMENT_SHADER, "display/encode.frag"}});
    gl::VertexArray emptyVertexArray = gl::VertexArray::create();
    gl::Texture color;
    gl::Framebuffer framebuffer;
};

DisplayEncoder::DisplayEncoder() : m_impl(std::make_unique<Impl>()) {}
DisplayEncoder::~DisplayEncoder() = default;
DisplayEncoder::DisplayEncoder(DisplayEncoder&&) noexcept = default;
DisplayEncoder& DisplayEncoder::operator=(DisplayEncoder&&) noexcept = default;

void DisplayEncoder::encode(const RenderTarget& linear, const DisplayTransform& t) {
    validate(t);
    Impl& r = *m_impl;
    const glm::ivec3 size(linear.width(), linear.height(), 1);
    if (!r.color || r.color.size() != size) {
        r.color = gl::Texture::create2D(GL_RGBA8, size.x, size.y, "display colour");
        r.framebuffer = gl::Framebuffer::create();
        r.framebuffer.attach(GL_COLOR_ATTACHMENT0, r.color);
        r.framebuffer.checkComplete("DisplayEncoder");
    }
    const gl::Program& p = r.program;
    p.set("linearColor", 0);
    detail::setDisplayUniforms(p, t);
    glBindTextureUnit(0, linear.colorTextureId());
    r.framebuffer.bind();
    glViewport(0, 0, size.x, size.y);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    gl::drawFullscreenTriangle(p, r.emptyVertexArray);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void detail::setDisplayUniforms(const gl::Program& program, const DisplayTransform& t) {
    program.set("exposureScale", std::exp2(t.exposure));
    program.set("toneMap", toneMapCode(t.toneMap));
    program.set("srgb", t.srgb ? 1 : 0);
}

std::uint32_t DisplayEncoder::framebufferId() const { return m_impl->framebuffer.id(); }

Image8 DisplayEncoder::read() const {
    const Impl& r = *m_impl;
    if (!r.color) throw Error(ErrorKind::InvalidArgument, "DisplayEncoder::read: nothing encoded yet");
    Image8 image(r.color.size().x, r.color.size().y);
    glGetTextureImage(r.color.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(image.data().size()),
                      image.data().data());
    return image.flippedVertically();
}

}  // namespace sss
