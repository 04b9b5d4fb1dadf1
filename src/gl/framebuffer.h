#pragma once
#include "gl/object.h"

#include <string_view>

namespace sss::gl {

class Texture;

struct FramebufferTraits {
    static constexpr GLenum labelNamespace = GL_FRAMEBUFFER;
    static void destroy(GLuint id) { glDeleteFramebuffers(1, &id); }
};

class Framebuffer : public Object<FramebufferTraits> {
public:
    Framebuffer() = default;
    static Framebuffer create();
    /// Attaches a whole texture (all layers: a layered attachment for arrays and 3D).
    void attach(GLenum attachment, const Texture& texture, int level = 0) const;
    /// Attaches one layer of an array or 3D texture.
    void attachLayer(GLenum attachment, const Texture& texture, int layer, int level = 0) const;
    void setDrawBuffers(std::initializer_list<GLenum> buffers) const;
    /// Throws Error(Gl) naming `what` and the status when the framebuffer is incomplete.
    void checkComplete(std::string_view what) const;
    void bind() const { glBindFramebuffer(GL_FRAMEBUFFER, id()); }

private:
    explicit Framebuffer(GLuint id) : Object(id) {}
};

}  // namespace sss::gl
