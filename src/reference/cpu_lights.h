#pragma once
// Internal: the scene's lights prepared once, in double, for the CPU renderers (the mesh
// reference and random walk, the volume reference and path tracer), and the light one of them
// sends to a point. lights.glsl is the GPU side.
#include "sss/light.h"

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cmath>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace sss::detail {

struct CpuLight {
    bool point = false;        // point or spot light: `vector` is a position
    glm::dvec3 vector{0.0};    // directional: unit vector towards the light; point, spot: world position
    glm::dvec3 radiance{0.0};  // color * intensity
    std::optional<SpotLight> spot;  // a spot light's cone (spotConeFactor); none for other lights
    glm::dvec3 spotAxis{0.0};       // spot: unit cone axis, the way it points
};

/// One light in double. Does not validate.
inline CpuLight toCpuLight(const Light& light) {
    CpuLight info;
    if (const auto* d = std::get_if<DirectionalLight>(&light)) {
        info.vector = -glm::normalize(glm::dvec3(d->direction));
        info.radiance = glm::dvec3(d->color) * double(d->intensity);
    } else if (const auto* p = std::get_if<PointLight>(&light)) {
        info.point = true;
        info.vector = glm::dvec3(p->position);
        info.radiance = glm::dvec3(p->color) * double(p->intensity);
    } else {
        const auto& s = std::get<SpotLight>(light);
        info.point = true;
        info.vector = glm::dvec3(s.position);
        info.radiance = glm::dvec3(s.color) * double(s.intensity);
        info.spot = s;
        info.spotAxis = glm::normalize(glm::dvec3(s.direction));
    }
    return info;
}

/// Validates every light (errors name "<where>: lights[i]") and keeps those that emit anything.
inline std::vector<CpuLight> prepareCpuLights(const std::vector<Light>& lights, const std::string& where) {
    std::vector<CpuLight> prepared;
    for (size_t i = 0; i < lights.size(); ++i) {
        validateLight(lights[i], where + ": lights[" + std::to_string(i) + "]");
        CpuLight info = toCpuLight(lights[i]);
        if (info.radiance.x > 0.0 || info.radiance.y > 0.0 || info.radiance.z > 0.0) prepared.push_back(info);
    }
    return prepared;
}

/// The share of its intensity a positional light sends towards world point `x`: the spot cone's
/// factor (in float, sss::spotConeFactor), 1 for point and directional lights.
inline double emittedShare(const CpuLight& l, const glm::dvec3& x) {
    if (!l.spot) return 1.0;
    const glm::dvec3 d = x - l.vector;
    const double length = glm::length(d);
    return spotConeFactor(*l.spot, length > 0.0 ? static_cast<float>(glm::dot(d, l.spotAxis) / length) : 1.0f);
}

/// The unit direction from `x` towards light `l` and the irradiance it gives normal to that
/// direction (point and spot lights fall off with the squared distance, spots with their cone).
/// False when x is at the light.
inline bool lightAt(const CpuLight& l, const glm::dvec3& x, glm::dvec3& towards, glm::dvec3& irradiance) {
    towards = l.vector;
    irradiance = l.radiance;
    if (!l.point) return true;
    const glm::dvec3 d = l.vector - x;
    const double d2 = glm::dot(d, d);
    if (!(d2 > 0.0)) return false;
    towards = d / std::sqrt(d2);
    irradiance = irradiance / d2 * emittedShare(l, x);
    return true;
}

}  // namespace sss::detail
