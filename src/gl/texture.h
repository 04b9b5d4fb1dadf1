#pragma once
#include "gl/object.h"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace sss::gl {

struct TextureTraits {
    static constexpr GLenum labelNamespace = GL_TEXTURE;
    static void destroy(GLuint id) { glDeleteTextures(1, &id); }
};

/// Immutable-storage texture: 2D, 2D array or 3D (glTextureStorage*). Sampling state defaults to
/// linear filtering and clamp-to-edge.
class Texture : public Object<TextureTraits> {
public:
    Texture() = default;
    static Texture create2D(GLenum internalFormat, int width, int height, int levels = 1);
    static Texture create2DArray(GLenum internalFormat, int width, int height, int layers);
    static Texture create3D(GLenum internalFormat, glm::ivec3 size);

    /// Uploads a whole 2D image, 3D volume, or (for arrays) all layers.
    void upload(GLenum format, GLenum type, const void* pixels) const;
    void setFilter(GLenum minFilter, GLenum magFilter) const;
    void setWrap(GLenum wrap) const;
    /// Colour returned outside the texture with GL_CLAMP_TO_BORDER.
    void setBorderColor(glm::vec4 color) const;
    void bind(GLuint unit) const { glBindTextureUnit(unit, id()); }
    /// Binds level 0 (all layers) as image `unit` for imageLoad/imageStore.
    void bindImage(GLuint unit, GLenum access) const {
        glBindImageTexture(unit, id(), 0, GL_TRUE, 0, access, m_format);
    }

    GLenum target() const { return m_target; }
    GLenum internalFormat() const { return m_format; }
    glm::ivec3 size() const { return m_size; }  ///< width, height, depth or layers (1 for 2D)

private:
    Texture(GLuint id, GLenum target, GLenum format, glm::ivec3 size)
        : Object(id), m_target(target), m_format(format), m_size(size) {}
    GLenum m_target = 0;
    GLenum m_format = 0;
    glm::ivec3 m_size{0};
};

}  // namespace sss::gl
