#pragma once
// Uploads DipoleConstants (derived once on the CPU in double) to the `DirpoleParams` uniform
// struct of shaders/common/dirpole.glsl.
#include "gl/program.h"
#include "sss/bssrdf.h"

#include <string>

namespace sss::detail {

void setDipoleUniforms(const gl::Program& program, const std::string& name, const DipoleConstants& c);

}  // namespace sss::detail
