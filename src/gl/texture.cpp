#include "gl/texture.h"

#include "sss/error.h"
#include "sss/gpu_memory.h"

#include <algorithm>
#include <string>
#include <utility>

namespace sss::gl {

std::uint64_t bytesPerTexel(GLenum internalFormat) {
    switch (internalFormat) {
        case GL_R8: return 1;
        case GL_R16: case GL_R16F: case GL_R16UI: return 2;
        case GL_DEPTH_COMPONENT16: return 2;
        case GL_DEPTH_COMPONENT24: return 3;
        case GL_RGBA8: case GL_R32F: case GL_R32UI: case GL_RG16F: case GL_DEPTH_COMPONENT32F: case GL_DEPTH24_STENCIL8:
        case GL_DEPTH_COMPONENT32: return 4;
        case GL_DEPTH32F_STENCIL8: return 8;
        case GL_RGBA16: case GL_RGBA16F: case GL_RGBA16_SNORM: case GL_RG32F: return 8;
        case GL_RGBA32F: return 16;
        default: throw Error(ErrorKind::InvalidArgument, "gl::Texture: internal format " + std::to_string(internalFormat) +
                                                             " has no known size (add it to bytesPerTexel)");
    }
}

const char* formatName(GLenum internalFormat) {
    switch (internalFormat) {
        case GL_R8: return "R8";
        case GL_R16: return "R16";
        case GL_R16F: return "R16F";
        case GL_R16UI: return "R16UI";
        case GL_RGBA8: return "RGBA8";
        case GL_R32F: return "R32F";
        case GL_R32UI: return "R32UI";
        case GL_RG16F: return "RG16F";
        case GL_DEPTH_COMPONENT32F: return "DEPTH32F";
        case GL_DEPTH24_STENCIL8: return "DEPTH24_STENCIL8";
        case GL_DEPTH_COMPONENT16: return "DEPTH16";
        case GL_DEPTH_COMPONENT24: return "DEPTH24";
        case GL_DEPTH_COMPONENT32: return "DEPTH32";
        case GL_DEPTH32F_STENCIL8: return "DEPTH32F_STENCIL8";
        case GL_RGBA16F: return "RGBA16F";
        case GL_RGBA16: return "RGBA16";
        case GL_RGBA16_SNORM: return "RGBA16_SNORM";
        case GL_RG32F: return "RG32F";
        case GL_RGBA32F: return "RGBA32F";
        default: return "texture";
    }
}

Texture Texture::create(GLenum target, GLenum internalFormat, glm::ivec3 size, int levels, std::string_view label) {
    const char* kind = target == GL_TEXTURE_3D ? "3D" : target == GL_TEXTURE_2D_ARRAY ? "2D array" : "2D";
    std::string description = std::to_string(size.x) + "x" + std::to_string(size.y);
    if (target != GL_TEXTURE_2D) description += "x" + std::to_string(size.z);
    description += std::string(" ") + formatName(internalFormat) + " " + kind + " texture";
    const std::string subject = std::string(label) + ": " + description;
    if (size.x < 1 || size.y < 1 || size.z < 1 || levels < 1)
        throw Error(ErrorKind::InvalidArgument, subject + ": every side and the level count must be >= 1");

    const GpuLimits limits = queryGpuLimits();
    auto requireAtMost = [&](int value, int limit, const char* name, const char* what) {
        if (value > limit)
            throw Error(ErrorKind::GpuLimit, subject + ": " + what + " " + std::to_string(value) + " exceeds " + name +
                                                 " (" + std::to_string(limit) + " on this GPU)");
    };
    if (target == GL_TEXTURE_3D) {
        const int side = std::max({size.x, size.y, size.z});
        requireAtMost(side, limits.max3DTextureSize, "GL_MAX_3D_TEXTURE_SIZE", "side");
    } else {
        requireAtMost(std::max(size.x, size.y), limits.maxTextureSize, "GL_MAX_TEXTURE_SIZE", "side");
        if (target == GL_TEXTURE_2D_ARRAY)
            requireAtMost(size.z, limits.maxArrayTextureLayers, "GL_MAX_ARRAY_TEXTURE_LAYERS", "layer count");
    }

    std::uint64_t bytes = 0;
    for (int level = 0; level < levels; ++level) {
        const auto side = [&](int s) { return static_cast<std::uint64_t>(std::max(1, s >> level)); };
        const std::uint64_t depth = target == GL_TEXTURE_3D ? side(size.z) : static_cast<std::uint64_t>(size.z);
        bytes += side(size.x) * side(size.y) * depth * bytesPerTexel(internalFormat);
    }

    GLuint id = 0;
    glCreateTextures(target, 1, &id);
    Object<TextureTraits> owner(id);  // deletes the name if the allocation throws
    MemoryReservation memory = allocateChecked(label, description, bytes, [&] {
        if (target == GL_TEXTURE_2D)
            glTextureStorage2D(id, levels, internalFormat, size.x, size.y);
        else
            glTextureStorage3D(id, levels, internalFormat, size.x, size.y, size.z);
    });
    Texture t(owner.release(), target, internalFormat, size, std::move(memory));
    t.setFilter(GL_LINEAR, GL_LINEAR);
    t.setWrap(GL_CLAMP_TO_EDGE);
    t.setLabel(label);
    return t;
}

Texture Texture::createBufferView(const Buffer& buffer, GLenum internalFormat, std::string_view label) {
    const std::uint64_t texels = buffer.size() / bytesPerTexel(internalFormat);
    GLint limit = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &limit);
    if (texels > static_cast<std::uint64_t>(limit))
        throw Error(ErrorKind::GpuLimit, std::string(label) + ": " + std::to_string(texels) + " " +
                                             formatName(internalFormat) + " texels exceed GL_MAX_TEXTURE_BUFFER_SIZE (" +
                                             std::to_string(limit) + " on this GPU)");
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_BUFFER, 1, &id);
    glTextureBuffer(id, internalFormat, buffer.id());
    Texture t(id, GL_TEXTURE_BUFFER, internalFormat, {static_cast<int>(texels), 1, 1}, MemoryReservation());
    t.setLabel(label);
    return t;
}

Texture Texture::create2D(GLenum internalFormat, int width, int height, std::string_view label, int levels) {
    return create(GL_TEXTURE_2D, internalFormat, {width, height, 1}, levels, label);
}

Texture Texture::create2DArray(GLenum internalFormat, int width, int height, int layers, std::string_view label) {
    return create(GL_TEXTURE_2D_ARRAY, internalFormat, {width, height, layers}, 1, label);
}

Texture Texture::create3D(GLenum internalFormat, glm::ivec3 size, std::string_view label, int levels) {
    return create(GL_TEXTURE_3D, internalFormat, size, levels, label);
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

void Texture::setSwizzle(GLint r, GLint g, GLint b, GLint a) const {
    const GLint swizzle[4] = {r, g, b, a};
    glTextureParameteriv(id(), GL_TEXTURE_SWIZZLE_RGBA, swizzle);
}

}  // namespace sss::gl
