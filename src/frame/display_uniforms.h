#pragma once
// The uniforms of shaders/common/display_transform.glsl for one DisplayTransform, set the same
// way by every pass that encodes for display (DisplayEncoder, HostTarget's present).
#include "gl/program.h"
#include "sss/display.h"

namespace sss::detail {

void setDisplayUniforms(const gl::Program& program, const DisplayTransform& transform);

}  // namespace sss::detail
