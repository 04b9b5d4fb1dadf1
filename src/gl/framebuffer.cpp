#include "gl/framebuffer.h"

#include "gl/texture.h"
#include "sss/error.h"

#include <string>
#include <vector>

namespace sss::gl {
namespace {

const char* statusName(GLenum status) {
    switch (status) {
        case GL_FRAMEBUFFER_UNDEFINED: return "GL_FRAMEBUFFER_UNDEFINED";
        case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT: return "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT";
        case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT: return "GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT";
        case GL_FRAMEBUFFER_UNSUPPORTED: return "GL_FRAMEBUFFER_UNSUPPORTED";
        case GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE: return "GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE";
        case GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS: return "GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS";
        default: return "unknown framebuffer status";
    }
}

}  // namespace

Framebuffer Framebuffer::create() {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    return Framebuffer(id);
}

void Framebuffer::attach(GLenum attachment, const Texture& texture, int level) const {
    glNamedFramebufferTexture(id(), attachment, texture.id(), level);
}

void Framebuffer::attachLayer(GLenum attachment, const Texture& texture, int layer, int level) const {
    glNamedFramebufferTextureLayer(id(), attachment, texture.id(), level, layer);
}

void Framebuffer::setDrawBuffers(std::initializer_list<GLenum> buffers) const {
    std::vector<GLenum> list(buffers);
    glNamedFramebufferDrawBuffers(id(), static_cast<GLsizei>(list.size()), list.data());
}

void Framebuffer::checkComplete(std::string_view what) const {
    const GLenum status = glCheckNamedFramebufferStatus(id(), GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw Error(ErrorKind::Gl, std::string(what) + ": framebuffer incomplete (" + statusName(status) + ")");
}

}  // namespace sss::gl
