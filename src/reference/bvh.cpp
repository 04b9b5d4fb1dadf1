// Binned-SAH bounding volume hierarchy over triangles, double precision (see bvh.h).
#include "reference/bvh.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

namespace sss::detail {
namespace {

constexpr int kBins = 16;
constexpr double kInf = std::numeric_limits<double>::infinity();

double halfArea(const glm::dvec3& lo, const glm::dvec3& hi) {
    const glm::dvec3 e = glm::max(hi - lo, glm::dvec3(0.0));
    return e.x * e.y + e.y * e.z + e.z * e.x;
}

// Slab test; returns the entry distance or +inf when the box is missed within (tMin, tMax).
double hitBox(const glm::dvec3& lo, const glm::dvec3& hi, const glm::dvec3& origin, const glm::dvec3& invDir,
              double tMin, double tMax) {
    for (int a = 0; a < 3; ++a) {
        double t0 = (lo[a] - origin[a]) * invDir[a];
        double t1 = (hi[a] - origin[a]) * invDir[a];
        if (t0 > t1) std::swap(t0, t1);
        // NaN (0 * inf: origin on a slab plane with the ray parallel to it) must not cull:
        // fmax/fmin ignore a NaN operand.
        tMin = std::fmax(tMin, t0);
        tMax = std::fmin(tMax, t1);
        if (tMin > tMax) return kInf;
    }
    return tMin;
}

}  // namespace

bool intersectTriangle(const glm::dvec3& origin, const glm::dvec3& direction, double tMin, double tMax,
                       const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2, double& t, double& u,
                       double& v) {
    const glm::dvec3 e1 = p1 - p0;
    const glm::dvec3 e2 = p2 - p0;
    const glm::dvec3 p = glm::cross(direction, e2);
    const double det = glm::dot(e1, p);
    if (det == 0.0 || !std::isfinite(det)) return false;
    const double invDet = 1.0 / det;
    const glm::dvec3 s = origin - p0;
    const double uu = glm::dot(s, p) * invDet;
    if (!(uu >= 0.0 && uu <= 1.0)) return false;
    const glm::dvec3 q = glm::cross(s, e1);
    const double vv = glm::dot(direction, q) * invDet;
    if (!(vv >= 0.0 && uu + vv <= 1.0)) return false;
    const double tt = glm::dot(e2, q) * invDet;
    if (!(tt > tMin && tt < tMax)) return false;
    t = tt;
    u = uu;
    v = vv;
    return true;
}

TriangleBvh::TriangleBvh(std::vector<glm::dvec3> positions, std::vector<uint32_t> indices, int maxLeafSize)
    : m_positions(std::move(positions)), m_indices(std::move(indices)) {
    assert(m_indices.size() % 3 == 0);
    const auto n = static_cast<uint32_t>(m_indices.size() / 3);
    if (n == 0) return;
    std::vector<uint32_t> ids(n);
    std::vector<glm::dvec3> centroids(n), lo(n), hi(n);
    for (uint32_t i = 0; i < n; ++i) {
        assert(m_indices[3 * i] < m_positions.size() && m_indices[3 * i + 1] < m_positions.size() &&
               m_indices[3 * i + 2] < m_positions.size());
        const glm::dvec3& a = m_positions[m_indices[3 * i]];
        const glm::dvec3& b = m_positions[m_indices[3 * i + 1]];
        const glm::dvec3& c = m_positions[m_indices[3 * i + 2]];
        ids[i] = i;
        lo[i] = glm::min(a, glm::min(b, c));
        hi[i] = glm::max(a, glm::max(b, c));
        centroids[i] = (a + b + c) / 3.0;
    }
    m_nodes.reserve(2 * static_cast<size_t>(n));
    build(ids, centroids, lo, hi, 0, n, 1, std::max(1, maxLeafSize));
    m_tris.reserve(n);
    for (uint32_t id : ids)
        m_tris.push_back({m_positions[m_indices[3 * id]], m_positions[m_indices[3 * id + 1]],
                          m_positions[m_indices[3 * id + 2]], id});
}

uint32_t TriangleBvh::build(std::vector<uint32_t>& ids, std::vector<glm::dvec3>& centroids,
                            std::vector<glm::dvec3>& lo, std::vector<glm::dvec3>& hi, uint32_t begin, uint32_t end,
                            int depth, int maxLeafSize) {
    m_depth = std::max(m_depth, depth);
    const auto nodeIndex = static_cast<uint32_t>(m_nodes.size());
    m_nodes.emplace_back();
    glm::dvec3 boxLo(kInf), boxHi(-kInf), cLo(kInf), cHi(-kInf);
    for (uint32_t i = begin; i < end; ++i) {
        boxLo = glm::min(boxLo, lo[ids[i]]);
        boxHi = glm::max(boxHi, hi[ids[i]]);
        cLo = glm::min(cLo, centroids[ids[i]]);
        cHi = glm::max(cHi, centroids[ids[i]]);
    }
    m_nodes[nodeIndex].lo = boxLo;
    m_nodes[nodeIndex].hi = boxHi;
    const uint32_t count = end - begin;

    auto makeLeaf = [&] {
        m_nodes[nodeIndex].first = begin;
        m_nodes[nodeIndex].count = count;
        return nodeIndex;
    };
    if (count <= static_cast<uint32_t>(maxLeafSize)) return makeLeaf();

    // Binned SAH over the centroids, all three axes.
    struct Bin {
        glm::dvec3 lo{kInf}, hi{-kInf};
        uint32_t count = 0;
    };
    double bestCost = kInf;
    int bestAxis = -1, bestSplit = -1;
    // Past depth 48 (pathological inputs) median splits bound the depth, and so the stacks.
    const int sahAxes = depth < 48 ? 3 : 0;
    for (int axis = 0; axis < sahAxes; ++axis) {
        const double extent = cHi[axis] - cLo[axis];
        if (!(extent > 0.0)) continue;
        std::array<Bin, kBins> bins{};
        const double scale = kBins / extent;
        for (uint32_t i = begin; i < end; ++i) {
            const uint32_t id = ids[i];
            const int b = std::min(kBins - 1, static_cast<int>((centroids[id][axis] - cLo[axis]) * scale));
            bins[b].lo = glm::min(bins[b].lo, lo[id]);
            bins[b].hi = glm::max(bins[b].hi, hi[id]);
            ++bins[b].count;
        }
        std::array<double, kBins - 1> leftCost{};
        Bin acc;
        for (int b = 0; b < kBins - 1; ++b) {
            acc.lo = glm::min(acc.lo, bins[b].lo);
            acc.hi = glm::max(acc.hi, bins[b].hi);
            acc.count += bins[b].count;
            leftCost[b] = acc.count ? acc.count * halfArea(acc.lo, acc.hi) : 0.0;
        }
        acc = Bin{};
        for (int b = kBins - 1; b >= 1; --b) {
            acc.lo = glm::min(acc.lo, bins[b].lo);
            acc.hi = glm::max(acc.hi, bins[b].hi);
            acc.count += bins[b].count;
            const double cost = leftCost[b - 1] + (acc.count ? acc.count * halfArea(acc.lo, acc.hi) : 0.0);
            if (cost < bestCost) {
                bestCost = cost;
                bestAxis = axis;
                bestSplit = b;
            }
        }
    }
    uint32_t mid = begin;
    if (bestAxis >= 0) {
        const double scale = kBins / (cHi[bestAxis] - cLo[bestAxis]);
        const auto it = std::partition(ids.begin() + begin, ids.begin() + end, [&](uint32_t id) {
            const int b = std::min(kBins - 1, static_cast<int>((centroids[id][bestAxis] - cLo[bestAxis]) * scale));
            return b < bestSplit;
        });
        mid = static_cast<uint32_t>(it - ids.begin());
    }
    if (mid == begin || mid == end) {
        // Median split on the longest centroid axis (also when all centroids coincide: then by
        // order, so that leaves stay small anyway).
        const glm::dvec3 e = cHi - cLo;
        const int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
        mid = begin + count / 2;
        std::nth_element(ids.begin() + begin, ids.begin() + mid, ids.begin() + end,
                         [&](uint32_t a, uint32_t b) { return centroids[a][axis] < centroids[b][axis]; });
    }
    // Interior: first child follows immediately, the second's index is stored in `first`.
    build(ids, centroids, lo, hi, begin, mid, depth + 1, maxLeafSize);
    const uint32_t second = build(ids, centroids, lo, hi, mid, end, depth + 1, maxLeafSize);
    m_nodes[nodeIndex].first = second;
    m_nodes[nodeIndex].count = 0;
    return nodeIndex;
}

std::optional<BvhHit> TriangleBvh::closestHit(const BvhRay& ray) const {
    if (m_nodes.empty()) return std::nullopt;
    const glm::dvec3 invDir = 1.0 / ray.direction;
    double tMax = ray.tMax;
    std::optional<BvhHit> best;
    struct Entry {
        uint32_t node;
        double t;
    };
    Entry stack[128];
    int top = 0;
    const double tRoot = hitBox(m_nodes[0].lo, m_nodes[0].hi, ray.origin, invDir, ray.tMin, tMax);
    if (tRoot == kInf) return std::nullopt;
    stack[top++] = {0, tRoot};
    while (top > 0) {
        const Entry entry = stack[--top];
        if (entry.t > tMax) continue;  // a nearer hit was found after this node was pushed
        const Node& node = m_nodes[entry.node];
        if (node.count > 0) {
            for (uint32_t i = node.first; i < node.first + node.count; ++i) {
                const Tri& tri = m_tris[i];
                double t, u, v;
                if (intersectTriangle(ray.origin, ray.direction, ray.tMin, tMax, tri.p0, tri.p1, tri.p2, t, u, v)) {
                    tMax = t;
                    best = BvhHit{t, tri.id, u, v};
                }
            }
            continue;
        }
        const auto a = static_cast<uint32_t>(&node - m_nodes.data()) + 1;
        const uint32_t b = node.first;
        const double ta = hitBox(m_nodes[a].lo, m_nodes[a].hi, ray.origin, invDir, ray.tMin, tMax);
        const double tb = hitBox(m_nodes[b].lo, m_nodes[b].hi, ray.origin, invDir, ray.tMin, tMax);
        // Push the farther child first so the nearer one is visited next.
        if (ta <= tb) {
            if (tb != kInf) stack[top++] = {b, tb};
            if (ta != kInf) stack[top++] = {a, ta};
        } else {
            if (ta != kInf) stack[top++] = {a, ta};
            if (tb != kInf) stack[top++] = {b, tb};
        }
        assert(top <= 126);
    }
    return best;
}

bool TriangleBvh::anyHit(const BvhRay& ray) const {
    if (m_nodes.empty()) return false;
    const glm::dvec3 invDir = 1.0 / ray.direction;
    uint32_t stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& node = m_nodes[stack[--top]];
        if (hitBox(node.lo, node.hi, ray.origin, invDir, ray.tMin, ray.tMax) == kInf) continue;
        if (node.count > 0) {
            for (uint32_t i = node.first; i < node.first + node.count; ++i) {
                const Tri& tri = m_tris[i];
                double t, u, v;
                if (intersectTriangle(ray.origin, ray.direction, ray.tMin, ray.tMax, tri.p0, tri.p1, tri.p2, t, u, v))
                    return true;
            }
            continue;
        }
        stack[top++] = node.first;
        stack[top++] = static_cast<uint32_t>(&node - m_nodes.data()) + 1;
        assert(top <= 126);
    }
    return false;
}

}  // namespace sss::detail
