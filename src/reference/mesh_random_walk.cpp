// Physical ground truth inside a triangle mesh: adjoint random walks from the eye with
// next-event estimation through the refracting boundary, in double (see sss/random_walk.h).
#include "sss/random_walk.h"

#include "reference/bvh.h"
#include "reference/cpu_lights.h"
#include "util/parallel.h"
#include "reference/walk_sampling.h"
#include "reference/world_mesh.h"

#include "sss/error.h"
#include "util/format.h"

#include <glm/common.hpp>
#include <glm/ext/vector_int3.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace sss {
namespace {

using detail::formatNumber;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kRouletteWeight = 0.25;  // path weight below which Russian roulette starts
constexpr int kNeeQueries = 4;            // ray queries of the entry-point fixed-point iteration
constexpr double kNeeConverged = 1e-9;    // |change of d| below which the iteration stops
constexpr int kMaxGridCells = 1 << 26;
constexpr double kExactRing = 3.0;  // cells this close (in cells) to the surface get exact distances

[[noreturn]] void invalid(const std::string& message) {
    throw Error(ErrorKind::InvalidArgument, "renderMeshRandomWalk: " + message);
}

void validateOptions(const MeshRandomWalkOptions& o) {
    if (o.pathsPerPixel < 1)
        invalid("MeshRandomWalkOptions::pathsPerPixel must be >= 1, got " + formatNumber(o.pathsPerPixel));
    if (o.threads < 0) invalid("MeshRandomWalkOptions::threads must be >= 0, got " + formatNumber(o.threads));
    if (o.maxEvents < 1) invalid("MeshRandomWalkOptions::maxEvents must be >= 1, got " + formatNumber(o.maxEvents));
    if (!std::isfinite(o.millimetresPerUnit) || o.millimetresPerUnit <= 0.0)
        invalid("MeshRandomWalkOptions::millimetresPerUnit must be finite and > 0, got " +
                formatNumber(o.millimetresPerUnit));
    if (!std::isfinite(o.background.x) || !std::isfinite(o.background.y) || !std::isfinite(o.background.z))
        invalid("MeshRandomWalkOptions::background must be finite");
    if (o.distanceGridCells < 0 || o.distanceGridCells > kMaxGridCells)
        invalid("MeshRandomWalkOptions::distanceGridCells must be in [0, " + formatNumber(kMaxGridCells) + "], got " +
                formatNumber(o.distanceGridCells));
}

// A light reduced to what the estimator needs.
// World-space triangle data.
struct TriInfo {
    glm::dvec3 p0, p1, p2;
    glm::dvec3 n0, n1, n2;  // transformed (not normalised) vertex normals
    glm::dvec3 ng;          // unit geometric normal, front side (0 if degenerate)
};

// Squared distance from q to the triangle (a, b, c): the closest point by the Voronoi region of
// q (vertex, edge or face), in barycentric terms.
double distanceSquaredToTriangle(const glm::dvec3& q, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    const glm::dvec3 ab = b - a, ac = c - a, aq = q - a;
    const double d1 = glm::dot(ab, aq), d2 = glm::dot(ac, aq);
    auto d2to = [&](const glm::dvec3& p) { return glm::dot(q - p, q - p); };
    if (d1 <= 0.0 && d2 <= 0.0) return d2to(a);
    const glm::dvec3 bq = q - b;
    const double d3 = glm::dot(ab, bq), d4 = glm::dot(ac, bq);
    if (d3 >= 0.0 && d4 <= d3) return d2to(b);
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return d2to(a + (d1 / (d1 - d3)) * ab);
    const glm::dvec3 cq = q - c;
    const double d5 = glm::dot(ab, cq), d6 = glm::dot(ac, cq);
    if (d6 >= 0.0 && d5 <= d6) return d2to(c);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return d2to(a + (d2 / (d2 - d6)) * ac);
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) return d2to(b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b));
    const double sum = va + vb + vc;
    if (!(sum > 0.0)) {  // degenerate triangle: its edges
        auto segment = [&](const glm::dvec3& p, const glm::dvec3& r) {
            const glm::dvec3 e = r - p;
            const double ee = glm::dot(e, e);
            const double t = ee > 0.0 ? std::clamp(glm::dot(q - p, e) / ee, 0.0, 1.0) : 0.0;
            return d2to(p + t * e);
        };
        return std::min({segment(a, b), segment(b, c), segment(c, a)});
    }
    return d2to(a + (vb / sum) * ab + (vc / sum) * ac);
}

// 1D squared Euclidean distance transform of f (Felzenszwalb and Huttenlocher's lower envelope
// of parabolas), in place; `v`, `z` are scratch.
void distanceTransform1d(std::vector<double>& f, std::vector<int>& v, std::vector<double>& z, std::vector<double>& out) {
    const int n = static_cast<int>(f.size());
    v.assign(n, 0);
    z.assign(n + 1, 0.0);
    out.assign(n, 0.0);
    int k = 0;
    int first = -1;
    for (int q = 0; q < n; ++q)
        if (f[q] < kInf) {
            first = q;
            break;
        }
    if (first < 0) return;  // all infinite: stays so (out is overwritten below)
    v[0] = first;
    z[0] = -kInf;
    z[1] = kInf;
    for (int q = first + 1; q < n; ++q) {
        if (!(f[q] < kInf)) continue;
        double s;
        for (;;) {
            const int p = v[k];
            s = ((f[q] + double(q) * q) - (f[p] + double(p) * p)) / (2.0 * q - 2.0 * p);
            if (s <= z[k] && k > 0) {
                --k;
                continue;
            }
            break;
        }
        ++k;
        v[k] = q;
        z[k] = s;
        z[k + 1] = kInf;
    }
    k = 0;
    for (int q = 0; q < n; ++q) {
        while (z[k + 1] < q) ++k;
        const double d = q - v[k];
        out[q] = d * d + f[v[k]];
    }
    f.swap(out);
}

// Lower bounds on the distance from any point of a cell to the surface (see the header).
class DistanceGrid {
public:
    DistanceGrid() = default;

    DistanceGrid(const std::vector<TriInfo>& tris, const glm::dvec3& lo, const glm::dvec3& hi, int maxCells,
                 int threads) {
        const glm::dvec3 extent = hi - lo;
        const double longest = std::max({extent.x, extent.y, extent.z});
        if (!(longest > 0.0) || maxCells < 27) return;
        // Cubic cells, one spare layer on every side, at most maxCells in all.
        double h = std::cbrt(std::max(extent.x, 1e-3 * longest) * std::max(extent.y, 1e-3 * longest) *
                             std::max(extent.z, 1e-3 * longest) / maxCells);
        for (;;) {
            for (int a = 0; a < 3; ++a) m_n[a] = static_cast<int>(std::ceil(extent[a] / h)) + 2;
            if (double(m_n[0]) * m_n[1] * m_n[2] <= maxCells) break;
            h *= 1.02;
        }
        m_h = h;
        m_origin = lo - glm::dvec3(h);
        const size_t cells = size_t(m_n[0]) * m_n[1] * m_n[2];

        // Buckets: each triangle in every cell of its bounding box whose centre is within half a
        // cell diagonal of its plane (a superset of the cells it meets).
        const double halfDiagonal = 0.5 * std::sqrt(3.0) * h;
        std::vector<uint32_t> count(cells + 1, 0);
        auto forCells = [&](const TriInfo& t, auto&& f) {
            const glm::dvec3 tlo = glm::min(t.p0, glm::min(t.p1, t.p2)), thi = glm::max(t.p0, glm::max(t.p1, t.p2));
            glm::ivec3 c0, c1;
            for (int a = 0; a < 3; ++a) {
                c0[a] = std::clamp(static_cast<int>(std::floor((tlo[a] - m_origin[a]) / h - 1e-9)), 0, m_n[a] - 1);
                c1[a] = std::clamp(static_cast<int>(std::floor((thi[a] - m_origin[a]) / h + 1e-9)), 0, m_n[a] - 1);
            }
            glm::dvec3 normal = glm::cross(t.p1 - t.p0, t.p2 - t.p0);
            const double len = glm::length(normal);
            normal = len > 0.0 ? normal / len : glm::dvec3(0.0);
            for (int z = c0.z; z <= c1.z; ++z)
                for (int y = c0.y; y <= c1.y; ++y)
                    for (int x = c0.x; x <= c1.x; ++x) {
                        if (len > 0.0 && std::abs(glm::dot(centre(x, y, z) - t.p0, normal)) > halfDiagonal * 1.000001)
                            continue;
                        f(index(x, y, z));
                    }
        };
        for (const TriInfo& t : tris) forCells(t, [&](size_t i) { ++count[i + 1]; });
        for (size_t i = 0; i < cells; ++i) count[i + 1] += count[i];
        std::vector<uint32_t> members(count[cells]);
        {
            std::vector<uint32_t> fill(count.begin(), count.end() - 1);
            for (uint32_t id = 0; id < tris.size(); ++id) forCells(tris[id], [&](size_t i) { members[fill[i]++] = id; });
        }

        // Exact distance transform (in cells, squared) of the cells that hold a triangle.
        std::vector<double> d2(cells);
        for (size_t i = 0; i < cells; ++i) d2[i] = count[i + 1] > count[i] ? 0.0 : kInf;
        {
            std::vector<double> line, out, z;
            std::vector<int> v;
            for (int axis = 0; axis < 3; ++axis) {
                const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
                line.resize(m_n[axis]);
                for (int j = 0; j < m_n[a2]; ++j)
                    for (int i = 0; i < m_n[a1]; ++i) {
                        glm::ivec3 c(0);
                        c[a1] = i;
                        c[a2] = j;
                        for (int k = 0; k < m_n[axis]; ++k) {
                            c[axis] = k;
                            line[k] = d2[index(c.x, c.y, c.z)];
                        }
                        distanceTransform1d(line, v, z, out);
                        for (int k = 0; k < m_n[axis]; ++k) {
                            c[axis] = k;
                            d2[index(c.x, c.y, c.z)] = line[k];
                        }
                    }
            }
        }

        // Bounds: near the surface the exact distance of the centre minus half a diagonal,
        // farther the transform's centre-to-centre distance minus a whole diagonal (both boxes).
        m_bound.assign(cells, 0.0f);
        const double shrink = 1.0 - 1e-6;   // float rounding and ray-query tolerance stay inside
        const double slack = 1e-9 * longest;
        struct Scratch {
            std::vector<uint32_t> stamp;  // per triangle: the last query that measured it
            uint32_t query = 0;
        };
        detail::parallelFor(
            threads, m_n[2], [&] { return Scratch{std::vector<uint32_t>(tris.size(), 0u), 0u}; },
            [&](Scratch& scratch, std::int64_t zz) {
                const int z = static_cast<int>(zz);
                for (int y = 0; y < m_n[1]; ++y)
                    for (int x = 0; x < m_n[0]; ++x) {
                        const size_t i = index(x, y, z);
                        const double cellsAway = std::sqrt(d2[i]);
                        double bound;
                        if (cellsAway <= kExactRing) {
                            if (++scratch.query == 0) {  // wrapped: forget every stamp
                                std::fill(scratch.stamp.begin(), scratch.stamp.end(), 0u);
                                scratch.query = 1;
                            }
                            bound = std::sqrt(nearestSquared(x, y, z, tris, count, members, scratch.stamp,
                                                             scratch.query)) -
                                    halfDiagonal;
                        } else {
                            bound = h * (cellsAway - std::sqrt(3.0));
                        }
                        bound = bound * shrink - slack;
                        m_bound[i] = bound > 0.0 ? static_cast<float>(bound) * float(shrink) : 0.0f;
                    }
            },
            [](const Scratch&) {});
    }

    bool empty() const { return m_bound.empty(); }
    double cellSize() const { return m_h; }

    // A lower bound on the distance from p to the surface (0 outside the grid).
    double bound(const glm::dvec3& p) const {
        if (m_bound.empty()) return 0.0;
        const glm::dvec3 f = (p - m_origin) / m_h;
        if (!(f.x >= 0.0 && f.y >= 0.0 && f.z >= 0.0 && f.x < m_n[0] && f.y < m_n[1] && f.z < m_n[2])) return 0.0;
        return m_bound[index(static_cast<int>(f.x), static_cast<int>(f.y), static_cast<int>(f.z))];
    }

private:
    size_t index(int x, int y, int z) const { return (size_t(z) * m_n[1] + y) * m_n[0] + x; }
    glm::dvec3 centre(int x, int y, int z) const { return m_origin + m_h * (glm::dvec3(x, y, z) + 0.5); }

    // Squared distance from a cell's centre to the nearest triangle: rings of cells outward
    // until no unvisited cell can hold anything nearer (a cell r rings away is at least
    // (r - 1/2) cells from the centre).
    double nearestSquared(int x, int y, int z, const std::vector<TriInfo>& tris, const std::vector<uint32_t>& count,
                          const std::vector<uint32_t>& members, std::vector<uint32_t>& stamp, uint32_t query) const {
        const glm::dvec3 c = centre(x, y, z);
        double best = kInf;
        const int maxRing = std::max({m_n[0], m_n[1], m_n[2]});
        for (int r = 0; r <= maxRing; ++r) {
            const double reach = (r - 0.5) * m_h;
            if (r > 0 && best <= reach * reach) break;
            for (int k = z - r; k <= z + r; ++k) {
                if (k < 0 || k >= m_n[2]) continue;
                for (int j = y - r; j <= y + r; ++j) {
                    if (j < 0 || j >= m_n[1]) continue;
                    const bool faceKJ = k == z - r || k == z + r || j == y - r || j == y + r;
                    for (int i = x - r; i <= x + r; i += (faceKJ ? 1 : std::max(1, 2 * r))) {
                        if (i < 0 || i >= m_n[0]) continue;
                        const size_t cell = index(i, j, k);
                        for (uint32_t m = count[cell]; m < count[cell + 1]; ++m) {
                            const uint32_t id = members[m];
                            if (stamp[id] == query) continue;
                            stamp[id] = query;
                            best = std::min(best, distanceSquaredToTriangle(c, tris[id].p0, tris[id].p1, tris[id].p2));
                        }
                    }
                }
            }
        }
        return best;
    }

    glm::dvec3 m_origin{0.0};
    double m_h = 0.0;
    int m_n[3] = {0, 0, 0};
    std::vector<float> m_bound;
};

// Per-channel medium in scene units.
struct Channel {
    double sigmaT = 0.0;
    double albedo = 0.0;
    int index = 0;
};

// A surface point met by a ray: the geometric and shading normals, both turned to the side the
// ray came from... or leaves to; see Renderer::surface().
struct Surface {
    glm::dvec3 ng{0.0};  // unit geometric normal
    glm::dvec3 n{0.0};   // unit shading normal on the same side
};

// Refraction of the light arriving from unit direction w (pointing away from the surface, to
// the side of the unit normal n, cos = n . w > 0) into a medium of relative index eta: the
// propagation direction inside, or nullopt under total internal reflection (eta < 1).
std::optional<glm::dvec3> refractIn(const glm::dvec3& w, const glm::dvec3& n, double cosOut, double eta) {
    const double r = 1.0 / eta;
    const double sin2In = r * r * (1.0 - cosOut * cosOut);
    if (sin2In >= 1.0) return std::nullopt;
    const double cosIn = std::sqrt(1.0 - sin2In);
    return glm::normalize(-r * w + (r * cosOut - cosIn) * n);
}

// Where the beam of a light entered last time: the first guess of the next entry point's
// normal, and its triangle (hitting it again ends the fixed-point iteration).
struct EntryGuess {
    glm::dvec3 normal{0.0};
    uint32_t triangle = std::numeric_limits<uint32_t>::max();
};

struct Stats {
    std::int64_t paths = 0, events = 0, queries = 0, nee = 0, truncated = 0, escaped = 0;
    void add(const Stats& o) {
        paths += o.paths;
        events += o.events;
        queries += o.queries;
        nee += o.nee;
        truncated += o.truncated;
        escaped += o.escaped;
    }
};

struct PixelResult {
    bool covered = false;
    glm::dvec3 mean{0.0}, standardError{0.0}, singleMean{0.0}, singleStandardError{0.0};
};

class Renderer {
public:
    Renderer(const Mesh& mesh, const glm::mat4& model, const ScatteringMaterial& material,
             const std::vector<Light>& lights, const Camera& camera, int width, int height,
             const MeshRandomWalkOptions& options)
        : m_options(options), m_width(width), m_height(height), m_g(material.g), m_eta(material.eta) {
        detail::WorldMesh world = detail::toWorldMesh(mesh, model, "renderMeshRandomWalk");
        m_offset = 1e-7 * world.sceneSize;
        m_lo = world.lo - glm::dvec3(4.0 * m_offset);
        m_hi = world.hi + glm::dvec3(4.0 * m_offset);

        for (int c = 0; c < 3; ++c) {
            m_channels[c].index = c;
            m_channels[c].sigmaT = (material.sigmaA[c] + material.sigmaS[c]) * options.millimetresPerUnit;
            m_channels[c].albedo = material.sigmaS[c] / (material.sigmaA[c] + material.sigmaS[c]);
        }

        m_lights = detail::prepareCpuLights(lights, "renderMeshRandomWalk");

        const auto& idx = mesh.indices();
        m_tris.resize(mesh.triangleCount());
        double area = 0.0;
        for (size_t t = 0; t < m_tris.size(); ++t) {
            TriInfo& tri = m_tris[t];
            tri.p0 = world.positions[idx[3 * t]];
            tri.p1 = world.positions[idx[3 * t + 1]];
            tri.p2 = world.positions[idx[3 * t + 2]];
            tri.n0 = world.normals[idx[3 * t]];
            tri.n1 = world.normals[idx[3 * t + 1]];
            tri.n2 = world.normals[idx[3 * t + 2]];
            const glm::dvec3 cr = glm::cross(tri.p1 - tri.p0, tri.p2 - tri.p0);
            const double len = glm::length(cr);
            area += 0.5 * len;
            tri.ng = len > 0.0 ? world.side * cr / len : glm::dvec3(0.0);
        }
        if (!(area > 0.0)) invalid("the mesh \"" + mesh.name() + "\" has zero surface area");

        m_bvh.emplace(std::move(world.positions), std::vector<uint32_t>(idx.begin(), idx.end()));
        if (options.distanceGridCells > 0)
            m_grid = DistanceGrid(m_tris, m_lo, m_hi, options.distanceGridCells, options.threads);
        m_neeRoulette = options.neeRoulette && !m_grid.empty();

        const glm::dmat4 viewProjection =
            glm::dmat4(camera.projection(float(width) / float(height))) * glm::dmat4(camera.view());
        m_inverseViewProjection = glm::inverse(viewProjection);
    }

    MeshRandomWalkResult run() {
        const size_t count = static_cast<size_t>(m_width) * m_height;
        std::vector<PixelResult> pixels(count);
        Stats stats;
        detail::parallelFor(
            m_options.threads, static_cast<std::int64_t>(count), [] { return Worker{}; },
            [&](Worker& worker, std::int64_t i) {
                pixels[static_cast<size_t>(i)] =
                    renderPixel(static_cast<int>(i % m_width), static_cast<int>(i / m_width), worker);
            },
            [&](const Worker& worker) { stats.add(worker.stats); });

        MeshRandomWalkResult result;
        result.image = Image(m_width, m_height);
        result.standardError = Image(m_width, m_height);
        result.singleScattering = Image(m_width, m_height);
        result.singleStandardError = Image(m_width, m_height);
        double sumErr2 = 0.0, sumMean2 = 0.0;
        const float paths = static_cast<float>(m_options.pathsPerPixel);
        for (int y = 0; y < m_height; ++y)
            for (int x = 0; x < m_width; ++x) {
                const PixelResult& p = pixels[static_cast<size_t>(y) * m_width + x];
                if (!p.covered) {
                    result.image.at(x, y) = glm::vec4(glm::vec3(m_options.background), 0.0f);
                    continue;
                }
                ++result.coveredPixels;
                result.image.at(x, y) = glm::vec4(glm::vec3(p.mean), 1.0f);
                result.standardError.at(x, y) = glm::vec4(glm::vec3(p.standardError), paths);
                result.singleScattering.at(x, y) = glm::vec4(glm::vec3(p.singleMean), 1.0f);
                result.singleStandardError.at(x, y) = glm::vec4(glm::vec3(p.singleStandardError), paths);
                for (int c = 0; c < 3; ++c) {
                    sumErr2 += p.standardError[c] * p.standardError[c];
                    sumMean2 += p.mean[c] * p.mean[c];
                }
            }
        result.relativeRmseEstimate = sumMean2 > 0.0 ? std::sqrt(sumErr2 / sumMean2) : 0.0;
        result.meanPathsPerPixel = result.coveredPixels ? 3.0 * m_options.pathsPerPixel : 0.0;
        if (stats.paths > 0) {
            const double n = static_cast<double>(stats.paths);
            result.meanEventsPerPath = static_cast<double>(stats.events) / n;
            result.meanRayQueriesPerPath = static_cast<double>(stats.queries) / n;
            result.meanNextEventsPerPath = static_cast<double>(stats.nee) / n;
        }
        result.paths = stats.paths;
        result.truncatedPaths = stats.truncated;
        result.escapedPaths = stats.escaped;
        result.distanceGridCellSize = m_grid.cellSize();
        return result;
    }

private:
    // The normals at a ray's hit, turned to the side of `towards` by the geometric normal
    // (the facing rule; see the header).
    Surface surface(const detail::BvhHit& hit, const glm::dvec3& towards) const {
        const TriInfo& tri = m_tris[hit.triangle];
        Surface s;
        s.ng = glm::dot(tri.ng, towards) < 0.0 ? -tri.ng : tri.ng;
        glm::dvec3 n = (1.0 - hit.u - hit.v) * tri.n0 + hit.u * tri.n1 + hit.v * tri.n2;
        const double len = glm::length(n);
        n = len > 1e-300 ? n / len : s.ng;
        s.n = glm::dot(n, s.ng) < 0.0 ? -n : n;
        return s;
    }

    struct Worker {
        Stats stats;
        std::vector<EntryGuess> guesses;  // per light
    };

    PixelResult renderPixel(int x, int y, Worker& worker) const {
        PixelResult result;
        const detail::BvhRay ray = detail::pixelRay(m_inverseViewProjection, x, y, m_width, m_height);
        const auto hit = m_bvh->closestHit(ray);
        if (!hit) return result;
        result.covered = true;
        if (m_lights.empty()) return result;

        const glm::dvec3 xo = ray.origin + hit->t * ray.direction;
        const glm::dvec3 wo = -glm::normalize(ray.direction);
        Surface s = surface(*hit, wo);
        double cosO = glm::dot(s.n, wo);
        std::optional<glm::dvec3> into = cosO > 0.0 ? refractIn(wo, s.n, cosO, m_eta) : std::nullopt;
        if (!into || glm::dot(*into, s.ng) >= 0.0) {  // the shading normal fails: the geometric one
            s.n = s.ng;
            cosO = glm::dot(s.ng, wo);
            into = cosO > 0.0 ? refractIn(wo, s.ng, cosO, m_eta) : std::nullopt;
        }
        if (!into || !(cosO > 0.0)) return result;  // total reflection (eta < 1) or grazing
        const double exitFactor = fresnelTransmittance(m_eta, cosO) / (m_eta * m_eta);
        if (!(exitFactor > 0.0)) return result;

        PathStart start{xo - m_offset * s.ng, *into, EntryGuess{s.n, hit->triangle}};
        const int n = m_options.pathsPerPixel;
        const std::uint64_t pixel = static_cast<std::uint64_t>(y) * m_width + x;
        for (const Channel& ch : m_channels) {
            bool lit = false;
            for (const detail::CpuLight& l : m_lights) lit = lit || l.radiance[ch.index] > 0.0;
            if (!lit || !(ch.albedo > 0.0)) continue;  // exactly black
            std::uint64_t key = detail::mix64(m_options.seed + 0x9e3779b97f4a7c15ull);
            key = detail::mix64(key ^ (pixel + 0x632be59bd9b4e019ull));
            key = detail::mix64(key ^ (static_cast<std::uint64_t>(ch.index) + 0x85157af5ull));
            detail::Xoshiro256 rng(key);
            double sum = 0.0, sum2 = 0.0, sumSingle = 0.0, sum2Single = 0.0;
            for (int i = 0; i < n; ++i) {
                double single = 0.0;
                const double v = path(start, ch, rng, single, worker);
                sum += v;
                sum2 += v * v;
                sumSingle += single;
                sum2Single += single * single;
            }
            auto standardError = [n](double s1, double s2) {
                if (n < 2) return 0.0;
                const double mean = s1 / n;
                return std::sqrt(std::max(0.0, s2 / n - mean * mean) / (n - 1));
            };
            result.mean[ch.index] = exitFactor * sum / n;
            result.standardError[ch.index] = exitFactor * standardError(sum, sum2);
            result.singleMean[ch.index] = exitFactor * sumSingle / n;
            result.singleStandardError[ch.index] = exitFactor * standardError(sumSingle, sum2Single);
        }
        return result;
    }

    struct PathStart {
        glm::dvec3 origin;  // x_o, just inside
        glm::dvec3 direction;
        EntryGuess entry;  // the outward shading normal at x_o and its triangle
    };

    bool insideBox(const glm::dvec3& p) const {
        return p.x >= m_lo.x && p.y >= m_lo.y && p.z >= m_lo.z && p.x <= m_hi.x && p.y <= m_hi.y && p.z <= m_hi.z;
    }

    // One adjoint path of channel `ch`: returns the sum of its weighted next-event terms (before
    // the exit factor T_o / eta^2); `single` gets the first collision's term.
    double path(const PathStart& start, const Channel& ch, detail::Xoshiro256& rng, double& single,
                Worker& worker) const {
        Stats& stats = worker.stats;
        std::vector<EntryGuess>& guesses = worker.guesses;
        guesses.assign(m_lights.size(), start.entry);
        glm::dvec3 p = start.origin, dir = start.direction;
        double weight = 1.0, total = 0.0;
        std::int64_t events = 0;
        ++stats.paths;
        for (;;) {
            const double s = -std::log(rng.openUniform()) / ch.sigmaT;
            if (s >= m_grid.bound(p)) {
                ++stats.queries;
                detail::BvhRay ray;
                ray.origin = p;
                ray.direction = dir;
                ray.tMax = s;
                if (const auto hit = m_bvh->closestHit(ray)) {
                    // At the boundary from inside: Fresnel reflection or exit.
                    const glm::dvec3 y = p + hit->t * dir;
                    Surface b = surface(*hit, dir);  // normals pointing out, along dir
                    double cosI = glm::dot(dir, b.n);
                    glm::dvec3 reflected = dir - (2.0 * cosI) * b.n;
                    if (!(cosI > 0.0) || glm::dot(reflected, b.ng) >= 0.0) {
                        b.n = b.ng;
                        cosI = glm::dot(dir, b.ng);
                        reflected = dir - (2.0 * cosI) * b.ng;
                    }
                    double cosT;
                    const double f = detail::fresnelReflectance(m_eta, cosI, cosT);
                    if (f >= 1.0 || rng.uniform() < f) {
                        dir = glm::normalize(reflected);
                        p = y - m_offset * b.ng;
                        guesses.assign(m_lights.size(), EntryGuess{b.n, hit->triangle});
                        continue;
                    }
                    break;  // leaves: no delta light lies along a sampled direction
                }
            }
            p += s * dir;
            if (!insideBox(p)) {  // through a hole of an open mesh
                ++stats.escaped;
                break;
            }
            if (events == m_options.maxEvents) {
                ++stats.truncated;
                break;
            }
            ++events;
            weight *= ch.albedo;
            const double e = nextEvent(p, dir, ch, rng, guesses, stats);
            total += weight * e;
            if (events == 1) single = weight * e;
            dir = detail::scatterHenyeyGreenstein(dir, m_g, rng);
            if (weight < kRouletteWeight) {
                if (rng.uniform() * kRouletteWeight >= weight) break;
                weight = kRouletteWeight;
            }
        }
        stats.events += events;
        return total;
    }

    // In-scattered radiance at p from the refracted, unscattered beams of all lights, towards
    // -dir (see the header), after the roulette by the distance bound.
    double nextEvent(const glm::dvec3& p, const glm::dvec3& dir, const Channel& ch, detail::Xoshiro256& rng,
                     std::vector<EntryGuess>& guesses, Stats& stats) const {
        double q = 1.0;
        if (m_neeRoulette) {
            q = std::exp(-ch.sigmaT * m_grid.bound(p));
            if (q < 1.0 && rng.uniform() >= q) return 0.0;
        }
        ++stats.nee;
        double sum = 0.0;
        for (size_t i = 0; i < m_lights.size(); ++i) {
            const double e = m_lights[i].radiance[ch.index];
            if (e > 0.0) sum += e * beam(p, dir, m_lights[i], ch, q, rng, guesses[i], stats);
        }
        return sum;
    }

    // p_HG * T cos_out / cos_in * exp(-sigma_t |p - x|) * falloff * V for one light, per unit
    // light radiance (the falloff includes a spot's cone), divided by the probability q that the
    // roulette by the distance bound let it be estimated. Updates `guess` to the entry point found.
    double beam(const glm::dvec3& p, const glm::dvec3& dir, const detail::CpuLight& l, const Channel& ch, double q,
                detail::Xoshiro256& rng, EntryGuess& guess, Stats& stats) const {
        glm::dvec3 wl = l.point ? glm::normalize(l.vector - p) : l.vector;
        const double cosGuess = glm::dot(guess.normal, wl);
        glm::dvec3 d = -wl;
        if (cosGuess > 0.0)
            if (const auto r = refractIn(wl, guess.normal, cosGuess, m_eta)) d = *r;
        uint32_t lastTriangle = guess.triangle;
        double distance = 0.0, cosOut = 0.0;
        glm::dvec3 x(0.0), ngOut(0.0);
        for (int it = 0; it < kNeeQueries; ++it) {
            detail::BvhRay ray;
            ray.origin = p;
            ray.direction = -d;
            ++stats.queries;
            const auto hit = m_bvh->closestHit(ray);
            if (!hit) return 0.0;  // open mesh: no entry point
            distance = hit->t;
            x = p - distance * d;
            if (it == 0 && m_neeRoulette) {
                // Second roulette, now that the distance to the entry point is known: go on with
                // probability exp(-sigma_t t) / q (<= 1, as t >= the bound), so that the beam is
                // followed with overall probability exp(-sigma_t t), its attenuation.
                const double q2 = std::min(1.0, std::exp(-ch.sigmaT * distance) / q);
                if (q2 < 1.0 && rng.uniform() >= q2) return 0.0;
                q *= q2;
            }
            Surface s = surface(*hit, -d);  // outward
            if (l.point) wl = glm::normalize(l.vector - x);
            cosOut = glm::dot(s.n, wl);
            std::optional<glm::dvec3> next = cosOut > 0.0 ? refractIn(wl, s.n, cosOut, m_eta) : std::nullopt;
            if (!next || glm::dot(*next, s.ng) >= 0.0) {
                s.n = s.ng;
                cosOut = glm::dot(s.ng, wl);
                next = cosOut > 0.0 ? refractIn(wl, s.ng, cosOut, m_eta) : std::nullopt;
            }
            if (!next) return 0.0;  // the light is behind this face (or totally reflected, eta < 1)
            ngOut = s.ng;
            guess = EntryGuess{s.n, hit->triangle};
            const bool converged = glm::length(*next - d) <= kNeeConverged || hit->triangle == lastTriangle;
            lastTriangle = hit->triangle;
            if (converged || it + 1 == kNeeQueries) break;
            d = *next;
        }
        const double t = fresnelTransmittance(m_eta, cosOut);
        if (!(t > 0.0)) return 0.0;
        const double cosIn = std::sqrt(std::max(0.0, 1.0 - (1.0 - cosOut * cosOut) / (m_eta * m_eta)));
        double value = detail::henyeyGreenstein(m_g, -glm::dot(d, dir)) * t * cosOut / cosIn *
                       std::exp(-ch.sigmaT * distance) / q;
        if (!(value > 0.0)) return 0.0;
        detail::BvhRay shadow;
        shadow.origin = x + m_offset * ngOut;
        if (l.point) {
            shadow.direction = l.vector - shadow.origin;  // tMax 1 stops at the light
            shadow.tMax = 1.0;
            value = value / glm::dot(l.vector - x, l.vector - x) * detail::emittedShare(l, x);
        } else {
            shadow.direction = wl;
        }
        ++stats.queries;
        return m_bvh->anyHit(shadow) ? 0.0 : value;
    }

    MeshRandomWalkOptions m_options;
    int m_width, m_height;
    double m_g, m_eta;
    std::array<Channel, 3> m_channels;
    std::vector<detail::CpuLight> m_lights;
    std::vector<TriInfo> m_tris;
    glm::dvec3 m_lo{0.0}, m_hi{0.0};  // bounding box, a little enlarged
    double m_offset = 0.0;
    std::optional<detail::TriangleBvh> m_bvh;
    DistanceGrid m_grid;
    bool m_neeRoulette = false;
    glm::dmat4 m_inverseViewProjection{1.0};
};

}  // namespace

MeshRandomWalkResult renderMeshRandomWalk(const Mesh& mesh, const glm::mat4& model, const ScatteringMaterial& material,
                                          const std::vector<Light>& lights, const Camera& camera, int width, int height,
                                          const MeshRandomWalkOptions& options) {
    if (width < 1 || height < 1 || width > kMaxImageSide || height > kMaxImageSide)
        invalid("image size must be in [1, " + std::to_string(kMaxImageSide) + "] on each side, got " +
                std::to_string(width) + " x " + std::to_string(height));
    validateOptions(options);
    material.validate();
    if (mesh.triangleCount() == 0) invalid("the mesh \"" + mesh.name() + "\" has no triangles");
    Renderer renderer(mesh, model, material, lights, camera, width, height, options);
    return renderer.run();
}

}  // namespace sss
