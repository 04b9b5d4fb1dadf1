#include "gl/texture.h"

namespace sss::gl {

Texture Texture::create2D(GLenum internalFormat, int width, int height, int levels) {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &id);
    glTextureStorage2D(id, levels, internalFormat, width, height);
    Texture t(id, GL_TEXTURE_2D, internalFormat, {width, height, 1});
    t.setFilter(GL_LINEAR, GL_LINEAR);
    t.setWrap(GL_CLAMP_TO_EDGE);
    return t;
}

Texture Texture::create2DArray(GLenum internalFormat, int width, int height, int layers) {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &id);
    glTextureStorage3D(id, 1, internalFormat, width, height, layers);
    Texture t(id, GL_TEXTURE_2D_ARRAY, internalFormat, {width, height, layers});
    t.setFilter(GL_LINEAR, GL_LINEAR);
    t.setWrap(GL_CLAMP_TO_EDGE);
    return t;
}

Texture Texture::create3D(GLenum internalFormat, glm::ivec3 size) {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_3D, 1, &id);
    glTextureStorage3D(id, 1, internalFormat, size.x, size.y, size.z);
    Texture t(id, GL_TEXTURE_3D, internalFormat, size);
    t.setFilter(GL_LINEAR, GL_LINEAR);
    t.setWrap(GL_CLAMP_TO_EDGE);
    return t;
}

void Texture::upload(GLenum format, GLenum type, const void* pixels) const {
    // Rows of 8-bit single-channel data are not 4-byte aligned in general.
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    if (m_target == GL_TEXTURE_2D)
        glTextureSubImage2D(id(), 0, 0, 0, m_size.x, m_size.y, format, type, pixels);
    else
        glTextureSubImage3D(id(), 0, 0, 0, 0, m_size.x, m_size.y, m_size.z, format, type, pixels);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
}

void Texture::setFilter(GLenum minFilter, GLenum magFilter) const {
    glTextureParameteri(id(), GL_TEXTURE_MIN_FILTER, static_cast<GLint>(minFilter));
    glTextureParameteri(id(), GL_TEXTURE_MAG_FILTER, static_cast<GLint>(magFilter));
}

void Texture::setWrap(GLenum wrap) const {
    glTextureParameteri(id(), GL_TEXTURE_WRAP_S, static_cast<GLint>(wrap));
    glTextureParameteri(id(), GL_TEXTURE_WRAP_T, static_cast<GLint>(wrap));
    if (m_target != GL_TEXTURE_2D) glTextureParameteri(id(), GL_TEXTURE_WRAP_R, static_cast<GLint>(wrap));
}

void Texture::setBorderColor(glm::vec4 color) const {
    glTextureParameterfv(id(), GL_TEXTURE_BORDER_COLOR, &color[0]);
}

}  // namespace sss::gl
