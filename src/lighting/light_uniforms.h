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
/// lightSpotAxis[index] and lightSpotCosines[index] (lights.glsl's layout, which path_trace.comp
/// shares): the cone of a spot light, no cone for other lights. setLightUniforms() calls it.
void setSpotConeUniforms(const gl::Program& program, int index, const Light& light);

}  // namespace sss::detail
