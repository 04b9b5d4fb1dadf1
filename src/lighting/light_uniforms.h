#pragma once
// Uploads sss::Light values to the uniforms declared in shaders/common/lights.glsl.
#include "gl/program.h"
#include "sss/light.h"

#include <string_view>
#include <vector>

namespace sss::detail {

inline constexpr int kMaxLights = 8;  // MAX_LIGHTS in shaders/common/lights.glsl

/// Validates every light and the count; `owner` prefixes error messages.
void validateLights(const std::vector<Light>& lights, std::string_view owner);
void setLightUniforms(const gl::Program& program, const std::vector<Light>& lights);

}  // namespace sss::detail
