#pragma once
// One triangle covering the viewport (shaders/common/fullscreen.vert), drawn with `program` and
// an empty vertex array; leaves no program or vertex array bound (src/lighting/gl_state.h).
#include "gl/gl.h"
#include "gl/program.h"
#include "gl/vertex_array.h"

namespace sss::gl {

inline void drawFullscreenTriangle(const Program& program, const VertexArray& emptyVertexArray) {
    program.use();
    emptyVertexArray.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glUseProgram(0);
}

}  // namespace sss::gl
