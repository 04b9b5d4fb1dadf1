#pragma once
#include "gl/object.h"

#include <cstddef>
#include <span>

namespace sss::gl {

struct BufferTraits {
    static constexpr GLenum labelNamespace = GL_BUFFER;
    static void destroy(GLuint id) { glDeleteBuffers(1, &id); }
};

/// Immutable-storage buffer (glNamedBufferStorage).
class Buffer : public Object<BufferTraits> {
public:
    Buffer() = default;
    /// @param flags glNamedBufferStorage flags; GL_DYNAMIC_STORAGE_BIT allows upload().
    static Buffer create(std::size_t bytes, const void* data, GLbitfield flags = GL_DYNAMIC_STORAGE_BIT);
    template <typename T>
    static Buffer fromSpan(std::span<const T> items, GLbitfield flags = 0) {
        return create(items.size_bytes(), items.data(), flags);
    }
    void upload(std::size_t offset, std::size_t bytes, const void* data) const;
    std::size_t size() const { return m_size; }

private:
    explicit Buffer(GLuint id, std::size_t size) : Object(id), m_size(size) {}
    std::size_t m_size = 0;
};

}  // namespace sss::gl
