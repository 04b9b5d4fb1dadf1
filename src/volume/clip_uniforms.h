#pragma once
// Sets shaders/volume/clip.glsl's uniforms in a program that includes it.
#include "gl/program.h"
#include "sss/bounds.h"
#include "sss/volume_clip.h"

#include <glm/mat4x4.hpp>

namespace sss::detail {

/// `clip` (null: nothing cut) for a volume of box `box` placed by `model`.
void setClipUniforms(const gl::Program& program, const VolumeClip* clip, const glm::mat4& model, const Bounds& box);

}  // namespace sss::detail
