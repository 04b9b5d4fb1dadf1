#pragma once
#include "gl/allocation.h"
#include "gl/object.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>

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
    /// @param label names the buffer in KHR_debug messages and in Error(GpuLimit) (gl/allocation.h).
    static Buffer create(std::size_t bytes, const void* data, GLbitfield flags, std::string_view label);
    void upload(std::size_t offset, std::size_t bytes, const void* data) const;
    std::size_t size() const { return m_size; }
    /// Binds the whole buffer to a shader-storage binding point. Throws Error(GpuLimit) naming the
    /// buffer where it is larger than one storage block may be (gl::storageBlockLimit(), asked when
    /// the buffer was made): a shader would read and write past what the device promises, a wrong
    /// picture with no GL error.
    void bindStorage(GLuint binding) const;

private:
    Buffer(GLuint id, std::size_t size, MemoryReservation memory, std::string_view label, std::int64_t storageLimit)
        : Object(id), m_size(size), m_memory(std::move(memory)), m_label(label), m_storageLimit(storageLimit) {}
    std::size_t m_size = 0;
    MemoryReservation m_memory;
    std::string m_label;
    std::int64_t m_storageLimit = 0;  // bytes; 0: none known
};

}  // namespace sss::gl
