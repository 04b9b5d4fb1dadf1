#pragma once
// Internal: clipping a ray to an axis-aligned box, shared by the CPU volume renderers (the
// reference and the path tracer) so both see exactly the same spans.
#include <glm/vec3.hpp>

#include <algorithm>
#include <utility>

namespace sss::detail {

/// Clips origin + t * dir, t in [tMin, tMax], to the box [boxMin, boxMax]; false if nothing is left.
inline bool clipToBox(const glm::dvec3& boxMin, const glm::dvec3& boxMax, const glm::dvec3& origin,
                      const glm::dvec3& dir, double& tMin, double& tMax) {
    for (int a = 0; a < 3; ++a) {
        if (dir[a] == 0.0) {
            if (origin[a] < boxMin[a] || origin[a] > boxMax[a]) return false;
            continue;
        }
        double t0 = (boxMin[a] - origin[a]) / dir[a], t1 = (boxMax[a] - origin[a]) / dir[a];
        if (t0 > t1) std::swap(t0, t1);
        tMin = std::max(tMin, t0);
        tMax = std::min(tMax, t1);
    }
    return tMin < tMax;
}

}  // namespace sss::detail
