#include "gl/buffer.h"

namespace sss::gl {

Buffer Buffer::create(std::size_t bytes, const void* data, GLbitfield flags) {
    GLuint id = 0;
    glCreateBuffers(1, &id);
    glNamedBufferStorage(id, static_cast<GLsizeiptr>(bytes), data, flags);
    return Buffer(id, bytes);
}

void Buffer::upload(std::size_t offset, std::size_t bytes, const void* data) const {
    glNamedBufferSubData(id(), static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), data);
}

}  // namespace sss::gl
