#pragma once
// The volume passes' last step: one fullscreen triangle whose fragments are premultiplied colour
// composited "over" what the target holds (no depth test or write), leaving the GL state as the
// contract in lighting/gl_state.h expects it.
#include "gl/fullscreen.h"
#include "gl/gl.h"
#include "gl/program.h"
#include "gl/vertex_array.h"

namespace sss::detail {

inline void drawPremultipliedOver(const gl::Program& program, const gl::VertexArray& emptyVertexArray) {
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    gl::drawFullscreenTriangle(program, emptyVertexArray);
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
}

}  // namespace sss::detail
