#pragma once
/// @file
/// Light sources shared by the mesh and volume renderers.

#include <glm/vec3.hpp>

#include <string_view>
#include <variant>

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

/// Either kind of light.
using Light = std::variant<DirectionalLight, PointLight>;

/// Checks a light: finite, non-zero direction (directional), finite position (point), finite
/// color and intensity, all >= 0. `what` names the light in messages ("SceneOptions::light").
/// @throws Error InvalidArgument naming `what`, the field and the bad value.
void validateLight(const Light& light, std::string_view what);

}  // namespace sss
