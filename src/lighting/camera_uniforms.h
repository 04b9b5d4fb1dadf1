#pragma once
// Uploads the viewer to the uniforms of shaders/common/camera.glsl.
#include "gl/program.h"
#include "sss/camera.h"

namespace sss::detail {

void setCameraUniforms(const gl::Program& program, const Camera& camera);

}  // namespace sss::detail
