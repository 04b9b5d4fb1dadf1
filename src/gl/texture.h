#pragma once
#include "gl/allocation.h"
#include "gl/buffer.h"
#include "gl/object.h"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <string_view>

namespace sss::gl {

struct TextureTraits {
    static constexpr GLenum labelNamespace = GL_TEXTURE;
    static void destroy(GLuint id) { glDeleteTextures(1, &id); }
};

/// Immutable-storage texture: 2D, 2D array or 3D (glTextureStorage*). Sampling state defaults to
/// linear filtering and clamp-to-edge. `label` names the texture in KHR_debug messages and in
/// the Error(GpuLimit) thrown when it does not fit: a side over the implementation's limit, more
/// memory than the budget or the driver has, or GL_OUT_OF_MEMORY (gl/allocation.h).
class Texture : public Object<TextureTraits> {
public:
    Texture() = default;
    static Texture create2D(GLenum internalFormat, int width, int height, std::string_view label, int levels = 1);
    static Texture create2DArray(GLenum internalFormat, int width, int height, int layers, std::string_view label);
    static Texture create3D(GLenum internalFormat, glm::ivec3 size, std::string_view label, int levels = 1);
    /// A buffer texture (GL_TEXTURE_BUFFER) over the whole of `buffer`, read as `internalFormat`;
    /// it owns no storage of its own (the buffer must outlive it).
    static Texture createBufferView(const Buffer& buffer, GLenum internalFormat, std::string_view label);

    /// Uploads a whole 2D image, 3D volume, or (for arrays) all layers.
    void upload(GLenum format, GLenum type, const void* pixels) const;
    void setFilter(GLenum minFilter, GLenum magFilter) const;
    void setWrap(GLenum wrap) const;
    /// Colour returned outside the texture with GL_CLAMP_TO_BORDER.
    void setBorderColor(glm::vec4 color) const;
    /// What sampling returns per channel (GL_RED .. GL_ALPHA, GL_ZERO, GL_ONE); images ignore it.
    void setSwizzle(GLint r, GLint g, GLint b, GLint a) const;
    void bind(GLuint unit) const { glBindTextureUnit(unit, id()); }
    /// Binds a mip level (all layers) as image `unit` for imageLoad/imageStore.
    void bindImage(GLuint unit, GLenum access, int level = 0) const {
        glBindImageTexture(unit, id(), level, GL_TRUE, 0, access, m_format);
    }

    GLenum target() const { return m_target; }
    GLenum internalFormat() const { return m_format; }
    glm::ivec3 size() const { return m_size; }  ///< width, height, depth or layers (1 for 2D)
    std::uint64_t bytes() const { return m_memory.bytes(); }

private:
    static Texture create(GLenum target, GLenum internalFormat, glm::ivec3 size, int levels, std::string_view label);
    Texture(GLuint id, GLenum target, GLenum format, glm::ivec3 size, MemoryReservation memory)
        : Object(id), m_target(target), m_format(format), m_size(size), m_memory(std::move(memory)) {}
    GLenum m_target = 0;
    GLenum m_format = 0;
    glm::ivec3 m_size{0};
    MemoryReservation m_memory;
};

/// Bytes per texel of the internal formats libsss uses; "RGBA16F" etc. for messages.
std::uint64_t bytesPerTexel(GLenum internalFormat);
const char* formatName(GLenum internalFormat);

}  // namespace sss::gl
