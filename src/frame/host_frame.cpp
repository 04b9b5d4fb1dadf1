// HostTarget (sss/host_frame.h): the host's depth into the libsss target, and the target's
// colour and depth back into the host's framebuffer.
#include "sss/host_frame.h"

#include "frame/display_uniforms.h"
#include "gl/framebuffer.h"
#include "gl/fullscreen.h"
#include "gl/gl.h"
#include "gl/program.h"
#include "gl/texture.h"
#include "gl/vertex_array.h"
#include "sss/error.h"

#include <optional>
#include <string>

namespace sss {
namespace {

// The internal format of the host framebuffer's depth buffer, or nullopt when it has none. The
// blit that copies it needs a destination of exactly that format.
std::optional<GLenum> depthFormatOf(GLuint framebuffer) {
    const GLenum depth = framebuffer == 0 ? GL_DEPTH : GL_DEPTH_ATTACHMENT;
    const GLenum stencil = framebuffer == 0 ? GL_STENCIL : GL_STENCIL_ATTACHMENT;
    GLint type = GL_NONE;
    glGetNamedFramebufferAttachmentParameteriv(framebuffer, depth, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
    if (type == GL_NONE) return std::nullopt;
    GLint bits = 0, stencilBits = 0, component = GL_NONE, stencilType = GL_NONE;
    glGetNamedFramebufferAttachmentParameteriv(framebuffer, depth, GL_FRAMEBUFFER_ATTACHMENT_DEPTH_SIZE, &bits);
    glGetNamedFramebufferAttachmentParameteriv(framebuffer, depth, GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE, &component);
    glGetNamedFramebufferAttachmentParameteriv(framebuffer, stencil, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &stencilType);
    if (stencilType != GL_NONE)
        glGetNamedFramebufferAttachmentParameteriv(framebuffer, stencil, GL_FRAMEBUFFER_ATTACHMENT_STENCIL_SIZE,
                                                   &stencilBits);
    if (bits == 0) return std::nullopt;
    const bool withStencil = stencilBits > 0;
    if (component == GL_FLOAT) return withStencil ? GL_DEPTH32F_STENCIL8 : GL_DEPTH_COMPONENT32F;
    if (bits >= 32) return GL_DEPTH_COMPONENT32;
    if (bits >= 24) return withStencil ? GL_DEPTH24_STENCIL8 : GL_DEPTH_COMPONENT24;
    return GL_DEPTH_COMPONENT16;
}

void checkFramebuffer(const HostFramebuffer& f) {
    const std::string size = std::to_string(f.width) + "x" + std::to_string(f.height);
    if (f.width < 1 || f.height < 1 || f.width > 16384 || f.height > 16384)
        throw Error(ErrorKind::InvalidArgument, "HostFramebuffer: width and height must be in [1, 16384], got " + size);
    if (f.framebuffer != 0 && !glIsFramebuffer(f.framebuffer))
        throw Error(ErrorKind::InvalidArgument, "HostFramebuffer::framebuffer: " + std::to_string(f.framebuffer) +
                                                    " is not a framebuffer of the current context");
    if (glCheckNamedFramebufferStatus(f.framebuffer, GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw Error(ErrorKind::InvalidArgument,
                    "HostFramebuffer::framebuffer: " + std::to_string(f.framebuffer) + " is not complete");
    if (!f.linear) validate(f.display);
}

}  // namespace

struct HostTarget::Impl {
    std::optional<RenderTarget> target;
    gl::Program depthIn = gl::Program::link({{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                             {GL_FRAGMENT_SHADER, "host/depth_in.frag"}});
    gl::Program present = gl::Program::link({{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                             {GL_FRAGMENT_SHADER, "host/present.frag"}});
    gl::VertexArray emptyVertexArray = gl::VertexArray::create();
    // The host's depth, blitted into a texture of its own format so that it can be sampled.
    gl::Texture hostDepth;
    gl::Framebuffer hostDepthFramebuffer;
    GLenum hostDepthFormat = GL_NONE;

    void resize(int width, int height) {
        if (!target || target->width() != width || target->height() != height) target.emplace(width, height);
    }
    void copyDepthIn(const HostFramebuffer& f);
    void presentInto(const HostFramebuffer& f) const;
};

void HostTarget::Impl::copyDepthIn(const HostFramebuffer& f) {
    const std::optional<GLenum> format = depthFormatOf(f.framebuffer);
    if (!format) return;  // no depth buffer: nothing of the host's hides libsss
    const glm::ivec3 size(f.width, f.height, 1);
    if (!hostDepth || hostDepth.size() != size || hostDepthFormat != *format) {
        hostDepth = gl::Texture::create2D(*format, f.width, f.height, "host depth");
        hostDepth.setFilter(GL_NEAREST, GL_NEAREST);
        hostDepthFramebuffer = gl::Framebuffer::create();
        const bool stencil = *format == GL_DEPTH24_STENCIL8 || *format == GL_DEPTH32F_STENCIL8;
        hostDepthFramebuffer.attach(stencil ? GL_DEPTH_STENCIL_ATTACHMENT : GL_DEPTH_ATTACHMENT, hostDepth);
        hostDepthFramebuffer.checkComplete("HostTarget host depth");
        hostDepthFormat = *format;
    }
    glBlitNamedFramebuffer(f.framebuffer, hostDepthFramebuffer.id(), f.x, f.y, f.x + f.width, f.y + f.height, 0, 0,
                           f.width, f.height, GL_DEPTH_BUFFER_BIT, GL_NEAREST);
    target->bindForDrawing();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_ALWAYS);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    depthIn.set("hostDepth", 0);
    hostDepth.bind(0);
    gl::drawFullscreenTriangle(depthIn, emptyVertexArray);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthFunc(GL_LESS);
    glDisable(GL_DEPTH_TEST);
}

void HostTarget::Impl::presentInto(const HostFramebuffer& f) const {
    glBindFramebuffer(GL_FRAMEBUFFER, f.framebuffer);
    glViewport(f.x, f.y, f.width, f.height);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_ALWAYS);
    glDepthMask(f.depth ? GL_TRUE : GL_FALSE);
    present.set("linearColor", 0);
    present.set("depth", 1);
    present.set("origin", glm::ivec2(f.x, f.y));
    present.set("encode", f.linear ? 0 : 1);
    detail::setDisplayUniforms(present, f.display);
    glBindTextureUnit(0, target->colorTextureId());
    glBindTextureUnit(1, target->depthTextureId());
    gl::drawFullscreenTriangle(present, emptyVertexArray);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
}

HostTarget::HostTarget() : m_impl(std::make_unique<Impl>()) {}
HostTarget::~HostTarget() = default;
HostTarget::HostTarget(HostTarget&&) noexcept = default;
HostTarget& HostTarget::operator=(HostTarget&&) noexcept = default;

HostTarget::Frame HostTarget::begin(const HostFramebuffer& framebuffer) { return Frame(*this, framebuffer); }

struct HostTarget::Frame::State {
    GlStateGuard guard;  // first: saved before anything below changes the state
    HostTarget::Impl& owner;
    HostFramebuffer framebuffer;
    bool presented = false;
};

HostTarget::Frame::Frame(HostTarget& owner, const HostFramebuffer& framebuffer) {
    checkFramebuffer(framebuffer);
    m_state.reset(new State{{}, *owner.m_impl, framebuffer});
    Impl& impl = m_state->owner;
    impl.resize(framebuffer.width, framebuffer.height);
    impl.target->clear({0.0f, 0.0f, 0.0f, 0.0f});
    if (framebuffer.depth) impl.copyDepthIn(framebuffer);
}

HostTarget::Frame::~Frame() = default;
HostTarget::Frame::Frame(Frame&&) noexcept = default;

RenderTarget& HostTarget::Frame::target() { return *m_state->owner.target; }

void HostTarget::Frame::present() {
    if (m_state->presented)
        throw Error(ErrorKind::InvalidArgument, "HostTarget::Frame::present: the frame was presented already");
    m_state->owner.presentInto(m_state->framebuffer);
    m_state->presented = true;
}

}  // namespace sss
