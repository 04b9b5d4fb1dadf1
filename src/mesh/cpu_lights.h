#pragma once
// Internal: the scene's lights prepared once, in double, for the CPU renderers of meshes (the
// reference and the random walk), and the light one of them sends to a point.
#include "sss/light.h"

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cmath>
#include <string>
#include <variant>
#include <vector>

namespace sss::detail {

struct CpuLight {
    bool point = false;
    glm::dvec3 vector{0.0};    // directional: unit vector towards the light; point: position
    glm::dvec3 radiance{0.0};  // color * intensity
};

/// Validates every light (errors name "<where>: lights[i]") and keeps those that emit anything.
inline std::vector<CpuLight> prepareCpuLights(const std::vector<Light>& lights, const std::string& where) {
    std::vector<CpuLight> prepared;
    for (size_t i = 0; i < lights.size(); ++i) {
        validateLight(lights[i], where + ": lights[" + std::to_string(i) + "]");
        CpuLight info;
        if (const auto* d = std::get_if<DirectionalLight>(&lights[i])) {
            info.vector = -glm::normalize(glm::dvec3(d->direction));
            info.radiance = glm::dvec3(d->color) * double(d->intensity);
        } else {
            const auto& p = std::get<PointLight>(lights[i]);
            info.point = true;
            info.vector = glm::dvec3(p.position);
            info.radiance = glm::dvec3(p.color) * double(p.intensity);
        }
        if (info.radiance.x > 0.0 || info.radiance.y > 0.0 || info.radiance.z > 0.0) prepared.push_back(info);
    }
    return prepared;
}

/// The unit direction from `x` towards light `l` and the irradiance it gives normal to that
/// direction (point lights fall off with the squared distance). False when x is at the light.
inline bool lightAt(const CpuLight& l, const glm::dvec3& x, glm::dvec3& towards, glm::dvec3& irradiance) {
    towards = l.vector;
    irradiance = l.radiance;
    if (!l.point) return true;
    const glm::dvec3 d = l.vector - x;
    const double d2 = glm::dot(d, d);
    if (!(d2 > 0.0)) return false;
    towards = d / std::sqrt(d2);
    irradiance /= d2;
    return true;
}

}  // namespace sss::detail
