#include "gl/buffer.h"

#include "gl/device.h"
#include "sss/error.h"

#include <string>

namespace sss::gl {

Buffer Buffer::create(std::size_t bytes, const void* data, GLbitfield flags, std::string_view label) {
    GLuint id = 0;
    glCreateBuffers(1, &id);
    Object<BufferTraits> owner(id);  // deletes the name if the allocation throws
    MemoryReservation memory = allocateChecked(label, std::to_string(bytes) + "-byte buffer", bytes, [&] {
        glNamedBufferStorage(id, static_cast<GLsizeiptr>(bytes), data, flags);
    });
    // Asked here, not at every bind: a glGet can make a threaded driver wait for its queue.
    Buffer buffer(owner.release(), bytes, std::move(memory), label, storageBlockLimit());
    buffer.setLabel(label);
    return buffer;
}

void Buffer::bindStorage(GLuint binding) const {
    if (m_storageLimit > 0 && m_size > static_cast<std::uint64_t>(m_storageLimit))
        throw Error(ErrorKind::GpuLimit, m_label + ": " + formatBytes(m_size) +
                                             " in one shader-storage binding, more than this device's "
                                             "GL_MAX_SHADER_STORAGE_BLOCK_SIZE (" +
                                             formatBytes(static_cast<std::uint64_t>(m_storageLimit)) + ")");
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, id());
}

void Buffer::upload(std::size_t offset, std::size_t bytes, const void* data) const {
    glNamedBufferSubData(id(), static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), data);
}

}  // namespace sss::gl
