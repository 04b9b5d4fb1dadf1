#include "volume/light_sweep_plan.h"

#include "core/light_geometry.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace sss::detail {
namespace {

constexpr float kPi = 3.14159265358979f;

float henyeyGreenstein(float cosine, float g) {
    const float denominator = 1.0f + g * g - 2.0f * g * cosine;
    return (1.0f - g * g) / (4.0f * kPi * denominator * std::sqrt(denominator));
}

// Sorted component magnitudes with their axes, largest first.
std::array<std::pair<float, int>, 3> rankAxes(glm::vec3 magnitude) {
    std::array<std::pair<float, int>, 3> ranked{{{magnitude.x, 0}, {magnitude.y, 1}, {magnitude.z, 2}}};
    std::sort(ranked.begin(), ranked.end(), [](auto a, auto b) { return a.first > b.first; });
    return ranked;
}

}  // namespace

float secondSweepWeight(float share) {
    return 0.5f * std::clamp((share - kSweepBlendStart) / (0.5f - kSweepBlendStart), 0.0f, 1.0f);
}

float chromaticityConeAngle(float g) {
    constexpr float maxAngle = 60.0f * kPi / 180.0f;
    if (g <= 1e-3f) return maxAngle;  // isotropic or backward: widest blur
    // Inverting the HG sampling formula at xi = 1/2 gives the cone holding half the energy.
    const float k = (1.0f - g * g);
    const float cosine = (1.0f + g * g - k * k) / (2.0f * g);
    return std::min(std::acos(std::clamp(cosine, -1.0f, 1.0f)), maxAngle);
}

ChromaticityCone chromaticityCone(float g) {
    const float angle = chromaticityConeAngle(g);
    const float centre = henyeyGreenstein(1.0f, g);
    const float ring = henyeyGreenstein(std::cos(angle), g);
    const float norm = centre + 8.0f * ring;
    return {std::tan(angle), centre / norm, ring / norm};
}

std::vector<LightSweep> planLightSweeps(const Light& light, const Bounds& box, glm::ivec3 dims) {
    const glm::vec3 voxelSize = box.size() / glm::vec3(dims);
    if (const auto* directional = std::get_if<DirectionalLight>(&light)) {
        // Rank axes by how far the light moves per slice, in voxels, so the previous-slice lookup
        // on the main axis stays within one texel even for anisotropic voxels.
        const glm::vec3 d = glm::normalize(directional->direction) / voxelSize;
        const auto ranked = rankAxes(glm::abs(d) / glm::length(d));
        const float w1 = ranked[0].first - ranked[2].first, w2 = ranked[1].first - ranked[2].first;
        const float sum = w1 + w2;
        const float second = secondSweepWeight(sum > 0 ? w2 / sum : 0.5f);
        std::vector<LightSweep> sweeps{{ranked[0].second, d[ranked[0].second] < 0, 1.0f - second}};
        if (second > 0) sweeps.push_back({ranked[1].second, d[ranked[1].second] < 0, second});
        return sweeps;
    }
    // Point or spot light: how far outside the box it is along each axis, in half-extents.
    const glm::vec3 position = *lightPosition(light);
    const glm::vec3 offset = position - box.center();
    const glm::vec3 ratio = glm::abs(offset) / (0.5f * box.size());
    const auto ranked = rankAxes(ratio);
    if (ranked[0].first <= 1.0f) {
        // Inside the box or on its boundary: sweep outward from the light in all six directions.
        std::vector<LightSweep> sweeps;
        for (int axis = 0; axis < 3; ++axis) {
            const float slice = (position[axis] - box.min[axis]) / voxelSize[axis] - 0.5f;
            // Each sweep starts at the first slice beyond the light, so nothing it passes through
            // lies behind the light.
            const int forward = std::clamp(static_cast<int>(std::ceil(slice)), 0, dims[axis] - 1);
            const int backward = std::clamp(static_cast<int>(std::ceil(static_cast<float>(dims[axis] - 1) - slice)), 0, dims[axis] - 1);
            sweeps.push_back({axis, false, 1.0f, forward, true});
            sweeps.push_back({axis, true, 1.0f, backward, true});
        }
        return sweeps;
    }
    // Outside: the light travels into the box through the face(s) it is beyond. A second axis
    // is valid only while the light is beyond that face too; its share reaches 0 as it stops,
    // and the second sweep runs only near the diagonal, as for a directional light.
    const float floor3 = std::max(1.0f, ranked[2].first);
    const float w1 = ranked[0].first - floor3, w2 = std::max(0.0f, ranked[1].first - floor3);
    const float second = w2 > 0 ? secondSweepWeight(w2 / (w1 + w2)) : 0.0f;
    std::vector<LightSweep> sweeps{{ranked[0].second, offset[ranked[0].second] > 0, 1.0f - second}};
    if (second > 0) sweeps.push_back({ranked[1].second, offset[ranked[1].second] > 0, second});
    return sweeps;
}

glm::ivec3 lightVolumeDims(glm::ivec3 volumeDims, float scale) {
    return glm::max(glm::ivec3(1), glm::ivec3(glm::round(glm::vec3(volumeDims) * scale)));
}

}  // namespace sss::detail
