// CPU reference renderer for mesh subsurface scattering: Monte Carlo integration of the
// directional dipole over the lit surface with shadow rays, in double (see sss/mesh_reference.h).
#include "sss/mesh_reference.h"

#include "mesh/reflectance_table.h"
#include "reference/bvh.h"
#include "reference/cpu_lights.h"
#include "reference/world_mesh.h"
#include "util/parallel.h"
#include "sss/error.h"
#include "sss/materials.h"
#include "util/format.h"

#include <glm/common.hpp>
#include <glm/exponential.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <numbers>
#include <optional>
#include <string>
#include <thread>
#include <unordered_map>
#include <variant>

namespace sss {
namespace {

using detail::formatNumber;

constexpr double kUniformShare = 0.1;  // share of the uniform-area component of every pdf
constexpr int kMaxSubdivision = 32;    // sub-triangles per edge of a triangle near x_o
constexpr int kKernelTableSize = 512;
constexpr int kCheckInterval = 16;  // samples between convergence tests

[[noreturn]] void invalid(const std::string& message) {
    throw Error(ErrorKind::InvalidArgument, "renderMeshReference: " + message);
}

void validateOptions(const MeshReferenceOptions& o) {
    if (!std::isfinite(o.targetRelativeError) || o.targetRelativeError < 0.0 || o.targetRelativeError >= 1.0)
        invalid("MeshReferenceOptions::targetRelativeError must be in [0, 1), got " +
                formatNumber(o.targetRelativeError));
    if (!std::isfinite(o.absoluteError) || o.absoluteError < 0.0)
        invalid("MeshReferenceOptions::absoluteError must be finite and >= 0, got " + formatNumber(o.absoluteError));
    if (o.minSamples < 2) invalid("MeshReferenceOptions::minSamples must be >= 2, got " + formatNumber(o.minSamples));
    if (o.maxSamples < o.minSamples)
        invalid("MeshReferenceOptions::maxSamples must be >= minSamples (" + formatNumber(o.minSamples) + "), got " +
                formatNumber(o.maxSamples));
    if (!std::isfinite(o.background.x) || !std::isfinite(o.background.y) || !std::isfinite(o.background.z))
        invalid("MeshReferenceOptions::background must be finite");
    if (!std::isfinite(o.millimetresPerUnit) || o.millimetresPerUnit <= 0.0)
        invalid("MeshReferenceOptions::millimetresPerUnit must be finite and > 0, got " +
                formatNumber(o.millimetresPerUnit));
    if (o.threads < 0) invalid("MeshReferenceOptions::threads must be >= 0, got " + formatNumber(o.threads));
}

// splitmix64: a small, well-mixed generator; one independent stream per pixel.
struct Rng {
    uint64_t state;
    uint64_t next() {
        uint64_t z = (state += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)
};

uint64_t mix64(uint64_t z) {
    z = (z ^ (z >> 33)) * 0xff51afd7ed558ccdull;
    z = (z ^ (z >> 33)) * 0xc4ceb9fe1a85ec53ull;
    return z ^ (z >> 33);
}

// A light reduced to what the integrand needs.
// World-space triangle data.
struct TriInfo {
    glm::dvec3 p0, e1, e2;  // p1 = p0 + e1, p2 = p0 + e2
    glm::dvec3 n0, n1, n2;  // transformed (not normalised) vertex normals
    glm::dvec3 ng;          // unit geometric normal, front side (0 if degenerate)
    glm::dvec3 centroid;
    double area = 0.0;
    double radius = 0.0;   // largest distance from the centroid to a vertex
    double longest = 0.0;  // longest edge
    double light = 0.0;    // light factor (how much the lights see the vertex normals)
    glm::dvec2 uv0{0.0}, uv1{0.0}, uv2{0.0};  // texture coordinates (textured materials)
};

// A textured material's coefficients per surface point (sss::TexturedScattering), by the rule the
// GPU renderer follows (mesh/reflectance_table.h): x_o's own profile, times the geometric mean of
// the entry points' `gathered` weighted by the light they bring, over x_o's own `gathered`.
class TexturedSurface {
public:
    // `texelsPerUnit`: detail::meanTexelDensity of the mesh as placed.
    TexturedSurface(const TexturedScattering& material, const Image8& reflectance, ScatteringProfile profile,
                    double millimetresPerUnit, double texelsPerUnit)
        : m_material(material), m_profile(profile), m_millimetresPerUnit(millimetresPerUnit),
          m_texelsPerUnit(texelsPerUnit), m_reflectance(reflectance, true),
          m_table(detail::reflectanceTable(material.eta, profile)), m_mips(reflectance, m_table) {
        if (material.meanFreePathScale) m_pathScale.emplace(*material.meanFreePathScale, false);
    }

    glm::dvec3 reflectance(glm::dvec2 uv) const { return m_reflectance(uv); }

    DipoleConstants constantsAt(glm::dvec2 uv) const {
        const double scale = m_pathScale ? std::max((*m_pathScale)(uv).x, 1.0 / 255.0) : 1.0;
        const ScatteringMaterial m =
            materialFromReflectance(reflectance(uv), m_material.meanFreePath * scale, m_material.eta, m_profile);
        return deriveDipoleConstants(m, m_millimetresPerUnit, m_profile);
    }

    /// ln of what the point's material gathers under even light (detail::ReflectanceTable).
    glm::dvec3 logGathered(glm::dvec2 uv) const {
        const glm::dvec3 r = reflectance(uv);
        glm::dvec3 g;
        for (int c = 0; c < 3; ++c) g[c] = detail::invertReflectance(m_table, r[c]).gathered;
        return glm::log(glm::max(g, glm::dvec3(detail::kMinGathered)));
    }

    /// ln gathered of an entry point: level 0 of the chain, as the GPU's light buffer reads it
    /// (and cheaper per sample than inverting the reflectance).
    glm::dvec3 entryLogGathered(glm::dvec2 uv) const { return {m_mips(uv, 0.0, 0), m_mips(uv, 0.0, 1), m_mips(uv, 0.0, 2)}; }

    /// The texture's mean ln gathered around a point of transport coefficient `sigmaTr`.
    glm::dvec3 surroundingLogGathered(glm::dvec2 uv, const glm::dvec3& sigmaTr) const {
        glm::dvec3 mean(0.0);
        for (int c = 0; c < 3; ++c)
            for (double width : detail::kSurroundingWidths)
                mean[c] += 0.5 * m_mips(uv, detail::surroundingLevel(width / std::max(sigmaTr[c], 1e-12), m_texelsPerUnit), c);
        return mean;
    }

private:
    TexturedScattering m_material;
    ScatteringProfile m_profile;
    double m_millimetresPerUnit;
    double m_texelsPerUnit;
    detail::TextureSampler m_reflectance;
    const detail::ReflectanceTable& m_table;
    detail::LogGatheredMips m_mips;
    std::optional<detail::TextureSampler> m_pathScale;
};

// What the integrand needs of the exit point: its profile and, textured, its ln `gathered` and
// its surroundings' mean of it.
struct ExitPoint {
    glm::dvec3 x, n;
    const DipoleConstants& constants;
    glm::dvec3 logGathered{0.0};
    glm::dvec3 surroundingLog{0.0};
};

// The planar normal-incidence S_d profile, each channel normalised to unit integral, summed:
// the shape of the sampling density around x_o.
class Kernel {
public:
    Kernel(const DipoleConstants& c, double sceneSize) {
        const double dMin = std::min({c.D.x, c.D.y, c.D.z});
        m_rMin = 1e-3 * dMin;
        const double rMax = std::max(2.0 * sceneSize, 1e2 * m_rMin);
        m_logStep = std::log(rMax / m_rMin) / (kKernelTableSize - 1);
        std::array<std::vector<double>, 3> s;
        std::vector<double> r(kKernelTableSize);
        for (auto& v : s) v.resize(kKernelTableSize);
        const glm::dvec3 z(0.0, 0.0, 1.0);
        for (int j = 0; j < kKernelTableSize; ++j) {
            r[j] = m_rMin * std::exp(m_logStep * j);
            const glm::dvec3 sd = evaluateSd(c, glm::dvec3(0.0), z, z, glm::dvec3(r[j], 0.0, 0.0), z);
            for (int ch = 0; ch < 3; ++ch) s[ch][j] = sd[ch];
        }
        std::array<double, 3> integral{};
        for (int ch = 0; ch < 3; ++ch) {
            double sum = std::numbers::pi * m_rMin * m_rMin * s[ch][0];
            for (int j = 1; j < kKernelTableSize; ++j)
                sum += std::numbers::pi * (r[j] * s[ch][j] + r[j - 1] * s[ch][j - 1]) * (r[j] - r[j - 1]);
            integral[ch] = sum;
        }
        m_table.assign(kKernelTableSize, 0.0);
        for (int ch = 0; ch < 3; ++ch)
            if (integral[ch] > 0.0 && std::isfinite(integral[ch]))
                for (int j = 0; j < kKernelTableSize; ++j) m_table[j] += s[ch][j] / integral[ch];
        // Kernel width: where the density falls to half of its centre value.
        m_width = r.back();
        for (int j = 0; j < kKernelTableSize; ++j)
            if (m_table[j] < 0.5 * m_table[0]) {
                m_width = r[j];
                break;
            }
        m_width = std::max(m_width, m_rMin);
    }

    double operator()(double d) const {
        if (!(d > m_rMin)) return m_table[0];
        const double f = std::log(d / m_rMin) / m_logStep;
        if (f >= kKernelTableSize - 1) return m_table.back();
        const int j = static_cast<int>(f);
        const double w = f - j;
        return m_table[j] + w * (m_table[j + 1] - m_table[j]);
    }
    double width() const { return m_width; }

private:
    double m_rMin = 0.0, m_logStep = 1.0, m_width = 0.0;
    std::vector<double> m_table;
};

// Barycentric (u, v) corners of the m x m regular subdivision of a triangle into equal cells.
std::vector<std::array<glm::dvec2, 3>> subdivisionCells(int m) {
    std::vector<std::array<glm::dvec2, 3>> cells;
    cells.reserve(static_cast<size_t>(m) * m);
    const double s = 1.0 / m;
    for (int i = 0; i < m; ++i)
        for (int j = 0; j < m - i; ++j) {
            cells.push_back({glm::dvec2(i * s, j * s), glm::dvec2((i + 1) * s, j * s), glm::dvec2(i * s, (j + 1) * s)});
            if (j < m - i - 1)
                cells.push_back({glm::dvec2((i + 1) * s, j * s), glm::dvec2((i + 1) * s, (j + 1) * s),
                                 glm::dvec2(i * s, (j + 1) * s)});
        }
    return cells;
}

size_t sampleCdf(const std::vector<double>& cdf, double u) {
    // cdf is inclusive and ends at 1; the first entry > u.
    const auto it = std::upper_bound(cdf.begin(), cdf.end(), u);
    return std::min(static_cast<size_t>(it - cdf.begin()), cdf.size() - 1);
}

struct PixelResult {
    glm::dvec3 mean{0.0};
    glm::dvec3 standardError{0.0};
    int samples = 0;
    bool covered = false;
    bool converged = true;
};

class Renderer {
public:
    // `textured`: a textured material instead; `material` is then the one the sampling kernel is
    // shaped for.
    Renderer(const Mesh& mesh, const glm::mat4& model, const ScatteringMaterial& material,
             const std::vector<Light>& lights, const Camera& camera, int width, int height,
             const MeshReferenceOptions& options, std::optional<TexturedSurface> textured = std::nullopt)
        : m_options(options), m_width(width), m_height(height), m_textured(std::move(textured)) {
        detail::WorldMesh world = detail::toWorldMesh(mesh, model, "renderMeshReference");
        m_sceneSize = world.sceneSize;
        m_offset = 1e-7 * m_sceneSize;

        m_constants = deriveDipoleConstants(material, options.millimetresPerUnit, options.profile);

        m_lights = detail::prepareCpuLights(lights, "renderMeshReference");

        const auto& idx = mesh.indices();
        m_tris.resize(mesh.triangleCount());
        m_totalArea = 0.0;
        for (size_t t = 0; t < m_tris.size(); ++t) {
            TriInfo& tri = m_tris[t];
            const std::vector<glm::dvec3>& p = world.positions;
            const glm::dvec3 &a = p[idx[3 * t]], &b = p[idx[3 * t + 1]], &c = p[idx[3 * t + 2]];
            tri.p0 = a;
            tri.e1 = b - a;
            tri.e2 = c - a;
            tri.n0 = world.normals[idx[3 * t]];
            tri.n1 = world.normals[idx[3 * t + 1]];
            tri.n2 = world.normals[idx[3 * t + 2]];
            if (!mesh.texcoords().empty()) {
                tri.uv0 = glm::dvec2(mesh.texcoords()[idx[3 * t]]);
                tri.uv1 = glm::dvec2(mesh.texcoords()[idx[3 * t + 1]]);
                tri.uv2 = glm::dvec2(mesh.texcoords()[idx[3 * t + 2]]);
            }
            const glm::dvec3 cr = glm::cross(tri.e1, tri.e2);
            const double len = glm::length(cr);
            tri.area = 0.5 * len;
            tri.ng = len > 0.0 ? world.side * cr / len : glm::dvec3(0.0);
            tri.centroid = (a + b + c) / 3.0;
            tri.radius = std::max({glm::distance(a, tri.centroid), glm::distance(b, tri.centroid),
                                   glm::distance(c, tri.centroid)});
            tri.longest = std::max({glm::length(tri.e1), glm::length(tri.e2), glm::distance(b, c)});
            m_totalArea += tri.area;
        }
        if (!(m_totalArea > 0.0)) invalid("the mesh \"" + mesh.name() + "\" has zero surface area");

        m_bvh.emplace(std::move(world.positions), std::vector<uint32_t>(idx.begin(), idx.end()));
        for (TriInfo& tri : m_tris) tri.light = lightFactor(tri);
        m_kernel.emplace(m_constants, m_sceneSize);
        for (int s = 1; s <= kMaxSubdivision; ++s) m_cells.push_back(subdivisionCells(s));

        const glm::dmat4 viewProjection =
            glm::dmat4(camera.projection(float(width) / float(height))) * glm::dmat4(camera.view());
        m_inverseViewProjection = glm::inverse(viewProjection);
    }

    MeshReferenceResult run() {
        std::vector<PixelResult> pixels(static_cast<size_t>(m_width) * m_height);
        detail::parallelFor(
            m_options.threads, m_height, [] { return Scratch{}; },
            [&](Scratch& scratch, std::int64_t row) {
                const int y = static_cast<int>(row);
                for (int x = 0; x < m_width; ++x)
                    pixels[static_cast<size_t>(y) * m_width + x] = renderPixel(x, y, scratch);
            },
            [](const Scratch&) {});

        MeshReferenceResult result;
        result.image = Image(m_width, m_height);
        result.standardError = Image(m_width, m_height);
        double sumErr2 = 0.0, sumMean2 = 0.0, samples = 0.0;
        for (int y = 0; y < m_height; ++y)
            for (int x = 0; x < m_width; ++x) {
                const PixelResult& p = pixels[static_cast<size_t>(y) * m_width + x];
                if (!p.covered) {
                    result.image.at(x, y) = glm::vec4(glm::vec3(m_options.background), 0.0f);
                    continue;
                }
                result.image.at(x, y) = glm::vec4(glm::vec3(p.mean), 1.0f);
                result.standardError.at(x, y) = glm::vec4(glm::vec3(p.standardError), float(p.samples));
                ++result.coveredPixels;
                if (!p.converged) ++result.unconvergedPixels;
                samples += p.samples;
                for (int c = 0; c < 3; ++c) {
                    sumErr2 += p.standardError[c] * p.standardError[c];
                    sumMean2 += p.mean[c] * p.mean[c];
                    if (p.mean[c] > 0.0 && p.standardError[c] > m_options.absoluteError)
                        result.maxRelativeStandardError =
                            std::max(result.maxRelativeStandardError, p.standardError[c] / p.mean[c]);
                }
            }
        result.relativeRmseEstimate = sumMean2 > 0.0 ? std::sqrt(sumErr2 / sumMean2) : 0.0;
        result.meanSamplesPerPixel = result.coveredPixels ? samples / result.coveredPixels : 0.0;
        return result;
    }

private:
    struct CellTable {
        int m = 1;
        std::vector<double> cdf;  // inclusive, over the m^2 cells
        double meanKernel = 0.0;  // mean of the kernel at the cell centroids
    };
    struct Scratch {
        std::vector<double> triangleCdf;
        std::unordered_map<uint32_t, CellTable> cells;
    };

    // How much the lights see a triangle, for the sampling heuristic only: sum over lights of
    // mean radiance (at the centroid for point lights) times the largest cosine of a vertex normal
    // (flipped like n_i) to the light, times 0.01 + 0.99 * the unshadowed fraction of four
    // probe points (the centroid and the vertices pulled a tenth towards it). A spot light counts
    // as a point light here: its cone, sharp at one probe, must not make lit triangles unsampled.
    double lightFactor(const TriInfo& tri) const {
        if (!(tri.area > 0.0)) return 0.0;
        double f = 0.0;
        const std::array<glm::dvec3, 4> probes{tri.centroid, 0.9 * tri.p0 + 0.1 * tri.centroid,
                                               0.9 * (tri.p0 + tri.e1) + 0.1 * tri.centroid,
                                               0.9 * (tri.p0 + tri.e2) + 0.1 * tri.centroid};
        for (const detail::CpuLight& l : m_lights) {
            glm::dvec3 wi = l.vector;
            double falloff = 1.0;
            if (l.point) {
                const glm::dvec3 d = l.vector - tri.centroid;
                const double d2 = glm::dot(d, d);
                if (!(d2 > 0.0)) continue;
                wi = d / std::sqrt(d2);
                falloff = 1.0 / d2;
            }
            const double s = glm::dot(tri.ng, wi) < 0.0 ? -1.0 : 1.0;
            double best = 0.0;
            for (const glm::dvec3* n : {&tri.n0, &tri.n1, &tri.n2}) {
                const double len = glm::length(*n);
                if (len > 0.0) best = std::max(best, s * glm::dot(*n, wi) / len);
            }
            if (!(best > 0.0)) continue;
            int unshadowed = 0;
            for (const glm::dvec3& p : probes) {
                if (reachesLight(p + (s * m_offset) * tri.ng, l, wi)) ++unshadowed;
            }
            f += (l.radiance.x + l.radiance.y + l.radiance.z) / 3.0 * falloff * std::min(best, 1.0) *
                 (0.01 + 0.99 * unshadowed / 4.0);
        }
        return f;
    }

    // Interpolated, normalised normal at barycentrics (u, v), flipped to the side of `towards`
    // by the geometric normal.
    static glm::dvec3 shadingNormal(const TriInfo& tri, double u, double v, const glm::dvec3& towards) {
        glm::dvec3 n = (1.0 - u - v) * tri.n0 + u * tri.n1 + v * tri.n2;
        const double len = glm::length(n);
        n = len > 1e-300 ? n / len : tri.ng;
        return glm::dot(tri.ng, towards) < 0.0 ? -n : n;
    }

    double distanceBound(const glm::dvec3& xo, const glm::dvec3& centroid, double radius) const {
        return std::max(0.0, glm::distance(xo, centroid) - radius);
    }

    int subdivisionOf(const TriInfo& tri, double distance) const {
        const double cell = 0.5 * std::max(distance, m_kernel->width());
        return std::clamp(static_cast<int>(std::ceil(tri.longest / cell)), 1, kMaxSubdivision);
    }

    const CellTable& cellTable(uint32_t t, const glm::dvec3& xo, Scratch& scratch) const {
        auto [it, inserted] = scratch.cells.try_emplace(t);
        CellTable& table = it->second;
        if (!inserted) return table;
        const TriInfo& tri = m_tris[t];
        table.m = subdivisionOf(tri, distanceBound(xo, tri.centroid, tri.radius));
        const auto& cells = m_cells[table.m - 1];
        table.cdf.resize(cells.size());
        double sum = 0.0;
        for (size_t c = 0; c < cells.size(); ++c) {
            const glm::dvec2 b = (cells[c][0] + cells[c][1] + cells[c][2]) / 3.0;
            const glm::dvec3 p = tri.p0 + b.x * tri.e1 + b.y * tri.e2;
            table.cdf[c] = (*m_kernel)(glm::distance(xo, p));
            sum += table.cdf[c];
        }
        table.meanKernel = sum / static_cast<double>(cells.size());
        const double uniform = 1.0 / static_cast<double>(cells.size());
        double acc = 0.0;
        for (double& w : table.cdf) {
            acc += (sum > 0.0 ? (1.0 - kUniformShare) * w / sum + kUniformShare * uniform : uniform);
            w = acc;
        }
        table.cdf.back() = 1.0;
        return table;
    }

    PixelResult renderPixel(int x, int y, Scratch& scratch) const {
        PixelResult result;
        const detail::BvhRay ray = detail::pixelRay(m_inverseViewProjection, x, y, m_width, m_height);
        const auto hit = m_bvh->closestHit(ray);
        if (!hit) return result;
        result.covered = true;
        const TriInfo& hitTri = m_tris[hit->triangle];
        const glm::dvec3 xo = hitTri.p0 + hit->u * hitTri.e1 + hit->v * hitTri.e2;
        const glm::dvec3 wo = -glm::normalize(ray.direction);
        const glm::dvec3 no = shadingNormal(hitTri, hit->u, hit->v, wo);
        std::optional<DipoleConstants> local;
        glm::dvec3 logGathered(0.0), surroundingLog(0.0);
        if (m_textured) {
            const glm::dvec2 uv = texcoordAt(hitTri, hit->u, hit->v);
            local = m_textured->constantsAt(uv);
            logGathered = m_textured->logGathered(uv);
            surroundingLog = m_textured->surroundingLogGathered(uv, local->sigmaTr);
        }
        const ExitPoint exit{xo, no, local ? *local : m_constants, logGathered, surroundingLog};
        const double exitT = fresnelTransmittance(exit.constants.eta, glm::dot(no, wo));
        if (!(exitT > 0.0) || m_lights.empty()) return result;

        // Triangle pdf for this x_o: the kernel integrated over the triangle by the midpoint rule
        // on its cells (one cell far from x_o), times the light factor.
        std::vector<double>& cdf = scratch.triangleCdf;
        cdf.resize(m_tris.size());
        scratch.cells.clear();
        double sum = 0.0;
        for (size_t t = 0; t < m_tris.size(); ++t) {
            const TriInfo& tri = m_tris[t];
            double w = 0.0;
            if (tri.light > 0.0) {
                const double kernel = subdivisionOf(tri, distanceBound(xo, tri.centroid, tri.radius)) > 1
                                          ? cellTable(static_cast<uint32_t>(t), xo, scratch).meanKernel
                                          : (*m_kernel)(glm::distance(xo, tri.centroid));
                w = tri.area * tri.light * kernel;
            }
            cdf[t] = w;
            sum += w;
        }
        const double uniformShare = sum > 0.0 ? kUniformShare : 1.0;
        double acc = 0.0;
        for (size_t t = 0; t < m_tris.size(); ++t) {
            acc += (sum > 0.0 ? (1.0 - uniformShare) * cdf[t] / sum : 0.0) + uniformShare * m_tris[t].area / m_totalArea;
            cdf[t] = acc;
        }
        for (size_t t = m_tris.size(); t-- > 0;) {  // the last triangle with any probability ends at 1
            if (t == 0 || cdf[t] > cdf[t - 1]) {
                for (size_t k = t; k < m_tris.size(); ++k) cdf[k] = 1.0;
                break;
            }
        }

        Rng rng{mix64(m_options.seed * 0x9e3779b97f4a7c15ull ^ mix64(static_cast<uint64_t>(y) * m_width + x + 1))};
        glm::dvec3 sumF(0.0), sumF2(0.0), sumLog(0.0);  // sumLog: textured, f times the entry's ln gathered
        int n = 0;
        const double target = m_options.targetRelativeError;
        const double absolute = m_options.absoluteError / exitT;  // errors are scaled by exitT at the end
        while (n < m_options.maxSamples) {
            glm::dvec3 entryLog(0.0);
            const glm::dvec3 f = sample(exit, cdf, rng, scratch, entryLog);
            sumF += f;
            sumLog += f * entryLog;
            sumF2 += f * f;
            ++n;
            if (n >= m_options.minSamples && (n % kCheckInterval == 0 || n == m_options.maxSamples)) {
                bool done = true;
                for (int c = 0; c < 3 && done; ++c) {
                    const double mean = sumF[c] / n;
                    const double var = std::max(0.0, (sumF2[c] / n - mean * mean)) * n / (n - 1);
                    const double se = std::sqrt(var / n);
                    done = se <= std::max(target * std::abs(mean), absolute);
                }
                if (done) break;
            }
        }
        result.samples = n;
        result.converged = true;
        // Textured: the rule's effective `gathered` over x_o's own (mesh/reflectance_table.h).
        glm::dvec3 effective(1.0);
        if (m_textured)
            for (int c = 0; c < 3; ++c)
                if (sumF[c] > 0.0)
                    effective[c] = std::exp((1.0 - detail::kSurroundingShare) * sumLog[c] / sumF[c] +
                                            detail::kSurroundingShare * exit.surroundingLog[c] - exit.logGathered[c]);
        for (int c = 0; c < 3; ++c) {
            const double mean = sumF[c] / n;
            const double var = std::max(0.0, (sumF2[c] / n - mean * mean)) * n / (n - 1);
            const double se = std::sqrt(var / n);
            result.mean[c] = exitT * effective[c] * mean;
            result.standardError[c] = exitT * effective[c] * se;
            if (se > std::max(target * std::abs(mean), absolute)) result.converged = false;
        }
        result.mean += singleScattering(exit, wo, hitTri);
        return result;
    }

    // One sample of sum over lights of T_i S_d E cos V, divided by its pdf.
    glm::dvec2 texcoordAt(const TriInfo& tri, double u, double v) const {
        return (1.0 - u - v) * tri.uv0 + u * tri.uv1 + v * tri.uv2;
    }

    // `logGathered`: textured, the entry point's ln gathered.
    glm::dvec3 sample(const ExitPoint& exit, const std::vector<double>& cdf, Rng& rng, Scratch& scratch,
                      glm::dvec3& logGathered) const {
        const glm::dvec3& xo = exit.x;
        const glm::dvec3& no = exit.n;
        const size_t t = sampleCdf(cdf, rng.uniform());
        const double pt = cdf[t] - (t > 0 ? cdf[t - 1] : 0.0);
        const TriInfo& tri = m_tris[t];
        int m = 1;
        double pc = 1.0;
        glm::dvec2 c0(0.0), c1(1.0, 0.0), c2(0.0, 1.0);
        if (subdivisionOf(tri, distanceBound(xo, tri.centroid, tri.radius)) > 1) {
            const CellTable& table = cellTable(static_cast<uint32_t>(t), xo, scratch);
            m = table.m;
            const size_t c = sampleCdf(table.cdf, rng.uniform());
            pc = table.cdf[c] - (c > 0 ? table.cdf[c - 1] : 0.0);
            const auto& cell = m_cells[m - 1][c];
            c0 = cell[0];
            c1 = cell[1];
            c2 = cell[2];
        }
        const double pdf = pt * pc * double(m) * double(m) / tri.area;
        if (!(pdf > 0.0)) return glm::dvec3(0.0);
        // Uniform point in the cell.
        const double su = std::sqrt(rng.uniform());
        const double r2 = rng.uniform();
        const glm::dvec2 bary = (1.0 - su) * c0 + su * (1.0 - r2) * c1 + su * r2 * c2;
        const glm::dvec3 xi = tri.p0 + bary.x * tri.e1 + bary.y * tri.e2;

        glm::dvec3 f(0.0);
        for (const detail::CpuLight& l : m_lights) {
            glm::dvec3 wi, irradiance;
            if (!detail::lightAt(l, xi, wi, irradiance)) continue;
            const glm::dvec3 ni = shadingNormal(tri, bary.x, bary.y, wi);
            const double cosI = glm::dot(ni, wi);
            if (!(cosI > 0.0)) continue;
            const double entryT = fresnelTransmittance(exit.constants.eta, cosI);
            if (!(entryT > 0.0)) continue;
            const glm::dvec3 sd = evaluateSd(exit.constants, xi, ni, wi, xo, no);
            if (sd.x <= 0.0 && sd.y <= 0.0 && sd.z <= 0.0) continue;
            // Shadow ray from just off the side of the triangle that faces the light.
            const double side = glm::dot(tri.ng, wi) < 0.0 ? -1.0 : 1.0;
            if (!reachesLight(xi + (side * m_offset) * tri.ng, l, wi)) continue;
            f += sd * irradiance * (entryT * cosI);
        }
        if (m_textured && (f.x > 0.0 || f.y > 0.0 || f.z > 0.0))
            logGathered = m_textured->entryLogGathered(texcoordAt(tri, bary.x, bary.y));
        return f / pdf;
    }

    // The profile's single scattering at x_o (exact, no variance): per light its irradiance on
    // the surface, if a shadow ray reaches the light, times evaluateSingleScattering().
    glm::dvec3 singleScattering(const ExitPoint& exit, const glm::dvec3& wo, const TriInfo& tri) const {
        const glm::dvec3& xo = exit.x;
        const glm::dvec3& no = exit.n;
        glm::dvec3 sum(0.0);
        if (!(exit.constants.singleScattering > 0.0)) return sum;
        for (const detail::CpuLight& l : m_lights) {
            glm::dvec3 wi, irradiance;
            if (!detail::lightAt(l, xo, wi, irradiance)) continue;
            const double cosI = glm::dot(no, wi);
            if (!(cosI > 0.0)) continue;
            const double side = glm::dot(tri.ng, wi) < 0.0 ? -1.0 : 1.0;
            if (!reachesLight(xo + (side * m_offset) * tri.ng, l, wi)) continue;
            sum += irradiance * cosI * evaluateSingleScattering(exit.constants, no, wi, wo);
        }
        return sum;
    }

    // Shadow ray: is light `l` (unit direction towards it `wi`) unoccluded from `origin`?
    bool reachesLight(const glm::dvec3& origin, const detail::CpuLight& l, const glm::dvec3& wi) const {
        detail::BvhRay ray;
        ray.origin = origin;
        if (l.point) {
            ray.direction = l.vector - origin;  // tMax 1 stops at the light
            ray.tMax = 1.0;
        } else {
            ray.direction = wi;
        }
        return !m_bvh->anyHit(ray);
    }

    MeshReferenceOptions m_options;
    int m_width, m_height;
    DipoleConstants m_constants;
    std::vector<detail::CpuLight> m_lights;
    std::vector<TriInfo> m_tris;
    double m_totalArea = 0.0;
    double m_sceneSize = 0.0;
    double m_offset = 0.0;
    std::optional<detail::TriangleBvh> m_bvh;
    std::optional<Kernel> m_kernel;
    std::vector<std::vector<std::array<glm::dvec2, 3>>> m_cells;
    std::optional<TexturedSurface> m_textured;
    glm::dmat4 m_inverseViewProjection{1.0};
};

// The checks both overloads make before any work.
void checkInputs(const Mesh& mesh, int width, int height, const MeshReferenceOptions& options) {
    if (width < 1 || height < 1 || width > kMaxImageSide || height > kMaxImageSide)
        invalid("image size must be in [1, " + std::to_string(kMaxImageSide) + "] on each side, got " +
                std::to_string(width) + " x " + std::to_string(height));
    validateOptions(options);
    if (mesh.triangleCount() == 0) invalid("the mesh \"" + mesh.name() + "\" has no triangles");
}

}  // namespace

MeshReferenceResult renderMeshReference(const Mesh& mesh, const glm::mat4& model, const ScatteringMaterial& material,
                                        const std::vector<Light>& lights, const Camera& camera, int width, int height,
                                        const MeshReferenceOptions& options) {
    checkInputs(mesh, width, height, options);
    Renderer renderer(mesh, model, material, lights, camera, width, height, options);
    return renderer.run();
}

MeshReferenceResult renderMeshReference(const Mesh& mesh, const glm::mat4& model, const TexturedScattering& material,
                                        const std::vector<Light>& lights, const Camera& camera, int width, int height,
                                        const MeshReferenceOptions& options) {
    checkInputs(mesh, width, height, options);
    material.validate();
    const Image8* reflectance = material.reflectance ? material.reflectance.get() : mesh.baseColour().get();
    if (!reflectance)
        invalid("the textured material \"" + material.name + "\" has no reflectance texture and the mesh \"" +
                mesh.name() + "\" no base colour");
    if (mesh.texcoords().empty()) invalid("the mesh \"" + mesh.name() + "\" has no texture coordinates");
    // The sampling kernel is shaped for the texture's mean colour.
    const detail::TextureSampler sampler(*reflectance, true);
    glm::dvec3 mean(0.0);
    for (int y = 0; y < reflectance->height(); ++y)
        for (int x = 0; x < reflectance->width(); ++x)
            mean += sampler({(x + 0.5) / reflectance->width(), (y + 0.5) / reflectance->height()});
    mean /= double(reflectance->width()) * reflectance->height();
    const ScatteringMaterial typical = materialFromReflectance(mean, material.meanFreePath, material.eta, options.profile);
    const double texelsPerUnit = detail::meanTexelDensity(mesh, model, reflectance->width(), reflectance->height());
    Renderer renderer(mesh, model, typical, lights, camera, width, height, options,
                      TexturedSurface(material, *reflectance, options.profile, options.millimetresPerUnit, texelsPerUnit));
    return renderer.run();
}

}  // namespace sss
