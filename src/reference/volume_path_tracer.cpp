// Physical ground truth for volumes: delta tracking against a majorant grid, next-event
// estimation with ratio tracking, RGB throughput (see sss/volume_path_tracer.h).
#include "core/volume_clip_space.h"
#include "sss/volume_path_tracer.h"

#include "volume/box_clip.h"
#include "core/voxel_storage.h"
#include "core/volume_reconstruction.h"

#include "util/format.h"
#include "reference/cpu_lights.h"
#include "util/parallel.h"
#include "reference/walk_sampling.h"

#include "sss/error.h"
#include "sss/volume_reference.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <variant>
#include <vector>

namespace sss {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Majorants are raised by this factor so that rounding in the reconstruction can
// never put sigma_t above its cell's bound (a larger majorant costs lookups, not accuracy).
constexpr double kMajorantSlack = 1.0 + 1e-6;
// Ratio tracking is rouletted below this transmittance (survivors continue at this value).
constexpr double kRatioRoulette = 0.125;

template <typename T>
std::string str(const T& v) {
    return detail::formatNumber(v);
}

bool finite(glm::dvec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

const std::string kWho = "renderVolumePathTraced";

[[noreturn]] void invalid(const std::string& message) { throw Error(ErrorKind::InvalidArgument, kWho + ": " + message); }

void validate(const VolumePathTracerOptions& o) {
    validate(o.clip, "VolumePathTracerOptions::clip");
    auto fail = [](const std::string& field, const std::string& rule, const std::string& value) {
        invalid("VolumePathTracerOptions::" + field + " must be " + rule + ", got " + value);
    };
    if (o.samplesPerPixel < 1 || o.samplesPerPixel > (1 << 24))
        fail("samplesPerPixel", "in [1, 16777216]", str(o.samplesPerPixel));
    if (o.threads < 0) fail("threads", ">= 0 (0: one per hardware thread)", str(o.threads));
    const int mode = static_cast<int>(o.mode);
    if (mode < 0 || mode > static_cast<int>(VolumeScatteringMode::MultipleScattering))
        fail("mode", "a VolumeScatteringMode value", str(mode));
    if (!std::isfinite(o.g) || !(o.g > -1.0 && o.g < 1.0)) fail("g", "in (-1, 1)", str(o.g));
    if (o.maxBounces < 1) fail("maxBounces", ">= 1", str(o.maxBounces));
    if (o.rouletteStartBounce < 0) fail("rouletteStartBounce", ">= 0", str(o.rouletteStartBounce));
    if (o.majorantGridResolution < 1 || o.majorantGridResolution > 1024)
        fail("majorantGridResolution", "in [1, 1024]", str(o.majorantGridResolution));
    const glm::dvec4 b = o.background;
    if (!finite(glm::dvec3(b)) || !std::isfinite(b.w)) fail("background", "finite", detail::formatVec(b));
}

// sigma_t * D from alpha_tf, capped: the reference's definition (sss/volume_reference.h).
double opticalDepthPerVoxel(double alpha) {
    if (!(alpha > 0.0)) return 0.0;
    if (alpha >= 1.0) return kMaxOpticalDepthPerVoxel;
    return std::min(-std::log1p(-alpha), kMaxOpticalDepthPerVoxel);
}

using detail::clipToBox;

struct PreparedLight {
    detail::CpuLight world;             // world space, where the falloff and a spot's cone apply
    glm::dvec3 towardsLightModel{0.0};  // directional: unit, model space
    glm::dvec3 positionModel{0.0};      // point and spot
};

// Per-thread counters; integers, so their sums do not depend on the thread count.
struct Tally {
    std::int64_t paths = 0, collisions = 0, lookups = 0, truncated = 0, violations = 0;
    void add(const Tally& o) {
        paths += o.paths;
        collisions += o.collisions;
        lookups += o.lookups;
        truncated += o.truncated;
        violations += o.violations;
    }
};

using Rng = detail::Xoshiro256;

struct Dir {
    double x, y, z;
};

// Range maximum over a fixed array in O(1) per query (sparse table).
class RangeMax {
public:
    explicit RangeMax(std::vector<double> values) {
        m_levels.push_back(std::move(values));
        for (std::size_t w = 1; 2 * w <= m_levels[0].size(); w *= 2) {
            const std::vector<double>& prev = m_levels.back();
            std::vector<double> next(prev.size() - w);
            for (std::size_t i = 0; i < next.size(); ++i) next[i] = std::max(prev[i], prev[i + w]);
            m_levels.push_back(std::move(next));
        }
    }
    double operator()(std::size_t lo, std::size_t hi) const {  // inclusive, lo <= hi
        std::size_t k = 0;
        while ((std::size_t{2} << k) <= hi - lo + 1) ++k;
        return std::max(m_levels[k][lo], m_levels[k][hi + 1 - (std::size_t{1} << k)]);
    }

private:
    std::vector<std::vector<double>> m_levels;
};

class PathTracer {
public:
    PathTracer(const Volume& volume, const TransferFunction& tf, int tfEntries, const glm::mat4& model,
               const std::vector<Light>& lights, const VolumePathTracerOptions& options)
        : m_reference(volume, tf, tfEntries, model, lights,
                      VolumeReferenceOptions{.clip = options.clip, .reconstruction = options.reconstruction}),
          m_options(options) {
        const Bounds box = volume.worldBounds();
        m_boxMin = glm::dvec3(box.min);
        m_boxMax = glm::dvec3(box.max);
        m_voxel = m_reference.voxelLength();
        m_clip = detail::textureClip(options.clip, model, box);
        m_modelToWorld = glm::dmat4(model);
        m_worldToModel = glm::inverse(m_modelToWorld);
        const glm::dmat3 worldToModelLinear(m_worldToModel);
        for (const Light& light : lights) {
            PreparedLight p{detail::toCpuLight(light)};
            if (p.world.point)
                p.positionModel = glm::dvec3(m_worldToModel * glm::dvec4(p.world.vector, 1.0));
            else
                p.towardsLightModel = glm::normalize(worldToModelLinear * p.world.vector);
            const glm::dvec3 e = p.world.radiance;
            if (e.x > 0.0 || e.y > 0.0 || e.z > 0.0) m_lights.push_back(p);
        }
        buildMajorants(volume, tf, tfEntries);
    }

    glm::ivec3 grid() const { return m_cells; }

    // One pixel: mean and standard error of rgb and alpha; false if it takes no paths.
    bool pixel(const glm::dmat4& inverseViewProjection, int x, int y, int width, int height, glm::dvec4& mean,
               glm::dvec4& standardError, Tally& tally) const {
        const int n = m_options.samplesPerPixel;
        if (!m_options.jitterPixels) {
            glm::dvec3 o, d;
            double t0, t1;
            if (!cameraRay(inverseViewProjection, centreNdc(x, y, width, height, 0.5, 0.5), o, d, t0, t1)) return false;
        }
        std::uint64_t key = detail::mix64(m_options.seed + 0x9e3779b97f4a7c15ull);
        key = detail::mix64(key ^ (static_cast<std::uint64_t>(y) * static_cast<std::uint64_t>(width) +
                                   static_cast<std::uint64_t>(x) + 0x632be59bd9b4e019ull));
        const glm::dvec4 bg = m_options.background;
        glm::dvec4 sum(0.0), sum2(0.0);
        for (int i = 0; i < n; ++i) {
            // A stream per path, not per pixel: path i draws the same numbers whatever the
            // earlier paths consumed, so the two modes agree up to the first next-event term.
            Rng rng(detail::mix64(key ^ (static_cast<std::uint64_t>(i) + 0x85157af5ull)));
            double u = 0.5, v = 0.5;
            if (m_options.jitterPixels) {
                u = rng.uniform();
                v = rng.uniform();
            }
            glm::dvec3 o, d;
            double t0, t1;
            glm::dvec3 value(0.0);
            bool hit = false;
            if (cameraRay(inverseViewProjection, centreNdc(x, y, width, height, u, v), o, d, t0, t1))
                value = path(o, d, t0, t1, rng, hit, tally);
            ++tally.paths;
            const double miss = hit ? 0.0 : 1.0;
            const glm::dvec4 sample(value + miss * glm::dvec3(bg), (1.0 - miss) + miss * bg.w);
            sum += sample;
            sum2 += sample * sample;
        }
        mean = sum / static_cast<double>(n);
        standardError = glm::dvec4(0.0);
        if (n > 1)
            for (int c = 0; c < 4; ++c)
                standardError[c] = std::sqrt(std::max(0.0, sum2[c] / n - mean[c] * mean[c]) / (n - 1));
        return true;
    }

private:
    static glm::dvec2 centreNdc(int x, int y, int width, int height, double u, double v) {
        return {(x + u) / width * 2.0 - 1.0, 1.0 - (y + v) / height * 2.0};
    }

    // The reference's camera ray (VolumeReference::Impl::tracePixel), clipped to the box.
    bool cameraRay(const glm::dmat4& inverseViewProjection, glm::dvec2 ndc, glm::dvec3& origin, glm::dvec3& dir,
                   double& t0, double& t1) const {
        const glm::dvec4 nearWorld = inverseViewProjection * glm::dvec4(ndc, -1.0, 1.0);
        const glm::dvec4 farWorld = inverseViewProjection * glm::dvec4(ndc, 1.0, 1.0);
        origin = glm::dvec3(m_worldToModel * glm::dvec4(glm::dvec3(nearWorld) / nearWorld.w, 1.0));
        const glm::dvec3 farModel = glm::dvec3(m_worldToModel * glm::dvec4(glm::dvec3(farWorld) / farWorld.w, 1.0));
        const glm::dvec3 d = farModel - origin;
        const double length = glm::length(d);
        if (!(length > 0.0)) return false;
        dir = d / length;
        t0 = 0.0;
        t1 = length;
        return clipToBox(m_boxMin, m_boxMax, origin, dir, t0, t1) &&
               m_clip.clipSpan((origin - m_boxMin) / (m_boxMax - m_boxMin), dir / (m_boxMax - m_boxMin), t0, t1);
    }

    void buildMajorants(const Volume& volume, const TransferFunction& tf, int tfEntries) {
        const glm::ivec3 dims = volume.dims();
        const int res = m_options.majorantGridResolution;
        m_cells = glm::ivec3(std::min(res, dims.x), std::min(res, dims.y), std::min(res, dims.z));
        m_cellSize = (m_boxMax - m_boxMin) / glm::dvec3(m_cells);
        // Raw voxel value -> TF coordinate, as the reference (monotone increasing).
        const glm::dvec2 toTf = detail::sampleToTfCoordinate(volume);
        const double normalise = 1.0 / detail::storedPerSample(volume.type()), scale = toTf.x, offset = toTf.y;
        auto coordinate = [&](double raw) { return std::clamp(raw * normalise * scale + offset, 0.0, 1.0); };
        std::vector<double> alphas;
        for (const glm::vec4& e : tf.table(tfEntries)) alphas.push_back(static_cast<double>(e.a));
        const RangeMax alphaMax(alphas);
        const std::size_t last = alphas.size() - 1;

        const std::vector<uint8_t>& bytes = volume.bytes();
        const detail::StorageToRaw storage = detail::storageToRaw(volume);
        auto raw = [&](int x, int y, int z) {  // what the texture holds, as the reference's field
            const std::size_t i = static_cast<std::size_t>(x) +
                                  static_cast<std::size_t>(dims.x) *
                                      (static_cast<std::size_t>(y) + static_cast<std::size_t>(dims.y) * z);
            return detail::storedValue(bytes.data(), volume.type(), i, storage);
        };
        // Voxels the reconstruction reads anywhere in cell c along an axis: texel centres at
        // (i + 0.5) / n, so the cell [c / R, (c + 1) / R] reads from floor(c n / R - 0.5) - reach + 1
        // up to floor((c + 1) n / R - 0.5) + reach (reach 1 trilinear, 2 cubic), clamped to the edge.
        const int reach = detail::reconstructionReach(m_options.reconstruction);
        auto footprint = [reach](int c, int cells, int n, int& first, int& lastVoxel) {
            first = std::clamp(static_cast<int>(std::floor(double(c) * n / cells - 0.5)) - reach + 1, 0, n - 1);
            lastVoxel = std::clamp(static_cast<int>(std::floor(double(c + 1) * n / cells - 0.5)) + reach, 0, n - 1);
        };
        m_majorant.assign(static_cast<std::size_t>(m_cells.x) * m_cells.y * m_cells.z, 0.0);
        for (int cz = 0; cz < m_cells.z; ++cz) {
            int z0, z1;
            footprint(cz, m_cells.z, dims.z, z0, z1);
            for (int cy = 0; cy < m_cells.y; ++cy) {
                int y0, y1;
                footprint(cy, m_cells.y, dims.y, y0, y1);
                for (int cx = 0; cx < m_cells.x; ++cx) {
                    int x0, x1;
                    footprint(cx, m_cells.x, dims.x, x0, x1);
                    double vMin = std::numeric_limits<double>::infinity(), vMax = -vMin;
                    for (int z = z0; z <= z1; ++z)
                        for (int y = y0; y <= y1; ++y)
                            for (int x = x0; x <= x1; ++x) {
                                const double v = raw(x, y, z);
                                vMin = std::min(vMin, v);
                                vMax = std::max(vMax, v);
                            }
                    // The table is linearly interpolated: its maximum over [xMin, xMax] is at a
                    // node between floor(xMin (N - 1)) and ceil(xMax (N - 1)).
                    const double fMin = coordinate(vMin) * static_cast<double>(last);
                    const double fMax = coordinate(vMax) * static_cast<double>(last);
                    const std::size_t i0 = std::min(static_cast<std::size_t>(std::floor(fMin)), last);
                    const std::size_t i1 = std::min(static_cast<std::size_t>(std::ceil(fMax)), last);
                    const double sigma = opticalDepthPerVoxel(alphaMax(i0, std::max(i0, i1))) / m_voxel;
                    m_majorant[cellIndex(cx, cy, cz)] = sigma * kMajorantSlack;
                }
            }
        }
    }

    std::size_t cellIndex(int x, int y, int z) const {
        return static_cast<std::size_t>(x) +
               static_cast<std::size_t>(m_cells.x) * (static_cast<std::size_t>(y) + static_cast<std::size_t>(m_cells.y) * z);
    }

    // Calls visit(majorant, ta, tb) for the cells the segment origin + t dir, t in [t0, t1],
    // crosses, in order (3D DDA), until visit returns false.
    template <typename Visit>
    void walkCells(glm::dvec3 origin, glm::dvec3 dir, double t0, double t1, Visit&& visit) const {
        if (!(t1 > t0)) return;
        if (m_majorant.size() == 1) {
            visit(m_majorant[0], t0, t1);
            return;
        }
        const glm::dvec3 p = origin + t0 * dir;
        int idx[3], step[3];
        double tNext[3], tDelta[3];
        for (int a = 0; a < 3; ++a) {
            idx[a] = std::clamp(static_cast<int>(std::floor((p[a] - m_boxMin[a]) / m_cellSize[a])), 0, m_cells[a] - 1);
            if (dir[a] > 0.0) {
                step[a] = 1;
                tNext[a] = t0 + (m_boxMin[a] + (idx[a] + 1) * m_cellSize[a] - p[a]) / dir[a];
                tDelta[a] = m_cellSize[a] / dir[a];
            } else if (dir[a] < 0.0) {
                step[a] = -1;
                tNext[a] = t0 + (m_boxMin[a] + idx[a] * m_cellSize[a] - p[a]) / dir[a];
                tDelta[a] = -m_cellSize[a] / dir[a];
            } else {
                step[a] = 0;
                tNext[a] = kInf;
                tDelta[a] = kInf;
            }
        }
        double t = t0;
        for (;;) {
            const int a = tNext[0] < tNext[1] ? (tNext[0] < tNext[2] ? 0 : 2) : (tNext[1] < tNext[2] ? 1 : 2);
            const double tb = std::min(tNext[a], t1);
            if (tb > t) {
                if (!visit(m_majorant[cellIndex(idx[0], idx[1], idx[2])], t, tb)) return;
                t = tb;
            }
            if (tNext[a] >= t1) return;
            idx[a] += step[a];
            if (idx[a] < 0 || idx[a] >= m_cells[a]) return;
            tNext[a] += tDelta[a];
        }
    }

    double sigmaT(double alpha) const { return opticalDepthPerVoxel(alpha) / m_voxel; }

    // Delta tracking: distance of the first real collision in [t0, t1] (its TF sample in tf), or
    // -1 if the path leaves the segment.
    double track(glm::dvec3 origin, glm::dvec3 dir, double t0, double t1, Rng& rng, Tally& tally,
                 glm::dvec4& tf) const {
        double tau = -std::log(rng.openUniform());  // optical depth (against the majorant) left
        double hit = -1.0;
        walkCells(origin, dir, t0, t1, [&](double majorant, double ta, double tb) {
            if (!(majorant > 0.0)) return true;  // empty cell: nothing to collide with
            double t = ta;
            for (;;) {
                const double dt = tau / majorant;
                if (dt >= tb - t) {
                    tau = std::max(0.0, tau - majorant * (tb - t));
                    return true;
                }
                t += dt;
                ++tally.lookups;
                const glm::dvec4 sample = m_reference.classify(origin + t * dir);
                const double sigma = sigmaT(sample.a);
                if (sigma > majorant) ++tally.violations;
                if (rng.uniform() * majorant < sigma) {
                    hit = t;
                    tf = sample;
                    return false;
                }
                tau = -std::log(rng.openUniform());
            }
        });
        return hit;
    }

    // Ratio tracking: an unbiased estimate of the transmittance over [0, t1] from origin.
    double transmittance(glm::dvec3 origin, glm::dvec3 dir, double t1, Rng& rng, Tally& tally) const {
        double tr = 1.0;
        walkCells(origin, dir, 0.0, t1, [&](double majorant, double ta, double tb) {
            if (!(majorant > 0.0)) return true;
            // The tentative points form a Poisson process of rate `majorant`: memoryless, so
            // each cell starts afresh.
            for (double t = ta;;) {
                t -= std::log(rng.openUniform()) / majorant;
                if (t >= tb) return true;
                ++tally.lookups;
                const double sigma = sigmaT(m_reference.classify(origin + t * dir).a);
                if (sigma > majorant) ++tally.violations;
                tr *= std::max(0.0, 1.0 - sigma / majorant);
                if (tr < kRatioRoulette) {
                    if (rng.uniform() * kRatioRoulette >= tr) {
                        tr = 0.0;
                        return false;
                    }
                    tr = kRatioRoulette;
                }
            }
        });
        return tr;
    }

    // Sum over lights of p_HG(l . d) E T_l at p, the path arriving along d.
    glm::dvec3 nextEvent(glm::dvec3 p, glm::dvec3 d, Rng& rng, Tally& tally) const {
        glm::dvec3 sum(0.0);
        for (const PreparedLight& light : m_lights) {
            glm::dvec3 l = light.towardsLightModel;
            glm::dvec3 radiance = light.world.radiance;
            double tEnd = kInf;
            if (light.world.point) {
                const glm::dvec3 toLight = light.positionModel - p;
                const double distance = glm::length(toLight);
                if (!(distance > 0.0)) continue;  // at the light: no direction (measure zero)
                const glm::dvec3 worldP = glm::dvec3(m_modelToWorld * glm::dvec4(p, 1.0));
                const glm::dvec3 toLightWorld = light.world.vector - worldP;
                radiance = radiance / std::max(glm::dot(toLightWorld, toLightWorld), 1e-8) *
                           detail::emittedShare(light.world, worldP);
                l = toLight / distance;
                tEnd = distance;
            }
            double t0 = 0.0;
            double tr = 1.0;
            if (clipToBox(m_boxMin, m_boxMax, p, l, t0, tEnd)) tr = transmittance(p, l, tEnd, rng, tally);
            if (tr > 0.0) sum += detail::henyeyGreenstein(m_options.g, glm::dot(l, d)) * radiance * tr;
        }
        return sum;
    }

    // One path from the eye: its value X (rgb); hit = the camera ray had a real collision.
    glm::dvec3 path(glm::dvec3 origin, glm::dvec3 dir, double t0, double t1, Rng& rng, bool& hit,
                    Tally& tally) const {
        const bool single = m_options.mode == VolumeScatteringMode::SingleScattering;
        glm::dvec3 value(0.0), throughput(1.0);
        hit = false;
        for (int bounce = 0;; ++bounce) {
            glm::dvec4 tf;
            const double t = track(origin, dir, t0, t1, rng, tally, tf);
            if (t < 0.0) break;  // left the box
            hit = true;
            ++tally.collisions;
            const glm::dvec3 p = origin + t * dir;
            const glm::dvec3 albedo = glm::clamp(glm::dvec3(tf), 0.0, 1.0);
            if (!m_lights.empty()) value += throughput * albedo * nextEvent(p, dir, rng, tally);
            if (single) break;
            throughput *= albedo;
            if (!(std::max({throughput.x, throughput.y, throughput.z}) > 0.0)) break;  // absorbed
            if (bounce + 1 >= m_options.maxBounces) {
                ++tally.truncated;
                break;
            }
            if (bounce + 1 >= m_options.rouletteStartBounce) {
                const double q = std::min(1.0, std::max({throughput.x, throughput.y, throughput.z}));
                if (q < 1.0) {
                    if (rng.uniform() >= q) break;
                    throughput /= q;
                }
            }
            const Dir next = detail::scatterHenyeyGreenstein(Dir{dir.x, dir.y, dir.z}, m_options.g, rng);
            dir = glm::dvec3(next.x, next.y, next.z);
            origin = p;
            t0 = 0.0;
            t1 = kInf;
            if (!clipToBox(m_boxMin, m_boxMax, origin, dir, t0, t1)) break;  // on a face, leaving
        }
        return value;
    }

    detail::TextureClip m_clip;   // the camera segments' clip (the light's is m_reference's)
    VolumeReference m_reference;  // reconstruction and classification, exactly the reference's
    VolumePathTracerOptions m_options;
    glm::dvec3 m_boxMin{0.0}, m_boxMax{0.0};
    double m_voxel = 1.0;
    glm::dmat4 m_modelToWorld{1.0}, m_worldToModel{1.0};
    std::vector<PreparedLight> m_lights;
    glm::ivec3 m_cells{1};
    glm::dvec3 m_cellSize{1.0};
    std::vector<double> m_majorant;
};

}  // namespace

VolumePathTracerResult renderVolumePathTraced(const Volume& volume, const TransferFunction& tf, int tfEntries,
                                              const glm::mat4& model, const std::vector<Light>& lights,
                                              const Camera& camera, int width, int height,
                                              const VolumePathTracerOptions& options) {
    if (width <= 0 || width > kMaxImageSide || height <= 0 || height > kMaxImageSide)
        invalid("width and height must be in 1.." + std::to_string(kMaxImageSide) + ", got " + std::to_string(width) +
                " x " + std::to_string(height));
    if (tfEntries < 2 || tfEntries > 65536)
        invalid("tfEntries must be in 2..65536, got " + std::to_string(tfEntries));
    const glm::dmat4 m(model);
    bool modelFinite = true;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) modelFinite = modelFinite && std::isfinite(m[c][r]);
    const double det = glm::determinant(m);
    if (!modelFinite || !std::isfinite(det) || det == 0.0) invalid("the model matrix must be finite and invertible");
    for (std::size_t i = 0; i < lights.size(); ++i) validateLight(lights[i], kWho + " light " + std::to_string(i));
    validate(options);

    const PathTracer tracer(volume, tf, tfEntries, model, lights, options);
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    const glm::dmat4 inverseViewProjection =
        glm::inverse(glm::dmat4(camera.projection(aspect)) * glm::dmat4(camera.view()));

    VolumePathTracerResult result;
    result.image = Image(width, height, glm::vec4(options.background));
    result.standardError = Image(width, height);
    result.majorantGrid = tracer.grid();
    std::vector<unsigned char> covered(static_cast<std::size_t>(width) * height, 0);
    Tally total;
    detail::parallelFor(
        options.threads, height, [] { return Tally{}; },
        [&](Tally& tally, std::int64_t row) {
            const int y = static_cast<int>(row);
            for (int x = 0; x < width; ++x) {
                glm::dvec4 mean, se;
                if (!tracer.pixel(inverseViewProjection, x, y, width, height, mean, se, tally)) continue;
                result.image.at(x, y) = glm::vec4(mean);
                result.standardError.at(x, y) = glm::vec4(se);
                covered[static_cast<std::size_t>(y) * width + x] = 1;
            }
        },
        [&](const Tally& tally) { total.add(tally); });

    double sumErr2 = 0.0, sumMean2 = 0.0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            if (!covered[static_cast<std::size_t>(y) * width + x]) continue;
            ++result.coveredPixels;
            for (int c = 0; c < 3; ++c) {
                const double v = result.image.at(x, y)[c], e = result.standardError.at(x, y)[c];
                sumErr2 += e * e;
                sumMean2 += v * v;
            }
        }
    result.relativeRmseEstimate = sumMean2 > 0.0 ? std::sqrt(sumErr2 / sumMean2) : 0.0;
    result.paths = total.paths;
    result.truncatedPaths = total.truncated;
    result.majorantViolations = total.violations;
    result.meanSamplesPerPixel = static_cast<double>(total.paths) / (static_cast<double>(width) * height);
    if (total.paths > 0) {
        result.meanCollisionsPerPath = static_cast<double>(total.collisions) / static_cast<double>(total.paths);
        result.meanLookupsPerPath = static_cast<double>(total.lookups) / static_cast<double>(total.paths);
    }
    return result;
}

}  // namespace sss
