#include "gl/query.h"

namespace sss::gl {

Query Query::create(GLenum target) {
    GLuint id = 0;
    glCreateQueries(target, 1, &id);
    return Query(id);
}

}  // namespace sss::gl
