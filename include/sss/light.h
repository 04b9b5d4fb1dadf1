#pragma once
/// @file
/// Light sources shared by the mesh and volume renderers.

#include "sss/api.h"
#include <glm/vec3.hpp>

#include <string_view>
#include <variant>

SSS_BEGIN_API

namespace sss {

/// A light at infinity.
struct DirectionalLight {
    glm::vec3 direction{0.0f, 0.0f, -1.0f};  ///< direction the light travels (not towards it); normalized on use, must be non-zero
    glm::vec3 color{1.0f};                   ///< linear RGB, each >= 0
    float intensity = 1.0f;                  ///< scales color, >= 0
    bool operator==(const DirectionalLight&) const = default;
};

/// An isotropic point light.
struct PointLight {
    glm::vec3 position{0.0f, 2.0f, 2.0f};  ///< world-space position
    glm::vec3 color{1.0f};                 ///< linear RGB, each >= 0
    float intensity = 1.0f;                ///< scales color, >= 0
    bool operator==(const PointLight&) const = default;
};

/// A point light that emits into a cone around `direction`. Inside the inner cone it is a point
/// light of the same colour and intensity; between the inner and the outer cone its radiant
/// intensity fades with spotConeFactor(); outside the outer cone it emits nothing.
struct SpotLight {
    glm::vec3 position{0.0f, 2.0f, 2.0f};     ///< world-space position
    glm::vec3 direction{0.0f, -1.0f, -1.0f};  ///< axis of the cone, the way it points; normalized on use, non-zero
    float coneAngle = 30.0f;                  ///< half-angle of the outer cone, degrees, in (0, 90]
    float falloff = 0.2f;  ///< share of coneAngle over which the edge fades, [0, 1]; 0: a hard edge
    glm::vec3 color{1.0f};  ///< linear RGB, each >= 0
    float intensity = 1.0f;  ///< scales color, >= 0
    bool operator==(const SpotLight&) const = default;
};

/// Any kind of light.
using Light = std::variant<DirectionalLight, PointLight, SpotLight>;

/// The fraction of a spot light's intensity sent at `cosAngle`, the cosine of the angle between
/// the cone axis and the direction of emission: 1 inside the inner cone (half-angle
/// coneAngle * (1 - falloff)), 0 outside the outer cone, and smoothstep in the cosine between.
/// The GLSL twin is spotConeFactor() in shaders/common/spot_cone.glsl.
float spotConeFactor(const SpotLight& light, float cosAngle);

/// Checks a light: finite, non-zero direction (directional, spot), finite position (point,
/// spot), coneAngle in (0, 90] and falloff in [0, 1] (spot), finite color and intensity, all
/// >= 0. `what` names the light in messages ("SceneOptions::light").
/// @throws Error InvalidArgument naming `what`, the field and the bad value.
void validateLight(const Light& light, std::string_view what);

}  // namespace sss

SSS_END_API
