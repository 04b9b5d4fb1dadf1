#pragma once
// Internal: a bounding volume hierarchy over triangles for CPU ray queries in double precision
// (the mesh reference renderer's camera and shadow rays). Binned SAH build, Moller-Trumbore
// ray-triangle tests, closest-hit and any-hit queries. Immutable after construction, so one
// instance may be queried from many threads at once.

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

namespace sss::detail {

/// A ray origin + t * direction, t in the open interval (tMin, tMax). direction need not be a
/// unit vector (t is then measured in multiples of it) but must be non-zero.
struct BvhRay {
    glm::dvec3 origin{0.0};
    glm::dvec3 direction{0.0, 0.0, 1.0};
    double tMin = 0.0;
    double tMax = std::numeric_limits<double>::infinity();
};

/// The camera ray of pixel (x, y) of a width x height image (row 0 at the top), through the
/// pixel centre: the segment from the near to the far plane (t in (0, 1)), as the CPU mesh
/// renderers define it (sss/mesh_reference.h).
inline BvhRay pixelRay(const glm::dmat4& inverseViewProjection, int x, int y, int width, int height) {
    const glm::dvec2 ndc((x + 0.5) / width * 2.0 - 1.0, 1.0 - (y + 0.5) / height * 2.0);
    const glm::dvec4 a = inverseViewProjection * glm::dvec4(ndc, -1.0, 1.0);
    const glm::dvec4 b = inverseViewProjection * glm::dvec4(ndc, 1.0, 1.0);
    BvhRay ray;
    ray.origin = glm::dvec3(a) / a.w;
    ray.direction = glm::dvec3(b) / b.w - ray.origin;
    ray.tMin = 0.0;
    ray.tMax = 1.0;
    return ray;
}

/// A ray-triangle intersection: ray parameter t, triangle index (into the indices given at
/// construction, divided by 3) and the barycentric weights u, v of the triangle's second and
/// third vertex (the first has 1 - u - v).
struct BvhHit {
    double t = 0.0;
    uint32_t triangle = 0;
    double u = 0.0;
    double v = 0.0;
};

/// Moller-Trumbore ray-triangle intersection in double. True (with t, u, v set) when the ray
/// meets the triangle (p0, p1, p2) at tMin < t < tMax, from either side, edges included
/// (u, v >= 0, u + v <= 1). Degenerate triangles and rays in the triangle's plane never hit.
bool intersectTriangle(const glm::dvec3& origin, const glm::dvec3& direction, double tMin, double tMax,
                       const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2, double& t, double& u,
                       double& v);

class TriangleBvh {
public:
    /// Builds the hierarchy over the triangles (indices, 3 per triangle) of `positions`.
    /// Asserts that every index is in range; an empty index list gives a BVH that hits nothing.
    TriangleBvh(std::vector<glm::dvec3> positions, std::vector<uint32_t> indices, int maxLeafSize = 4);

    /// The nearest intersection in (tMin, tMax); among hits at exactly the same t (a shared
    /// edge), whichever is found first.
    std::optional<BvhHit> closestHit(const BvhRay& ray) const;
    /// Whether any triangle is hit in (tMin, tMax) (shadow rays); stops at the first found.
    bool anyHit(const BvhRay& ray) const;

    std::size_t triangleCount() const { return m_indices.size() / 3; }
    std::size_t nodeCount() const { return m_nodes.size(); }
    /// Longest root-to-leaf path (1 for a single leaf).
    int depth() const { return m_depth; }
    const std::vector<glm::dvec3>& positions() const { return m_positions; }
    const std::vector<uint32_t>& indices() const { return m_indices; }

private:
    struct Node {
        glm::dvec3 lo{0.0}, hi{0.0};
        uint32_t first = 0;  // leaf: first entry in m_tris; interior: index of the second child
        uint32_t count = 0;  // leaf: number of triangles (> 0); interior: 0 (first child = this + 1)
    };
    struct Tri {  // leaf order, precomputed for the intersection test
        glm::dvec3 p0, p1, p2;
        uint32_t id;
    };

    uint32_t build(std::vector<uint32_t>& ids, std::vector<glm::dvec3>& centroids, std::vector<glm::dvec3>& lo,
                   std::vector<glm::dvec3>& hi, uint32_t begin, uint32_t end, int depth, int maxLeafSize);

    std::vector<glm::dvec3> m_positions;
    std::vector<uint32_t> m_indices;
    std::vector<Node> m_nodes;
    std::vector<Tri> m_tris;
    int m_depth = 0;
};

}  // namespace sss::detail
