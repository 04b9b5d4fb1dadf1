#pragma once
/// @file
/// Axis-aligned bounding box.

#include "sss/api.h"
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <limits>

SSS_BEGIN_API

namespace sss {

/// An axis-aligned box. Default-constructed it is empty (min = +inf, max = -inf), so the first
/// extend() sets it to a single point.
struct Bounds {
    glm::vec3 min{std::numeric_limits<float>::infinity()};   ///< smallest corner; +inf when empty
    glm::vec3 max{-std::numeric_limits<float>::infinity()};  ///< largest corner; -inf when empty

    /// Grows the box to contain point p.
    void extend(glm::vec3 p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }

    /// Grows the box to contain another box; extending by an empty box changes nothing.
    void extend(const Bounds& other) {
        if (other.empty()) return;
        extend(other.min);
        extend(other.max);
    }

    /// True when no point was added (any min component > max component).
    bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }

    /// Centre of the box; (0,0,0) when empty.
    glm::vec3 center() const { return empty() ? glm::vec3(0.0f) : (min + max) * 0.5f; }

    /// Extent along each axis (max - min); (0,0,0) when empty.
    glm::vec3 size() const { return empty() ? glm::vec3(0.0f) : max - min; }

    /// Radius of the bounding sphere around center(): half the diagonal; 0 when empty.
    float radius() const { return 0.5f * glm::length(size()); }
};

}  // namespace sss

SSS_END_API
