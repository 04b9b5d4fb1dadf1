#include "gl/vertex_array.h"

#include "gl/buffer.h"

namespace sss::gl {

VertexArray VertexArray::create() {
    GLuint id = 0;
    glCreateVertexArrays(1, &id);
    return VertexArray(id);
}

void VertexArray::setAttribute(GLuint location, const Buffer& buffer, int components, std::size_t offset,
                               std::size_t stride) const {
    // One binding point per attribute keeps the mapping trivial for the few attributes we use.
    glVertexArrayVertexBuffer(id(), location, buffer.id(), static_cast<GLintptr>(offset),
                              static_cast<GLsizei>(stride));
    glVertexArrayAttribFormat(id(), location, components, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(id(), location, location);
    glEnableVertexArrayAttrib(id(), location);
}


}  // namespace sss::gl
