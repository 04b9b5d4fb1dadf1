#pragma once
#include "gl/object.h"
#include "gl/buffer.h"

#include <cstddef>

namespace sss::gl {

struct VertexArrayTraits {
    static constexpr GLenum labelNamespace = GL_VERTEX_ARRAY;
    static void destroy(GLuint id) { glDeleteVertexArrays(1, &id); }
};


/// Vertex array object with direct-state-access attribute setup.
class VertexArray : public Object<VertexArrayTraits> {
public:
    VertexArray() = default;
    static VertexArray create();
    /// Float attribute `location` read from `buffer` at `offset` with the given stride.
    void setAttribute(GLuint location, const Buffer& buffer, int components, std::size_t offset,
                      std::size_t stride) const;
    void setIndexBuffer(const Buffer& buffer) const { glVertexArrayElementBuffer(id(), buffer.id()); }
    void bind() const { glBindVertexArray(id()); }

private:
    explicit VertexArray(GLuint id) : Object(id) {}
};

}  // namespace sss::gl
