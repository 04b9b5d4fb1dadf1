#pragma once
// Internal: what the renderers read off an sss::Light besides its colour.
#include "sss/light.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <optional>
#include <variant>
#include <vector>

namespace sss::detail {

/// The position of a point or spot light; none for a directional light.
inline std::optional<glm::vec3> lightPosition(const Light& light) {
    if (const auto* p = std::get_if<PointLight>(&light)) return p->position;
    if (const auto* s = std::get_if<SpotLight>(&light)) return s->position;
    return std::nullopt;
}

/// Colour times intensity, for any kind of light.
inline glm::vec3 lightRadiance(const Light& light) {
    return std::visit([](const auto& l) { return l.color * l.intensity; }, light);
}

/// The lights with colour and intensity 1: what light travels where, without how much of it.
/// Light volumes, photon paths and shadow maps depend on no more (the eye multiplies by the
/// radiance), so they are keyed on this.
std::vector<Light> withUnitRadiance(std::vector<Light> lights);

/// The lights as a light volume holds them: unit radiance, and each spot light as a point light
/// at its position (the eye applies the cone). A spot aimed or widened keeps its light volume.
std::vector<Light> asLightVolumeLights(std::vector<Light> lights);

/// The per-channel factor f with lightRadiance(now[i]) = f * lightRadiance(before[i]) for every
/// light, the lights otherwise the same: one intensity or colour change of a single light, or
/// all lights scaled alike. None where the lights differ otherwise, or where a channel that was
/// dark in every light now shines (nothing was traced for it).
std::optional<glm::vec3> commonRadianceScale(const std::vector<Light>& before, const std::vector<Light>& now);

/// (cos outer, cos inner): the cosines of the half-angles spotConeFactor() blends between, as
/// it computes them, so the GPU twin in shaders/common/spot_cone.glsl gets the same numbers.
glm::vec2 spotConeCosines(const SpotLight& light);

}  // namespace sss::detail
