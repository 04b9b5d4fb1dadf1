#include "sss/procedural.h"

#include "util/format.h"

#include "sss/error.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace sss {
namespace {

constexpr double kPi = 3.14159265358979323846;

template <typename T>
std::string str(const T& v) {
    return detail::formatNumber(v);
}

void checkRange(const char* what, int v, int lo, int hi) {
    if (v < lo || v > hi)
        throw Error(ErrorKind::InvalidArgument, std::string(what) + " must be in [" + std::to_string(lo) + ", " +
                                                    std::to_string(hi) + "], got " + std::to_string(v));
}

void checkPositive(const char* what, float v) {
    if (!std::isfinite(v) || v <= 0.0f)
        throw Error(ErrorKind::InvalidArgument, std::string(what) + " must be finite and > 0, got " + str(v));
}

struct Blob {
    glm::dvec3 centre;  // in [0,1]^3, fractions of the side
    double sigma;       // fraction of the side
    double amplitude;   // peak density in [0,1]
};

// Rasterizes `background(p)` plus Gaussian blobs into an n^3 uint8 volume, slice by slice so
// memory stays O(n^2) and each blob only touches voxels within 4 sigma (< 0.1 of one level).
Volume rasterize(int n, const std::vector<Blob>& blobs, const std::function<double(glm::dvec3)>& background) {
    const std::size_t side = static_cast<std::size_t>(n);
    std::vector<uint8_t> bytes(side * side * side);
    std::vector<double> slice(side * side);
    auto centreOf = [n](int i) { return (i + 0.5) / n; };  // voxel centres, not corners
    for (int z = 0; z < n; ++z) {
        const double pz = centreOf(z);
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                slice[static_cast<std::size_t>(y) * side + static_cast<std::size_t>(x)] =
                    background ? background(glm::dvec3(centreOf(x), centreOf(y), pz)) : 0.0;
        for (const Blob& b : blobs) {
            const double cutoff = 4.0 * b.sigma;
            const double dz = pz - b.centre.z;
            if (std::abs(dz) > cutoff) continue;
            auto lo = [&](double c) { return std::max(0, static_cast<int>(std::floor((c - cutoff) * n))); };
            auto hi = [&](double c) { return std::min(n - 1, static_cast<int>(std::ceil((c + cutoff) * n))); };
            const double inv2s2 = 1.0 / (2.0 * b.sigma * b.sigma);
            for (int y = lo(b.centre.y); y <= hi(b.centre.y); ++y) {
                const double dy = centreOf(y) - b.centre.y;
                for (int x = lo(b.centre.x); x <= hi(b.centre.x); ++x) {
                    const double dx = centreOf(x) - b.centre.x;
                    slice[static_cast<std::size_t>(y) * side + static_cast<std::size_t>(x)] +=
                        b.amplitude * std::exp(-(dx * dx + dy * dy + dz * dz) * inv2s2);
                }
            }
        }
        uint8_t* out = bytes.data() + static_cast<std::size_t>(z) * side * side;
        for (std::size_t i = 0; i < slice.size(); ++i)
            out[i] = static_cast<uint8_t>(std::lround(std::clamp(slice[i], 0.0, 1.0) * 255.0));
    }
    return Volume::fromData(glm::ivec3(n), VoxelType::UInt8, std::move(bytes));
}

double smoothstep(double e0, double e1, double x) {
    const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

}  // namespace

Mesh makeUvSphere(int segments, int rings, float radius) {
    checkRange("makeUvSphere: segments", segments, 3, 4096);
    checkRange("makeUvSphere: rings", rings, 2, 4096);
    checkPositive("makeUvSphere: radius", radius);
    std::vector<glm::vec3> normals;
    normals.reserve(static_cast<std::size_t>(2 + (rings - 1) * segments));
    normals.emplace_back(0.0f, 1.0f, 0.0f);
    for (int i = 1; i < rings; ++i) {
        const double theta = kPi * i / rings;
        for (int j = 0; j < segments; ++j) {
            const double phi = 2.0 * kPi * j / segments;
            // z = -sin(theta) sin(phi) makes (theta, phi) a right-handed, outward parametrization.
            normals.emplace_back(glm::dvec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                                            -std::sin(theta) * std::sin(phi)));
        }
    }
    normals.emplace_back(0.0f, -1.0f, 0.0f);
    std::vector<glm::vec3> positions(normals.size());
    std::transform(normals.begin(), normals.end(), positions.begin(), [radius](glm::vec3 n) { return n * radius; });

    const uint32_t south = static_cast<uint32_t>(normals.size() - 1);
    auto vertex = [&](int ring, int seg) -> uint32_t {  // ring 0 and `rings` are the poles
        if (ring == 0) return 0;
        if (ring == rings) return south;
        return static_cast<uint32_t>(1 + (ring - 1) * segments + seg % segments);
    };
    std::vector<uint32_t> indices;
    indices.reserve(static_cast<std::size_t>(rings) * static_cast<std::size_t>(segments) * 6);
    for (int i = 0; i < rings; ++i) {
        for (int j = 0; j < segments; ++j) {
            const uint32_t t0 = vertex(i, j), t1 = vertex(i, j + 1);
            const uint32_t b0 = vertex(i + 1, j), b1 = vertex(i + 1, j + 1);
            // At the poles one of the two triangles is degenerate; it is kept on purpose so the
            // counts match the reference sphere (20x20 -> 800 triangles).
            indices.insert(indices.end(), {t0, b0, b1, t0, b1, t1});
        }
    }
    return Mesh::fromArrays(std::move(positions), std::move(indices), std::move(normals), "uv-sphere");
}

Mesh makeFolds(int segments, int rings) {
    checkRange("makeFolds: segments", segments, 3, 4096);
    checkRange("makeFolds: rings", rings, 2, 4096);
    const Mesh sphere = makeUvSphere(segments, rings);
    std::vector<glm::vec3> positions(sphere.positions().begin(), sphere.positions().end());
    for (glm::vec3& p : positions) {
        const glm::dvec3 d = glm::normalize(glm::dvec3(p));
        const double theta = std::acos(std::clamp(d.y, -1.0, 1.0));
        const double phi = std::atan2(-d.z, d.x);
        const double sin2 = std::sin(theta) * std::sin(theta);  // no dimples at the poles
        const double groove = sin2 * std::pow(std::max(0.0, std::cos(8.0 * theta)), 4.0);
        const double fold = sin2 * std::pow(0.5 + 0.5 * std::cos(7.0 * phi), 6.0);
        p = glm::vec3(d * (1.0 - 0.3 * groove - 0.2 * fold));
    }
    std::vector<uint32_t> indices(sphere.indices().begin(), sphere.indices().end());
    return Mesh::fromArrays(std::move(positions), std::move(indices), {}, "folds");
}

Mesh makeTorus(float majorRadius, float minorRadius, int majorSegments, int minorSegments) {
    checkPositive("makeTorus: majorRadius", majorRadius);
    checkPositive("makeTorus: minorRadius", minorRadius);
    if (!(minorRadius < majorRadius))
        throw Error(ErrorKind::InvalidArgument, "makeTorus: minorRadius must be < majorRadius, got minorRadius " +
                                                    str(minorRadius) + ", majorRadius " + str(majorRadius));
    checkRange("makeTorus: majorSegments", majorSegments, 3, 4096);
    checkRange("makeTorus: minorSegments", minorSegments, 3, 4096);
    std::vector<glm::vec3> positions, normals;
    for (int i = 0; i < majorSegments; ++i) {
        const double u = 2.0 * kPi * i / majorSegments;
        const glm::dvec3 radial(std::cos(u), 0.0, std::sin(u));
        for (int j = 0; j < minorSegments; ++j) {
            const double v = 2.0 * kPi * j / minorSegments;
            const glm::dvec3 n = std::cos(v) * radial + std::sin(v) * glm::dvec3(0.0, 1.0, 0.0);
            normals.emplace_back(n);
            positions.emplace_back(double(majorRadius) * radial + double(minorRadius) * n);
        }
    }
    auto vertex = [&](int i, int j) {
        return static_cast<uint32_t>((i % majorSegments) * minorSegments + (j % minorSegments));
    };
    std::vector<uint32_t> indices;
    for (int i = 0; i < majorSegments; ++i)
        for (int j = 0; j < minorSegments; ++j) {
            const uint32_t a = vertex(i, j), b = vertex(i, j + 1), c = vertex(i + 1, j + 1), d = vertex(i + 1, j);
            indices.insert(indices.end(), {a, b, c, a, c, d});
        }
    return Mesh::fromArrays(std::move(positions), std::move(indices), std::move(normals), "torus");
}

Mesh makeSlab(glm::vec3 size) {
    checkPositive("makeSlab: size.x", size.x);
    checkPositive("makeSlab: size.y", size.y);
    checkPositive("makeSlab: size.z", size.z);
    const glm::vec3 h = 0.5f * size;
    // Per face: outward normal n and tangents u, v with cross(u, v) == n, so the corners
    // (-u-v, +u-v, +u+v, -u+v) run counter-clockwise seen from outside.
    struct Face { glm::vec3 n, u, v; };
    const Face faces[6] = {
        {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}},  {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
        {{0, 1, 0}, {0, 0, 1}, {1, 0, 0}},  {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
        {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},  {{0, 0, -1}, {0, 1, 0}, {1, 0, 0}},
    };
    std::vector<glm::vec3> positions, normals;
    std::vector<glm::vec2> texcoords;
    std::vector<uint32_t> indices;
    for (const Face& f : faces) {
        const uint32_t base = static_cast<uint32_t>(positions.size());
        const glm::vec3 c = f.n * h, du = f.u * h, dv = f.v * h;
        for (glm::vec3 corner : {c - du - dv, c + du - dv, c + du + dv, c - du + dv}) {
            positions.push_back(corner);
            normals.push_back(f.n);
            texcoords.push_back(glm::vec2(corner.x / size.x, corner.y / size.y) + 0.5f);
        }
        indices.insert(indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
    return Mesh::fromArrays(std::move(positions), std::move(indices), std::move(normals), "slab", std::move(texcoords));
}

CornellBox makeCornellBox(const Bounds& content) {
    if (content.empty()) throw Error(ErrorKind::InvalidArgument, "makeCornellBox: the content bounds are empty");
    const glm::vec3 size = content.size();
    const float half = 0.8f * std::max({size.x, size.y, size.z, 1e-6f});
    const glm::vec3 c = content.center();
    // Each wall: a quad with its inward normal, corners counter-clockwise seen from inside.
    auto quad = [&](std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals, std::vector<uint32_t>& indices,
                    glm::vec3 n, glm::vec3 u, glm::vec3 v) {
        const uint32_t base = static_cast<uint32_t>(positions.size());
        const glm::vec3 centre = c - n * half;
        for (glm::vec3 corner : {centre - u * half - v * half, centre + u * half - v * half,
                                 centre + u * half + v * half, centre - u * half + v * half}) {
            positions.push_back(corner);
            normals.push_back(n);
        }
        indices.insert(indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    };
    std::vector<glm::vec3> wp, wn, rp, rn, gp, gn;
    std::vector<uint32_t> wi, ri, gi;
    quad(wp, wn, wi, {0, 1, 0}, {0, 0, 1}, {1, 0, 0});    // floor
    quad(wp, wn, wi, {0, -1, 0}, {1, 0, 0}, {0, 0, 1});   // ceiling
    quad(wp, wn, wi, {0, 0, 1}, {1, 0, 0}, {0, 1, 0});    // back wall
    quad(rp, rn, ri, {1, 0, 0}, {0, 1, 0}, {0, 0, 1});    // left wall (red), faces +x
    quad(gp, gn, gi, {-1, 0, 0}, {0, 0, 1}, {0, 1, 0});   // right wall (green), faces -x
    CornellBox box{Mesh::fromArrays(std::move(wp), std::move(wi), std::move(wn), "cornell box white walls"),
                   Mesh::fromArrays(std::move(rp), std::move(ri), std::move(rn), "cornell box red wall"),
                   Mesh::fromArrays(std::move(gp), std::move(gi), std::move(gn), "cornell box green wall")};
    box.bounds.extend(c - glm::vec3(half));
    box.bounds.extend(c + glm::vec3(half));
    return box;
}

Volume makeBlobsVolume(int n) {
    checkRange("makeBlobsVolume: n", n, 2, 1024);
    const std::vector<Blob> blobs = {
        {{0.36, 0.42, 0.50}, 0.13, 0.9},
        {{0.68, 0.62, 0.44}, 0.08, 1.0},
        {{0.52, 0.72, 0.70}, 0.05, 0.6},
        {{0.58, 0.28, 0.30}, 0.10, 0.4},
    };
    return rasterize(n, blobs, nullptr);
}

Volume makeShellVolume(int n, float outerRadius, float thickness) {
    checkRange("makeShellVolume: n", n, 2, 1024);
    if (!std::isfinite(outerRadius) || outerRadius <= 0.0f || outerRadius > 0.5f)
        throw Error(ErrorKind::InvalidArgument,
                    "makeShellVolume: outerRadius must be in (0, 0.5] (a fraction of the side), got " + str(outerRadius));
    if (!std::isfinite(thickness) || thickness <= 0.0f || thickness > outerRadius)
        throw Error(ErrorKind::InvalidArgument, "makeShellVolume: thickness must be in (0, outerRadius = " +
                                                    str(outerRadius) + "], got " + str(thickness));
    const double outer = outerRadius, inner = double(outerRadius) - double(thickness);
    const double edge = 1.0 / n;  // soft over about one voxel on each side of each surface
    return rasterize(n, {}, [=](glm::dvec3 p) {
        const double d = glm::length(p - glm::dvec3(0.5));
        return smoothstep(inner - edge, inner + edge, d) * (1.0 - smoothstep(outer - edge, outer + edge, d));
    });
}

Volume makeBuckyLikeVolume(int n) {
    checkRange("makeBuckyLikeVolume: n", n, 2, 1024);
    // Truncated icosahedron (the C60 cage): cyclic permutations of (0, ±1, ±3φ),
    // (±1, ±(2+φ), ±2φ), (±φ, ±2, ±(2φ+1)); all 60 lie at radius sqrt(9φ² + 1).
    const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
    const double circumradius = std::sqrt(9.0 * phi * phi + 1.0);
    const double cageRadius = 0.35;
    const glm::dvec3 bases[3] = {{0.0, 1.0, 3.0 * phi}, {1.0, 2.0 + phi, 2.0 * phi}, {phi, 2.0, 2.0 * phi + 1.0}};
    std::vector<Blob> blobs;
    for (const glm::dvec3& b : bases)
        for (int perm = 0; perm < 3; ++perm) {
            const glm::dvec3 p = perm == 0 ? b : perm == 1 ? glm::dvec3(b.y, b.z, b.x) : glm::dvec3(b.z, b.x, b.y);
            for (int signs = 0; signs < 8; ++signs) {
                glm::dvec3 q = p;
                bool duplicate = false;
                for (int k = 0; k < 3; ++k)
                    if (signs & (1 << k)) {
                        if (q[k] == 0.0) duplicate = true;  // -0 is the same vertex as +0
                        q[k] = -q[k];
                    }
                if (!duplicate) blobs.push_back({glm::dvec3(0.5) + q * (cageRadius / circumradius), 0.03, 1.0});
            }
        }
    // Faint shell of "bond" density along the cage, like the real data's low-valued halo.
    return rasterize(n, blobs, [=](glm::dvec3 p) {
        const double d = glm::length(p - glm::dvec3(0.5)) - cageRadius;
        return 0.15 * std::exp(-d * d / (2.0 * 0.05 * 0.05));
    });
}

}  // namespace sss
