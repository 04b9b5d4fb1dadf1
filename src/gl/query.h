#pragma once
#include "gl/object.h"

namespace sss::gl {

struct QueryTraits {
    static constexpr GLenum labelNamespace = GL_QUERY;
    static void destroy(GLuint id) { glDeleteQueries(1, &id); }
};

/// A GL query object (used for GL_TIME_ELAPSED timing on real GPUs).
class Query : public Object<QueryTraits> {
public:
    Query() = default;
    static Query create(GLenum target);

private:
    explicit Query(GLuint id) : Object(id) {}
};

}  // namespace sss::gl
