#include "gl/buffer.h"

#include <string>

namespace sss::gl {

Buffer Buffer::create(std::size_t bytes, const void* data, GLbitfield flags, std::string_view label) {
    GLuint id = 0;
    glCreateBuffers(1, &id);
    Object<BufferTraits> owner(id);  // deletes the name if the allocation throws
    MemoryReservation memory = allocateChecked(label, std::to_string(bytes) + "-byte buffer", bytes, [&] {
        glNamedBufferStorage(id, static_cast<GLsizeiptr>(bytes), data, flags);
    });
    Buffer buffer(owner.release(), bytes, std::move(memory));
    buffer.setLabel(label);
    return buffer;
}

void Buffer::upload(std::size_t offset, std::size_t bytes, const void* data) const {
    glNamedBufferSubData(id(), static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), data);
}

}  // namespace sss::gl
