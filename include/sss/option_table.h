#pragma once
/// @file
/// The renderers' options, each declared once: its name (the C++ member, the scene-file key and,
/// in snake_case, the Python keyword), one line of help, its valid range and its command-line
/// flag. validate(), scene files, the command lines of sss-render, sss-viewer and sss-bench with
/// their --help, and the Python module all read these tables; each default is the struct's own.
/// Adding an option is one field in its struct and one line here.
#include "sss/api.h"
#include "sss/hybrid_compositor.h"
#include "sss/mesh_scattering_renderer.h"
#include "sss/volume_scattering_renderer.h"

#include <limits>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>

SSS_BEGIN_API

namespace sss {

/// The values a numeric field accepts (every component of a vector). Floating-point values must
/// also be finite.
struct OptionRange {
    double min = -std::numeric_limits<double>::infinity();
    double max = std::numeric_limits<double>::infinity();
    bool minExclusive = false;
    bool maxExclusive = false;
};

constexpr OptionRange atLeast(double min) { return {.min = min}; }
constexpr OptionRange above(double min) { return {.min = min, .minExclusive = true}; }
/// [min, max], with either end open on request: between(0, 1, true) is (0, 1].
constexpr OptionRange between(double min, double max, bool minExclusive = false, bool maxExclusive = false) {
    return {min, max, minExclusive, maxExclusive};
}

/// One field of the options struct Owner.
template <class Owner, class T>
struct OptionField {
    T Owner::*member;
    std::string_view name;  ///< the member's name: scene-file key; Python keyword in snake_case
    std::string_view help;  ///< one line: what it does
    OptionRange range{};    ///< numbers: the values accepted
    /// The command-line flag ("--cameras"), empty if none. For a bool, a switch that sets the
    /// opposite of the default ("--no-jitter" for a default of true).
    std::string_view flag{};
    std::string_view valueName{};  ///< its value in --help ("K"; enums list their names)
    std::string_view unit{};       ///< appended to messages: "finite and > 0 (voxels)"
};

/// The fields of an options struct, in order: OptionTable<Owner>::fields is a tuple of
/// OptionField, OptionTable<Owner>::name the struct's name for messages.
template <class Owner>
struct OptionTable;

/// Calls f(field) for each OptionField of Owner.
template <class Owner, class F>
constexpr void forEachOptionField(F&& f) {
    std::apply([&f](const auto&... field) { (f(field), ...); }, OptionTable<Owner>::fields);
}

/// "in 1..32", "finite and > 0", "in (0, 1]", ">= 1": a range as messages and help say it.
std::string describeRange(const OptionRange& range, bool integer);

/// "cameras" -> "cameras", "mapResolution" -> "map_resolution" (the Python keyword).
std::string snakeCase(std::string_view name);

template <>
struct OptionTable<MeshRenderOptions> {
    using O = MeshRenderOptions;
    static constexpr std::string_view name = "MeshRenderOptions";
    static constexpr std::tuple fields{
        OptionField<O, MeshShading>{&O::shading, "shading", "Blinn-Phong baseline or subsurface scattering"},
        OptionField<O, ScatteringProfile>{&O::profile, "profile",
            "subsurface profile: calibrated (the directional dipole rescaled to a random walk, plus single "
            "scattering) or dipole (the paper's, as the thesis)", {}, "--profile"},
        OptionField<O, MeshCombine>{&O::combine, "combine",
            "auto (vertex-estimate on meshes fine against the diffusion length, per-pixel on coarse ones), "
            "per-pixel (the K maps looked up at every pixel), per-vertex (resolved once per vertex after each map "
            "update: fixed frames cost about a Blinn-Phong frame) or vertex-estimate (evaluate-once: no maps, the "
            "radiosity estimated at each vertex; needs a finely tessellated mesh)", {}, "--combine"},
        OptionField<O, int>{&O::cameras, "cameras", "scattering maps K", between(1, 32), "--cameras", "K"},
        OptionField<O, int>{&O::samples, "samples", "samples per texel and frame", between(1, 4096), "--samples", "N"},
        OptionField<O, int>{&O::mapResolution, "mapResolution", "scattering-map side in texels", between(16, 8192)},
        OptionField<O, int>{&O::lightMapResolution, "lightMapResolution", "light-buffer side in texels",
                            between(16, 8192)},
        OptionField<O, double>{&O::millimetresPerUnit, "millimetresPerUnit", "millimetres per scene unit", above(0),
                               "--scale", "MM"},
        OptionField<O, float>{&O::sampleRadius, "sampleRadius", "sampling-disk radius in scene units; 0 chooses",
                              atLeast(0)},
        OptionField<O, float>{&O::spread, "spread", "spreads the samples: sigma* = min(sigma_tr) / spread",
                              atLeast(0.1)},
        OptionField<O, float>{&O::nearField, "nearField",
            "radius of the vertex estimate's near field, in mesh edge lengths (1: life-size meshes); 0: off",
            atLeast(0), "--near-field", "EDGES"},
        OptionField<O, float>{&O::nearFieldSpacing, "nearFieldSpacing",
            "near field evaluated once per light change at points this many light-buffer texels apart, read by "
            "camera moves; 0: per pixel every frame", atLeast(0), "--near-field-spacing", "TEXELS"},
        OptionField<O, int>{&O::accumulationFrames, "accumulationFrames", "frames accumulated into the scattering maps",
                            atLeast(1), "--frames", "F"},
        OptionField<O, float>{&O::depthBias, "depthBias", "visibility depth bias of the map lookup, in texels",
                              atLeast(0)},
        OptionField<O, float>{&O::seamShrink, "seamShrink", "seam shrink of the map lookup, in texels", atLeast(0)},
        OptionField<O, float>{&O::specular, "specular", "specular highlight weight; 0 turns it off", atLeast(0)},
        OptionField<O, float>{&O::shininess, "shininess", "highlight exponent", above(0)},
        OptionField<O, glm::vec3>{&O::environment, "environment",
            "radiance of a uniform environment lighting the translucent mesh, so faces the light misses are not "
            "black", atLeast(0), "--environment", "R,G,B"},
        OptionField<O, bool>{&O::finishEachPass, "finishEachPass", "wait for the GPU after each pass (timings)"},
        OptionField<O, bool>{&O::gpuPassTimes, "gpuPassTimes", "GL timestamps around each pass (GPU time per pass in the stats)"},
    };
};

template <>
struct OptionTable<VolumeRenderOptions> {
    using O = VolumeRenderOptions;
    static constexpr std::string_view name = "VolumeRenderOptions";
    static constexpr std::tuple fields{
        OptionField<O, VolumeShading>{&O::shading, "shading", "emission-absorption, gradient, scattering or both"},
        OptionField<O, float>{&O::stepSize, "stepSize", "ray step in voxels", above(0), "--step", "VOXELS", "voxels"},
        OptionField<O, float>{&O::earlyTermination, "earlyTermination", "stop rays at this opacity",
                              between(0, 1, true), "--early-termination", "A"},
        OptionField<O, bool>{&O::jitter, "jitter", "per-pixel ray offset against wood grain", {}, "--no-jitter"},
        OptionField<O, bool>{&O::preintegration, "preintegration",
            "pre-integrated classification; off: classify each sample alone (the thesis's post-classification)",
            {}, "--no-preintegration"},
        OptionField<O, bool>{&O::emptySpaceSkipping, "emptySpaceSkipping",
                             "skip transparent bricks (same image, faster)", {}, "--no-skipping"},
        OptionField<O, VolumeReconstruction>{&O::reconstruction, "reconstruction",
            "the field between voxels: trilinear, or cubic (the smooth cubic B-spline: no voxel terraces, about 3x "
            "the ray-cast cost)", {}, "--reconstruction"},
        OptionField<O, int>{&O::transferFunctionEntries, "transferFunctionEntries",
                            "entries of the transfer-function table", between(2, 65536)},
        OptionField<O, float>{&O::ambient, "ambient", "ambient fraction of the TF colour", atLeast(0)},
        OptionField<O, float>{&O::diffuse, "diffuse", "diffuse fraction of the TF colour", atLeast(0)},
        OptionField<O, float>{&O::emission, "emission", "self-illumination fraction of the TF colour", atLeast(0)},
        OptionField<O, glm::vec3>{&O::specular, "specular", "gradient highlight colour", atLeast(0)},
        OptionField<O, float>{&O::shininess, "shininess", "gradient highlight exponent", above(0)},
        OptionField<O, float>{&O::gradientThreshold, "gradientThreshold",
                              "gradient magnitude at which shading is fully on", above(0)},
        OptionField<O, bool>{&O::gradientVolume, "gradientVolume",
            "gradient modes read a gradient volume computed once (4 bytes per voxel for 8-bit data, "
            "else 8); off: gradients per sample",
            {}, "--no-gradient-volume"},
        OptionField<O, float>{&O::lightVolumeScale, "lightVolumeScale", "light-volume resolution relative to the data",
                              between(0, 1, true), "--light-volume-scale", "S"},
        OptionField<O, float>{&O::lightVolumePreviewScale, "lightVolumePreviewScale",
            "interactive light editing: the first frame after a light-volume change builds it at this scale, the "
            "next at --light-volume-scale; 0 = off", between(0, 1), "--light-volume-preview", "S"},
        OptionField<O, float>{&O::lightVolumeReach, "lightVolumeReach",
            "light-volume texels towards the light at which each sample reads the light volume, then carries the "
            "light back through the data", between(0, 16), "--light-volume-reach", "T"},
        OptionField<O, int>{&O::lightSweepSlices, "lightSweepSlices",
            "slices each light-volume dispatch advances at most, 0 = the measured choice (fewer dispatches, more "
            "arithmetic)", between(0, 16), "--light-sweep-slices", "N"},
        OptionField<O, LightPropagation>{&O::lightPropagation, "lightPropagation",
            "light-volume propagation: sweep (slice by slice), doubling (ray segments doubled per dispatch: about "
            "log2 of the slices) or auto (per device: doubling on hardware GPUs)", {}, "--light-propagation"},
        OptionField<O, LightVolumeFallback>{&O::lightVolumeFallback, "lightVolumeFallback",
            "when the light volume does not fit the GPU: halve its resolution until it fits, with a warning, or "
            "fail", {}, "--light-volume-fallback"},
        OptionField<O, float>{&O::anisotropy, "anisotropy", "Henyey-Greenstein g for the scattering cone",
                              between(-1, 1, true, true), "--anisotropy", "G"},
        OptionField<O, VolumeModel>{&O::model, "model",
            "paper (Ropinski: ambient + diffuse x light-volume colour) or physical (single scattering: TF colour as "
            "albedo x phase function x light; about 4 pi dimmer, raise --light-intensity or --exposure)", {},
            "--volume-model"},
        OptionField<O, bool>{&O::eyePass, "eyePass", "add the second, view-dependent pass towards the viewer", {},
                             "--eye-pass"},
        OptionField<O, float>{&O::eyePassStrength, "eyePassStrength", "weight of the eye pass", atLeast(0)},
        OptionField<O, bool>{&O::multipleScattering, "multipleScattering",
            "progressive GPU path tracing of all orders of scattering (the physical model)", {},
            "--multiple-scattering"},
        OptionField<O, int>{&O::samplesPerFrame, "samplesPerFrame",
                            "paths per pixel each render adds with multipleScattering", between(1, 4096)},
        OptionField<O, int>{&O::maxBounces, "maxBounces",
            "with --multiple-scattering: scatterings per path (1 = single scattering; Russian roulette ends paths "
            "earlier)", atLeast(1), "--max-bounces", "B"},
        OptionField<O, bool>{&O::multipleScatteringCache, "multipleScatteringCache",
            "add light scattered more than once from a view-independent photon-traced cache (the physical model)", {},
            "--multiple-scattering-cache"},
        OptionField<O, int>{&O::cacheResolution, "cacheResolution",
                            "multiple-scattering cache cells along the box's longest side (finer: more accurate once refined, "
                            "slightly worse first frames, 8 times the memory per doubling)",
                            between(1, 1024),
                            "--cache-resolution", "N"},
        OptionField<O, int>{&O::cachePhotonsPerFrame, "cachePhotonsPerFrame",
                            "photons each render adds while the multiple-scattering cache refines", between(1, 1 << 24),
                            "--cache-photons-per-frame", "N"},
        OptionField<O, int>{&O::cachePhotons, "cachePhotons",
                            "photons after which the multiple-scattering cache stops refining", between(1, 1 << 30),
                            "--cache-photons", "N"},
        OptionField<O, CacheViewEvaluation>{&O::cacheViewEvaluation, "cacheViewEvaluation",
            "where the multiple-scattering cache's light towards the viewer is evaluated: per-cell (once per camera "
            "move), per-sample, or auto (per device and target size)", {}, "--cache-view-evaluation"},
        OptionField<O, RayCaster>{&O::rayCaster, "rayCaster",
            "ray caster: fragment (fullscreen triangle), compute (dispatch over the volume's screen rectangle) or auto "
            "(per device: compute on hardware GPUs)", {}, "--ray-caster"},
        OptionField<O, bool>{&O::finishEachPass, "finishEachPass", "wait for the GPU after each pass (timings)"},
        OptionField<O, bool>{&O::gpuPassTimes, "gpuPassTimes", "GL timestamps around each pass (GPU time per pass in the stats)"},
    };
};

template <>
struct OptionTable<HybridOptions> {
    using O = HybridOptions;
    static constexpr std::string_view name = "HybridOptions";
    static constexpr std::tuple fields{
        OptionField<O, glm::vec4>{&O::background, "background", "clear colour, linear RGBA"},
        OptionField<O, bool>{&O::cornellBox, "cornellBox", "surround the content with a Cornell box"},
        OptionField<O, bool>{&O::meshShadowsInVolumes, "meshShadowsInVolumes", "meshes shadow the volumes"},
        OptionField<O, bool>{&O::meshShadowsOnMeshes, "meshShadowsOnMeshes", "meshes shadow meshes and the box"},
        OptionField<O, bool>{&O::volumeShadowsOnMeshes, "volumeShadowsOnMeshes",
                             "volumes tint and dim the light reaching meshes"},
        OptionField<O, int>{&O::shadowMapResolution, "shadowMapResolution", "the meshes' shadow maps, texels per side",
                            between(64, 8192)},
        OptionField<O, bool>{&O::clearTarget, "clearTarget", "clear the target before drawing; off: draw over it"},
    };
};

namespace detail {
/// Where a range check is: the field, its range, and whether it is one component of a vector.
struct OptionCheck {
    std::string_view owner, field;
    OptionRange range;
    std::string_view unit;
    bool vector = false;
};
// Throw Error(InvalidArgument, owner, field, reason) if the value breaks the range.
void checkOptionValue(const OptionCheck& check, int value);
void checkOptionValue(const OptionCheck& check, float value);
void checkOptionValue(const OptionCheck& check, double value);
}  // namespace detail

/// Checks every numeric field of `options` against its table's range, in table order. Throws
/// Error(InvalidArgument) with field() and reason() set, e.g. "MeshRenderOptions::cameras must
/// be in 1..32, got 0".
template <class Owner>
void validateOptionRanges(const Owner& options) {
    forEachOptionField<Owner>([&options](const auto& field) {
        using T = std::remove_cvref_t<decltype(options.*field.member)>;
        const T& value = options.*field.member;
        detail::OptionCheck check{OptionTable<Owner>::name, field.name, field.range, field.unit};
        if constexpr (std::is_same_v<T, int> || std::is_floating_point_v<T>) {
            detail::checkOptionValue(check, value);
        } else if constexpr (std::is_same_v<T, glm::vec3> || std::is_same_v<T, glm::vec4>) {
            check.vector = true;
            for (int i = 0; i < T::length(); ++i) detail::checkOptionValue(check, value[i]);
        }
    });
}

}  // namespace sss

SSS_END_API
