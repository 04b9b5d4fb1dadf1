#pragma once
// Internal: what the renderers read off an sss::Light besides its colour.
#include "sss/light.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <optional>
#include <variant>

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

/// (cos outer, cos inner): the cosines of the half-angles spotConeFactor() blends between, as
/// it computes them, so the GPU twin in shaders/common/spot_cone.glsl gets the same numbers.
glm::vec2 spotConeCosines(const SpotLight& light);

}  // namespace sss::detail
