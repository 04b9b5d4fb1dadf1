#include "core/volume_clip_space.h"
#include "sss/volume_reference.h"

#include "util/format.h"
#include "reference/cpu_lights.h"
#include "util/parallel.h"
#include "volume/box_clip.h"
#include "volume/light_sweep_plan.h"
#include "core/voxel_storage.h"
#include "core/volume_reconstruction.h"

#include "sss/error.h"
#include "sss/image_compare.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <exception>
#include <limits>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <variant>

namespace sss {
namespace {

// Where shading looks from; like shaders/common/camera.glsl towardsViewer().
struct Viewer {
    glm::dvec3 position, forward;
    bool orthographic;
    glm::dvec3 towards(glm::dvec3 p) const { return orthographic ? -forward : glm::normalize(position - p); }
};


constexpr double kMinStepVoxels = 1.0 / 1024.0;

template <typename T>
std::string str(const T& v) {
    return detail::formatNumber(v);
}

std::string str(glm::dvec3 v) { return detail::formatVec(v); }
std::string str(glm::dvec4 v) { return detail::formatVec(v); }

bool finite(glm::dvec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void validate(const VolumeReferenceOptions& o) {
    validate(o.clip, "VolumeReferenceOptions::clip");
    auto fail = [](const std::string& field, const std::string& rule, const std::string& value) {
        throw Error(ErrorKind::InvalidArgument, "VolumeReferenceOptions::" + field + " must be " + rule + ", got " + value);
    };
    const int shading = static_cast<int>(o.shading);
    if (shading < 0 || shading > static_cast<int>(ReferenceShading::ScatteringGradient))
        fail("shading", "a ReferenceShading value", str(shading));
    if (!std::isfinite(o.stepVoxels) || !(o.stepVoxels >= kMinStepVoxels))
        fail("stepVoxels", "finite and >= 1/1024 (voxels)", str(o.stepVoxels));
    if (!std::isfinite(o.shadowStepVoxels) || !(o.shadowStepVoxels >= kMinStepVoxels))
        fail("shadowStepVoxels", "finite and >= 1/1024 (voxels)", str(o.shadowStepVoxels));
    const glm::dvec4 b = o.background;
    if (!finite(glm::dvec3(b)) || !std::isfinite(b.w))
        fail("background", "finite", str(b));
    if (!(o.earlyTermination > 0.0 && o.earlyTermination <= 1.0))
        fail("earlyTermination", "in (0, 1]", str(o.earlyTermination));
    if (!std::isfinite(o.ambient) || !(o.ambient >= 0.0)) fail("ambient", "finite and >= 0", str(o.ambient));
    if (!std::isfinite(o.diffuse) || !(o.diffuse >= 0.0)) fail("diffuse", "finite and >= 0", str(o.diffuse));
    if (!(o.anisotropy > -1.0 && o.anisotropy < 1.0)) fail("anisotropy", "in (-1, 1)", str(o.anisotropy));
    const glm::dvec3 s = o.specular;
    if (!finite(s) || !(s.x >= 0.0 && s.y >= 0.0 && s.z >= 0.0))
        fail("specular", "finite and >= 0", str(s));
    if (!std::isfinite(o.shininess) || !(o.shininess > 0.0)) fail("shininess", "finite and > 0", str(o.shininess));
    if (!std::isfinite(o.gradientThreshold) || !(o.gradientThreshold > 0.0))
        fail("gradientThreshold", "finite and > 0", str(o.gradientThreshold));
    if (o.threads < 0) fail("threads", ">= 0 (0: one per hardware thread)", str(o.threads));
    if (!(o.chromaticityConeScale == 0.0 || (o.chromaticityConeScale > 0.0 && o.chromaticityConeScale <= 1.0)))
        fail("chromaticityConeScale", "0 (straight) or in (0, 1]", str(o.chromaticityConeScale));
    if (o.chromaticityWalks < 1) fail("chromaticityWalks", ">= 1", str(o.chromaticityWalks));
}

void validateSize(int width, int height, const char* who) {
    if (width <= 0 || width > kMaxImageSide || height <= 0 || height > kMaxImageSide)
        throw Error(ErrorKind::InvalidArgument, std::string(who) + ": width and height must be in 1.." +
                                                    std::to_string(kMaxImageSide) + ", got " + std::to_string(width) +
                                                    " x " + std::to_string(height));
}

double smoothstep(double edge0, double edge1, double x) {
    const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

// A light prepared for both spaces: shading happens in world space (as on the GPU), shadow
// rays run in model space (where sigma_t is defined).
struct PreparedLight {
    detail::CpuLight world;             // as the mesh references hold it, world space
    glm::dvec3 towardsLightModel{0.0};  // directional: unit, in model space
    glm::dvec3 positionModel{0.0};      // point and spot
    std::vector<detail::LightSweep> sweeps;  // the light volume's, for chromaticityConeScale > 0
};

// Deterministic per sample, so the image does not depend on the thread that renders a row.
struct SampleRng {
    std::uint64_t state;
    SampleRng(glm::dvec3 p, std::size_t light) {
        state = 0x9e3779b97f4a7c15ull * (light + 1);
        for (int a = 0; a < 3; ++a) state = mix(state ^ std::bit_cast<std::uint64_t>(p[a]));
    }
    static std::uint64_t mix(std::uint64_t z) {  // splitmix64's finaliser
        z += 0x9e3779b97f4a7c15ull;
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    double uniform() {
        state = mix(state);
        return static_cast<double>(state >> 11) * 0x1.0p-53;
    }
};

}  // namespace

struct VolumeReference::Impl {
    glm::ivec3 dims{0};
    std::vector<float> raw;  // x fastest: what the GPU texture holds (voxel_storage.h's storedValue)
    double normalise = 1.0;  // raw -> sample (1/255, 1/65535, or 1 for Float32)
    double valueScale = 1.0, valueOffset = 0.0;  // sample -> TF coordinate
    glm::dvec3 boxMin{0.0}, boxMax{0.0}, boxSize{0.0};
    double voxel = 0.0;  // reference length D, model units
    std::vector<glm::dvec4> table;
    glm::dmat4 modelToWorld{1.0}, worldToModel{1.0};
    glm::dmat3 normalToWorld{1.0};
    std::vector<PreparedLight> lights;
    VolumeReferenceOptions options;
    detail::TextureClip volumeClip;  // options.clip in texture coordinates
    glm::dvec3 coneVoxel{0.0};  // the light volume's voxel at chromaticityConeScale
    detail::ChromaticityCone cone;

    // The light volume's sweeps and cone for the options' chromaticityConeScale (none at 0).
    void prepareCone() {
        for (PreparedLight& light : lights) light.sweeps.clear();
        if (!(options.chromaticityConeScale > 0.0)) return;
        const glm::ivec3 lightDims = detail::lightVolumeDims(dims, static_cast<float>(options.chromaticityConeScale));
        coneVoxel = boxSize / glm::dvec3(lightDims);
        cone = detail::chromaticityCone(static_cast<float>(options.anisotropy));
        Bounds box;
        box.extend(glm::vec3(boxMin));
        box.extend(glm::vec3(boxMax));
        for (PreparedLight& light : lights) {
            const Light modelLight = light.world.point ? Light{PointLight{.position = glm::vec3(light.positionModel)}}
                                                       : Light{DirectionalLight{.direction = glm::vec3(-light.towardsLightModel)}};
            light.sweeps = detail::planLightSweeps(modelLight, box, lightDims);
        }
    }

    // s(p) at texture coordinate tc, texel centres at (i+0.5)/n, clamp-to-edge.
    double field(glm::dvec3 tc) const {
        return options.reconstruction == VolumeReconstruction::CubicBSpline ? cubicField(tc) : trilinearField(tc);
    }

    double voxelAt(int x, int y, int z) const {
        return static_cast<double>(raw[static_cast<std::size_t>(x) +
                                       static_cast<std::size_t>(dims.x) *
                                           (static_cast<std::size_t>(y) + static_cast<std::size_t>(dims.y) * z)]);
    }

    // The tensor-product cubic B-spline over the 4^3 voxels around tc.
    double cubicField(glm::dvec3 tc) const {
        int first[3];
        std::array<double, 4> w[3];
        for (int a = 0; a < 3; ++a) {
            const double x = tc[a] * dims[a] - 0.5;
            const double fl = std::floor(x);
            w[a] = detail::cubicBSplineWeights(x - fl);
            first[a] = static_cast<int>(std::clamp(fl, -4.0, static_cast<double>(dims[a]) + 4.0)) - 1;
        }
        auto index = [&](int a, int k) { return std::clamp(first[a] + k, 0, dims[a] - 1); };
        double sum = 0.0;
        for (int k = 0; k < 4; ++k) {
            double plane = 0.0;
            for (int j = 0; j < 4; ++j) {
                double row = 0.0;
                for (int i = 0; i < 4; ++i) row += w[0][i] * voxelAt(index(0, i), index(1, j), index(2, k));
                plane += w[1][j] * row;
            }
            sum += w[2][k] * plane;
        }
        return sum * normalise;
    }

    // GL_LINEAR.
    double trilinearField(glm::dvec3 tc) const {
        int i0[3], i1[3];
        double w[3];
        for (int a = 0; a < 3; ++a) {
            const double f = tc[a] * dims[a] - 0.5;
            const double fl = std::floor(f);
            w[a] = f - fl;
            const int i = static_cast<int>(std::clamp(fl, -1.0, static_cast<double>(dims[a])));
            i0[a] = std::clamp(i, 0, dims[a] - 1);
            i1[a] = std::clamp(i + 1, 0, dims[a] - 1);
        }
        const std::size_t sx = 1, sy = static_cast<std::size_t>(dims.x),
                          sz = static_cast<std::size_t>(dims.x) * static_cast<std::size_t>(dims.y);
        auto at = [&](int x, int y, int z) {
            return static_cast<double>(raw[static_cast<std::size_t>(x) * sx + static_cast<std::size_t>(y) * sy +
                                           static_cast<std::size_t>(z) * sz]);
        };
        const double c00 = at(i0[0], i0[1], i0[2]) + w[0] * (at(i1[0], i0[1], i0[2]) - at(i0[0], i0[1], i0[2]));
        const double c10 = at(i0[0], i1[1], i0[2]) + w[0] * (at(i1[0], i1[1], i0[2]) - at(i0[0], i1[1], i0[2]));
        const double c01 = at(i0[0], i0[1], i1[2]) + w[0] * (at(i1[0], i0[1], i1[2]) - at(i0[0], i0[1], i1[2]));
        const double c11 = at(i0[0], i1[1], i1[2]) + w[0] * (at(i1[0], i1[1], i1[2]) - at(i0[0], i1[1], i1[2]));
        const double c0 = c00 + w[1] * (c10 - c00);
        const double c1 = c01 + w[1] * (c11 - c01);
        return (c0 + w[2] * (c1 - c0)) * normalise;
    }

    glm::dvec3 toTexture(glm::dvec3 p) const { return (p - boxMin) / boxSize; }

    // The medium as the light sees it: without the cut matter unless it casts shadows.
    glm::dvec4 classifyForLight(glm::dvec3 tc) const {
        return volumeClip.lightSeesMedium(tc) ? classifySample(field(tc)) : glm::dvec4(0.0);
    }

    void prepareClip() {
        volumeClip = detail::textureClip(options.clip, glm::mat4(modelToWorld), Bounds{glm::vec3(boxMin), glm::vec3(boxMax)});
    }

    glm::dvec4 classifySample(double sample) const {
        const double x = std::clamp(sample * valueScale + valueOffset, 0.0, 1.0);
        const int n = static_cast<int>(table.size());
        const double f = x * (n - 1);
        const int i = std::min(static_cast<int>(std::floor(f)), n - 2);
        const double t = f - i;
        const glm::dvec4& lo = table[static_cast<std::size_t>(i)];
        const glm::dvec4& hi = table[static_cast<std::size_t>(i) + 1];
        return lo + t * (hi - lo);
    }

    // sigma_t * D from alpha_tf, capped (see kMaxOpticalDepthPerVoxel).
    static double opticalDepthPerVoxel(double alpha) {
        if (!(alpha > 0.0)) return 0.0;
        if (alpha >= 1.0) return kMaxOpticalDepthPerVoxel;
        return std::min(-std::log1p(-alpha), kMaxOpticalDepthPerVoxel);
    }

    // Opacity of a piece `length` (model units) long with TF opacity alpha.
    double pieceOpacity(double alpha, double length) const {
        return -std::expm1(-opticalDepthPerVoxel(alpha) * length / voxel);
    }

    // Clips origin + t * dir, t in [tMin, tMax], to the box; false if nothing is left.
    bool clip(glm::dvec3 origin, glm::dvec3 dir, double& tMin, double& tMax) const {
        return detail::clipToBox(boxMin, boxMax, origin, dir, tMin, tMax);
    }

    // Number of equal pieces of length <= step covering `length`.
    static long pieces(double length, double step) {
        return length > 0.0 ? std::max(1L, static_cast<long>(std::ceil(length / step))) : 0L;
    }

    ReferenceLightSample incident(glm::dvec3 p, const PreparedLight& light) const {
        ReferenceLightSample out;
        out.radiance = light.world.radiance;
        glm::dvec3 dir;
        double tEnd = std::numeric_limits<double>::infinity();
        if (!light.world.point) {
            dir = light.towardsLightModel;
        } else {
            const glm::dvec3 toLight = light.positionModel - p;
            const double distance = glm::length(toLight);
            const glm::dvec3 worldP = glm::dvec3(modelToWorld * glm::dvec4(p, 1.0));
            const glm::dvec3 toLightWorld = light.world.vector - worldP;
            out.radiance = light.world.radiance / std::max(glm::dot(toLightWorld, toLightWorld), 1e-8) *
                           detail::emittedShare(light.world, worldP);
            if (!(distance > 0.0)) return out;
            dir = toLight / distance;
            tEnd = distance;
        }
        double t0 = 0.0;
        if (!clip(p, dir, t0, tEnd)) return out;  // p on the boundary, facing out
        const long m = pieces(tEnd, options.shadowStepVoxels * voxel);
        const double h = tEnd / static_cast<double>(m);
        double l = 1.0;
        glm::dvec3 c(1.0);
        // From the light towards p: c = (1 - a) c + a C_tf is the exact solution of
        // dc/ds = sigma_t (C_tf - c) over a piece with constant sigma_t and C_tf.
        for (long k = 0; k < m; ++k) {
            const double s = tEnd - (static_cast<double>(k) + 0.5) * h;
            const glm::dvec4 tf = classifyForLight(toTexture(p + s * dir));
            if (!(tf.a > 0.0)) continue;
            const double a = pieceOpacity(tf.a, h);
            c = (1.0 - a) * c + a * glm::dvec3(tf);
            l *= 1.0 - a;
        }
        out.transmittance = l;
        out.chromaticity = c;
        // The light volume's cone gather (chromaticityConeScale): only where some light arrives.
        if (options.model == VolumeModel::Paper && !light.sweeps.empty() && l > 1e-6) {
            SampleRng rng(p, static_cast<std::size_t>(&light - lights.data()));
            glm::dvec3 sum(0.0);
            for (int w = 0; w < options.chromaticityWalks; ++w) sum += coneWalk(p, light, rng);
            out.chromaticity = sum / static_cast<double>(options.chromaticityWalks);
        }
        return out;
    }

    // One random walk from p towards the light through the light volume's slice planes: between
    // planes c changes as along a shadow ray; at each plane the walk moves to the crossing or to
    // one of the 8 ring points, drawn with the cone's weights. Its c is an unbiased estimate of
    // what the slice recurrence gives at p.
    glm::dvec3 coneWalk(glm::dvec3 p, const PreparedLight& light, SampleRng& rng) const {
        // The sweep that fills p's voxel: the one whose axis the light travels most along there
        // (a point light inside the volume), else one of the blended sweeps by its weight.
        detail::LightSweep sweep = light.sweeps.front();
        if (sweep.pyramid) {
            const glm::dvec3 travel = (p - light.positionModel) / coneVoxel;
            const glm::dvec3 m = glm::abs(travel);
            sweep.axis = m.x >= m.y && m.x >= m.z ? 0 : (m.y >= m.z ? 1 : 2);
            sweep.reversed = travel[sweep.axis] < 0.0;
        } else if (light.sweeps.size() > 1 && rng.uniform() >= light.sweeps.front().weight) {
            sweep = light.sweeps[1];
        }
        const int a = sweep.axis, u = (a + 1) % 3, v = (a + 2) % 3;
        const double sign = sweep.reversed ? -1.0 : 1.0;  // the light travels towards sign * axis a
        const double ringTexels = std::min(1.0 / coneVoxel[u], 1.0 / coneVoxel[v]);
        const double maxPiece = options.shadowStepVoxels * voxel;
        glm::dvec3 x = p, colour(0.0);
        double through = 1.0;
        // Sweep coordinate in light-volume voxels: planes at integers, the light coming from below.
        const double w = sign > 0.0 ? (x[a] - boxMin[a]) / coneVoxel[a] : (boxMax[a] - x[a]) / coneVoxel[a];
        double plane = std::ceil(w) - 1.0;
        double axisDistance = (w - plane) * coneVoxel[a];  // to the next plane towards the light
        while (plane >= 0.0) {
            glm::dvec3 toLight = light.towardsLightModel;
            double lightDistance = std::numeric_limits<double>::infinity();
            if (light.world.point) {
                toLight = light.positionModel - x;
                lightDistance = glm::length(toLight);
                if (!(lightDistance > 1e-12)) break;
                toLight /= lightDistance;
            }
            const double dz = std::max(-sign * toLight[a], 1e-3);  // along the sweep, per unit path
            const double pathToPlane = axisDistance / dz;
            // The medium up to the plane, or to the box's side or the light if nearer, from p's side.
            const double reach = std::min(pathToPlane, lightDistance);
            double t0 = 0.0, t1 = reach;
            if (!clip(x, toLight, t0, t1)) break;
            const long m = pieces(t1 - t0, maxPiece);
            const double h = (t1 - t0) / static_cast<double>(m);
            for (long k = 0; k < m && through > 1e-4; ++k) {
                const glm::dvec4 tf = classifyForLight(toTexture(x + (t0 + (static_cast<double>(k) + 0.5) * h) * toLight));
                if (!(tf.a > 0.0)) continue;
                const double alpha = pieceOpacity(tf.a, h);
                colour += through * alpha * glm::dvec3(tf);
                through *= 1.0 - alpha;
            }
            // Done at the light, beyond the box's side, at the face the light enters by, or once
            // nothing more can get through.
            if (lightDistance <= pathToPlane || t1 < reach || plane <= 0.0 || through <= 1e-4) break;
            x += pathToPlane * toLight;
            x[a] = sign > 0.0 ? boxMin[a] + plane * coneVoxel[a] : boxMax[a] - plane * coneVoxel[a];
            // The gather at this plane: the ring only where it spans half a texel, as on the GPU.
            const double radius = static_cast<double>(cone.tangent) * (coneVoxel[a] / dz);
            if (radius * ringTexels >= 0.5 && rng.uniform() >= cone.centreWeight) {
                const double angle = std::floor(rng.uniform() * 8.0) * (std::numbers::pi / 4.0);
                x[u] += radius * std::cos(angle);
                x[v] += radius * std::sin(angle);
                if (x[u] < boxMin[u] || x[u] > boxMax[u] || x[v] < boxMin[v] || x[v] > boxMax[v]) break;
            }
            plane -= 1.0;
            axisDistance = coneVoxel[a];
        }
        return colour + through * glm::dvec3(1.0);  // what is left enters unattenuated and white
    }

    struct Normal {
        glm::dvec3 n;
        double strength;
    };

    Normal gradientNormal(glm::dvec3 tc, glm::dvec3 v) const {
        const glm::dvec3 h = 1.0 / glm::dvec3(dims);
        glm::dvec3 g(field(tc + glm::dvec3(h.x, 0, 0)) - field(tc - glm::dvec3(h.x, 0, 0)),
                     field(tc + glm::dvec3(0, h.y, 0)) - field(tc - glm::dvec3(0, h.y, 0)),
                     field(tc + glm::dvec3(0, 0, h.z)) - field(tc - glm::dvec3(0, 0, h.z)));
        g *= 0.5 * valueScale;
        const glm::dvec3 outward = normalToWorld * (-g * glm::dvec3(dims) / boxSize);
        const double len = glm::length(outward);
        glm::dvec3 n = len > 1e-12 ? outward / len : v;
        if (glm::dot(n, v) < 0.0) n = -n;
        return {n, smoothstep(0.0, options.gradientThreshold, glm::length(g))};
    }

    // Unit vector towards the light and the radiance arriving at a world position (lights.glsl).
    static glm::dvec3 towardsLight(const PreparedLight& light, glm::dvec3 worldP, glm::dvec3& radiance) {
        if (!light.world.point) {
            radiance = light.world.radiance;
            return light.world.vector;
        }
        const glm::dvec3 toLight = light.world.vector - worldP;
        const double d2 = std::max(glm::dot(toLight, toLight), 1e-8);
        radiance = light.world.radiance / d2 * detail::emittedShare(light.world, worldP);
        return toLight / std::sqrt(d2);
    }

    glm::dvec3 shade(glm::dvec3 p, glm::dvec3 tc, glm::dvec3 color, const Viewer& viewer) const {
        const ReferenceShading mode = options.shading;
        if (mode == ReferenceShading::EmissionAbsorption) return color;
        const glm::dvec3 worldP = glm::dvec3(modelToWorld * glm::dvec4(p, 1.0));
        const bool gradient = mode == ReferenceShading::Gradient || mode == ReferenceShading::ScatteringGradient;
        glm::dvec3 v(0.0);
        Normal surface{glm::dvec3(0.0), 0.0};
        if (gradient) {
            v = viewer.towards(worldP);
            surface = gradientNormal(tc, v);
        }
        const bool physical = options.model == VolumeModel::Physical &&
                              (mode == ReferenceShading::Scattering || mode == ReferenceShading::ScatteringGradient);
        if (physical && !gradient) v = viewer.towards(worldP);
        glm::dvec3 lit = physical ? glm::dvec3(0.0) : options.ambient * color;
        for (const PreparedLight& light : lights) {
            glm::dvec3 radiance;
            const glm::dvec3 l = towardsLight(light, worldP, radiance);
            if (mode == ReferenceShading::Gradient) {
                const double nDotL = std::max(glm::dot(surface.n, l), 0.0);
                if (nDotL <= 0.0) continue;
                const glm::dvec3 h = glm::normalize(l + v);
                const double spec = std::pow(std::max(glm::dot(surface.n, h), 0.0), options.shininess);
                lit += radiance * (options.diffuse * color * nDotL + options.specular * spec);
                continue;
            }
            const ReferenceLightSample arriving = incident(p, light);
            if (physical) {
                const double g = options.anisotropy;
                const double d = 1.0 + g * g + 2.0 * g * glm::dot(l, v);  // cos theta = -l . v
                const double phase = (1.0 - g * g) / (4.0 * std::numbers::pi * d * std::sqrt(d));
                lit += color * arriving.radiance * (arriving.transmittance * phase);
            } else {
                lit += options.diffuse * color * arriving.radiance * arriving.chromaticity * arriving.transmittance;
            }
            if (mode == ReferenceShading::ScatteringGradient && glm::dot(surface.n, l) > 0.0) {
                const glm::dvec3 h = glm::normalize(l + v);
                lit += surface.strength * arriving.transmittance * radiance * options.specular *
                       std::pow(std::max(glm::dot(surface.n, h), 0.0), options.shininess);
            }
        }
        if (mode == ReferenceShading::Gradient) return color + surface.strength * (lit - color);
        return lit;
    }

    glm::dvec4 tracePixel(const glm::dmat4& inverseViewProjection, glm::dvec2 ndc, const Viewer& viewer) const {
        const glm::dvec4 nearWorld = inverseViewProjection * glm::dvec4(ndc, -1.0, 1.0);
        const glm::dvec4 farWorld = inverseViewProjection * glm::dvec4(ndc, 1.0, 1.0);
        const glm::dvec3 nearModel = glm::dvec3(worldToModel * glm::dvec4(glm::dvec3(nearWorld) / nearWorld.w, 1.0));
        const glm::dvec3 farModel = glm::dvec3(worldToModel * glm::dvec4(glm::dvec3(farWorld) / farWorld.w, 1.0));
        const glm::dvec3 d = farModel - nearModel;
        const double length = glm::length(d);
        glm::dvec3 color(0.0);
        double alpha = 0.0;
        double t0 = 0.0, t1 = length;
        if (length > 0.0 && clip(nearModel, d / length, t0, t1) &&
            volumeClip.clipSpan(toTexture(nearModel), d / length / boxSize, t0, t1)) {
            const glm::dvec3 dir = d / length;
            const long m = pieces(t1 - t0, options.stepVoxels * voxel);
            const double h = (t1 - t0) / static_cast<double>(m);
            for (long k = 0; k < m; ++k) {
                const glm::dvec3 p = nearModel + (t0 + (static_cast<double>(k) + 0.5) * h) * dir;
                const glm::dvec3 tc = toTexture(p);
                const glm::dvec4 tf = classifySample(field(tc));
                if (!(tf.a > 0.0)) continue;
                const double a = pieceOpacity(tf.a, h);
                const glm::dvec3 c = shade(p, tc, glm::dvec3(tf), viewer);
                color += (1.0 - alpha) * a * c;
                alpha += (1.0 - alpha) * a;
                if (alpha >= options.earlyTermination) break;
            }
        }
        const glm::dvec4 bg = options.background;
        return {color + (1.0 - alpha) * glm::dvec3(bg), alpha + (1.0 - alpha) * bg.w};
    }
};

VolumeReference::VolumeReference(const Volume& volume, const TransferFunction& tf, int tfEntries,
                                 const glm::mat4& model, std::vector<Light> lights,
                                 const VolumeReferenceOptions& options) {
    const std::string who = "VolumeReference";
    if (tfEntries < 2 || tfEntries > 65536)
        throw Error(ErrorKind::InvalidArgument,
                    who + ": tfEntries must be in 2..65536, got " + std::to_string(tfEntries));
    const glm::dmat4 m(model);
    bool modelFinite = true;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) modelFinite = modelFinite && std::isfinite(m[c][r]);
    const double det = glm::determinant(m);
    if (!modelFinite || !std::isfinite(det) || det == 0.0)
        throw Error(ErrorKind::InvalidArgument, who + ": the model matrix must be finite and invertible");
    for (std::size_t i = 0; i < lights.size(); ++i) validateLight(lights[i], who + " light " + std::to_string(i));
    validate(options);

    auto impl = std::make_unique<Impl>();
    impl->options = options;
    impl->dims = volume.dims();
    impl->raw.resize(volume.voxelCount());
    // The GPU texture's contents and mapping (GpuVolume::upload, voxel_storage.h).
    const detail::StorageToRaw storage = detail::storageToRaw(volume);
    for (std::size_t i = 0; i < impl->raw.size(); ++i)
        impl->raw[i] = static_cast<float>(detail::storedValue(volume.bytes().data(), volume.type(), i, storage));
    impl->normalise = 1.0 / detail::storedPerSample(volume.type());
    const glm::dvec2 toTf = detail::sampleToTfCoordinate(volume);
    impl->valueScale = toTf.x;
    impl->valueOffset = toTf.y;
    const Bounds box = volume.worldBounds();
    impl->boxMin = glm::dvec3(box.min);
    impl->boxMax = glm::dvec3(box.max);
    impl->boxSize = impl->boxMax - impl->boxMin;
    const glm::dvec3 voxel = impl->boxSize / glm::dvec3(impl->dims);
    impl->voxel = std::min({voxel.x, voxel.y, voxel.z});
    for (const glm::vec4& e : tf.table(tfEntries)) impl->table.emplace_back(e);
    impl->modelToWorld = m;
    impl->worldToModel = glm::inverse(m);
    impl->normalToWorld = glm::transpose(glm::inverse(glm::dmat3(m)));
    const glm::dmat3 worldToModelLinear(impl->worldToModel);
    for (const Light& light : lights) {
        PreparedLight p{detail::toCpuLight(light), {}, {}, {}};
        if (p.world.point)
            p.positionModel = glm::dvec3(impl->worldToModel * glm::dvec4(p.world.vector, 1.0));
        else
            p.towardsLightModel = glm::normalize(worldToModelLinear * p.world.vector);
        impl->lights.push_back(p);
    }
    impl->prepareCone();
    impl->prepareClip();
    m_impl = std::move(impl);
}

VolumeReference::~VolumeReference() = default;
VolumeReference::VolumeReference(VolumeReference&&) noexcept = default;
VolumeReference& VolumeReference::operator=(VolumeReference&&) noexcept = default;

void VolumeReference::setOptions(const VolumeReferenceOptions& options) {
    validate(options);
    m_impl->options = options;
    m_impl->prepareCone();
    m_impl->prepareClip();
}

const VolumeReferenceOptions& VolumeReference::options() const { return m_impl->options; }

double VolumeReference::voxelLength() const { return m_impl->voxel; }

glm::dvec4 VolumeReference::classify(glm::dvec3 modelPoint) const {
    return m_impl->classifyForLight(m_impl->toTexture(modelPoint));
}

double VolumeReference::extinction(glm::dvec3 modelPoint) const {
    return Impl::opticalDepthPerVoxel(classify(modelPoint).a) / m_impl->voxel;
}

ReferenceLightSample VolumeReference::incidentLight(glm::dvec3 modelPoint, std::size_t light) const {
    if (light >= m_impl->lights.size())
        throw Error(ErrorKind::InvalidArgument, "VolumeReference::incidentLight: light " + std::to_string(light) +
                                                    " is out of range (" + std::to_string(m_impl->lights.size()) +
                                                    " lights)");
    return m_impl->incident(modelPoint, m_impl->lights[light]);
}

Image VolumeReference::render(const Camera& camera, int width, int height) const {
    validateSize(width, height, "VolumeReference::render");
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    const glm::dmat4 inverseViewProjection =
        glm::inverse(glm::dmat4(camera.projection(aspect)) * glm::dmat4(camera.view()));
    const Viewer viewer{glm::dvec3(camera.position()), glm::dvec3(camera.forward()),
                        camera.projectionType() == Projection::Orthographic};
    Image image(width, height);

    detail::parallelFor(
        m_impl->options.threads, height, [] { return 0; },
        [&](int&, std::int64_t row) {
            const int y = static_cast<int>(row);
            for (int x = 0; x < width; ++x) {
                const glm::dvec2 ndc((x + 0.5) / width * 2.0 - 1.0, 1.0 - (y + 0.5) / height * 2.0);
                image.at(x, y) = glm::vec4(m_impl->tracePixel(inverseViewProjection, ndc, viewer));
            }
        },
        [](int) {});
    return image;
}

Image renderVolumeReference(const Volume& volume, const TransferFunction& tf, int tfEntries, const glm::mat4& model,
                            const std::vector<Light>& lights, const Camera& camera, int width, int height,
                            const VolumeReferenceOptions& options) {
    validateSize(width, height, "renderVolumeReference");
    return VolumeReference(volume, tf, tfEntries, model, lights, options).render(camera, width, height);
}

ConvergedReference renderVolumeReferenceConverged(const Volume& volume, const TransferFunction& tf, int tfEntries,
                                                  const glm::mat4& model, const std::vector<Light>& lights,
                                                  const Camera& camera, int width, int height,
                                                  const VolumeReferenceOptions& options, double tolerance,
                                                  double startStepVoxels, double minStepVoxels) {
    const std::string who = "renderVolumeReferenceConverged: ";
    validateSize(width, height, "renderVolumeReferenceConverged");
    if (!std::isfinite(tolerance) || !(tolerance > 0.0))
        throw Error(ErrorKind::InvalidArgument, who + "tolerance must be finite and > 0, got " + str(tolerance));
    if (!std::isfinite(startStepVoxels) || !std::isfinite(minStepVoxels) || !(minStepVoxels >= kMinStepVoxels) ||
        !(minStepVoxels <= startStepVoxels))
        throw Error(ErrorKind::InvalidArgument, who + "need 1/1024 <= minStepVoxels <= startStepVoxels, got " +
                                                    str(minStepVoxels) + " and " + str(startStepVoxels));
    validate(options);
    const double shadowRatio = options.shadowStepVoxels / options.stepVoxels;
    VolumeReferenceOptions o = options;
    auto withStep = [&](double step) {
        o.stepVoxels = step;
        o.shadowStepVoxels = std::max(step * shadowRatio, kMinStepVoxels);
        return o;
    };
    VolumeReference reference(volume, tf, tfEntries, model, lights, withStep(startStepVoxels));
    ConvergedReference result{reference.render(camera, width, height), startStepVoxels, o.shadowStepVoxels,
                              std::numeric_limits<double>::infinity(), 1, false};
    while (result.stepVoxels * 0.5 >= minStepVoxels) {
        const double step = result.stepVoxels * 0.5;
        reference.setOptions(withStep(step));
        Image next = reference.render(camera, width, height);
        result.lastChange = computeErrorMetrics(next, result.image).relRmse;
        result.image = std::move(next);
        result.stepVoxels = step;
        result.shadowStepVoxels = o.shadowStepVoxels;
        ++result.renders;
        if (result.lastChange < tolerance) {
            result.converged = true;
            break;
        }
    }
    return result;
}

}  // namespace sss
