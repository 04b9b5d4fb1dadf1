#pragma once
/// @file
/// Renders a scalar volume by single-pass GPU ray casting with a transfer function. Modes:
///  - VolumeShading::EmissionAbsorption: transfer-function colour and opacity only;
///  - VolumeShading::Gradient: plus Blinn-Phong shading with normals from central differences;
///  - VolumeShading::Scattering: light from a light volume (Ropinski, Doering, Rezk-Salama 2010):
///    per light, the chromaticity c and intensity l of the light arriving at each point,
///    propagated slice by slice from the light, with hard shadows in l and the colour of the
///    medium the light crossed, blurred over a forward cone, in c. A sample of TF colour C is
///    shaded C * (ambient + emission + diffuse * sum_lights E * c * l);
///  - VolumeShading::ScatteringGradient: Scattering plus gradient Blinn-Phong highlights, each
///    dimmed by l.
/// EmissionAbsorption and Gradient are the thesis's "scattering off" baselines.
///
/// Optical model shared by every mode: the TF opacity alpha is defined per voxel length (the
/// smallest voxel edge), i.e. extinction sigma_t = -ln(1 - alpha) per voxel; the ray step and the
/// light propagation both correct opacity for their own path lengths.

#include "sss/api.h"
#include "sss/camera.h"
#include "sss/light.h"
#include "sss/render_target.h"
#include "sss/stats.h"
#include "sss/transfer_function.h"
#include "sss/volume.h"
#include "sss/volume_clip.h"

#include <glm/mat4x4.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

SSS_BEGIN_API

namespace sss {

namespace detail {
struct SSS_INTERNAL VolumeRendererAccess;  // hybrid-scene hooks (src/hybrid/shared_lighting.h)
}

enum class VolumeShading { EmissionAbsorption, Gradient, Scattering, ScatteringGradient };

/// What a lit sample scatters towards the viewer in the light-volume modes (Scattering,
/// ScatteringGradient).
enum class VolumeModel {
    /// The paper's (Ropinski et al. 2010): C_tf (ambient + diffuse E c l), an ambient term as
    /// emission, a constant diffuse factor and the light volume's chromaticity c (default).
    Paper,
    /// Physical single scattering: C_tf (the single-scattering albedo) E l p_HG(anisotropy,
    /// cos theta), the Henyey-Greenstein phase function (per steradian) between the light's
    /// direction of travel and the direction to the viewer; no ambient, no emission, no
    /// chromaticity (its light volume carries the intensity l alone, a cheaper sweep), no eye
    /// pass. What renderVolumePathTraced() computes in its single-scattering
    /// mode. About 4 pi dimmer than the paper's model at diffuse 1 (the phase function is per
    /// steradian): raise the light or the exposure.
    Physical,
};

/// "paper" or "physical".
std::string_view toString(VolumeModel model);
/// Parses "paper" or "physical"; nullopt otherwise.
std::optional<VolumeModel> parseVolumeModel(std::string_view name);

/// Which ray caster draws the volume. Both cast the same rays with the same shader code and give
/// the same image (within 1/255); they differ in how the GPU runs them.
enum class RayCaster {
    /// Picked per device from measurements (benchmarks/README.md, "Fragment or compute"): compute
    /// on hardware GPUs, whose datacenter parts run fragment work on a fraction of the chip;
    /// fragment on software rasterisers, where it is measured faster.
    Auto,
    /// A fullscreen triangle whose fragments are blended over the target (the thesis's way).
    Fragment,
    /// A compute dispatch over the volume's screen rectangle that composites into the target's
    /// colour through image load/store.
    Compute,
};

/// Where the multiple-scattering cache's light towards the viewer is evaluated
/// (docs/multiple-scattering.md, "Towards the viewer"). Both evaluate the same lobe; per cell, the
/// products of the cells' values interpolate, per sample the values do (images within about 1 %).
enum class CacheViewEvaluation {
    /// Per device and target size: per cell on hardware GPUs, whose compute runs the pass over
    /// the cells on the whole chip; on software rasterisers per cell where the cache's cells (at
    /// cacheResolution) are at most kCacheCellsPerPixel times the target's pixels, per sample
    /// where they are more.
    Auto,
    /// Once per cell of the level read and camera move (a compute pass); samples read three
    /// textures and do a multiply-add.
    PerCell,
    /// At every shaded sample, from the cache's five textures.
    PerSample,
};

/// CacheViewEvaluation::Auto's threshold on software rasterisers: on llvmpipe, with the bonsai
/// at the default step, per sample was faster above 6-10 cells per pixel
/// (docs/multiple-scattering.md, "Towards the viewer").
inline constexpr double kCacheCellsPerPixel = 8.0;

/// How the light volume is carried from the light through the medium
/// (docs/light-volume-sweep.md). Both give the light arriving at each voxel along the ray to the
/// light, through the same medium samples and the same colour cone.
enum class LightPropagation {
    /// Picked per device from measurements (docs/light-volume-sweep.md, "Ray doubling"):
    /// Doubling on hardware GPUs, Sweep on software rasterisers.
    Auto,
    /// Slice by slice away from the light (Ropinski et al. 2010): one dependent step per slice,
    /// each a GPU-wide wait, and a cubic lookup of the previous slice per voxel.
    Sweep,
    /// Ray doubling: each voxel's segment towards the light doubles in length per dispatch,
    /// joined with the segment beyond it, so a 256^3 light volume takes 10 dispatches (19 with
    /// the paper model's colour, computed at half resolution). Rays are straight, as the CPU
    /// reference's shadow rays; each level's lookup is linear, and the colour cone blurs per
    /// level instead of per slice (lightSweepSlices does not apply).
    Doubling,
};

/// What the renderer does when a light volume does not fit the GPU at the requested
/// resolution (a side over GL_MAX_3D_TEXTURE_SIZE, the memory budget, or GL_OUT_OF_MEMORY).
enum class LightVolumeFallback {
    /// Halve the light-volume resolution until it fits, logging a warning that names the size
    /// asked, the limit and the resolution used (VolumeScatteringRenderer::lightVolumeScaleInUse).
    Reduce,
    /// Throw the Error(ErrorKind::GpuLimit).
    Fail,
};

struct VolumeRenderOptions {
    VolumeShading shading = VolumeShading::EmissionAbsorption;
    /// Distance between samples along a ray, in voxels of the smallest spacing, > 0. Opacity is
    /// corrected so the image does not darken or brighten as the step changes. With
    /// pre-integration, half a voxel keeps the light volume's modes within about 5 % of their
    /// CPU reference on bucky, bonsai and the engine (sss-bench --accuracy light-volume); the
    /// thesis used 1 (default: 0.5).
    float stepSize = 0.5f;
    /// Rays stop once their accumulated opacity reaches this, in (0, 1] (default: 0.99).
    float earlyTermination = 0.99f;
    /// Offsets each ray's first sample by a per-pixel amount against wood-grain (default: on).
    bool jitter = true;
    /// Pre-integrated classification (Engel, Kraus & Ertl 2001): each sample stands for the ray
    /// segment since the previous one, with the colour and opacity the transfer function
    /// integrates to over every value the data passes through between the two (taken as linear),
    /// read from a 256 x 256 table rebuilt when the transfer function or the step changes. A
    /// point-sampled steep transfer function misses thin structures that fall between samples
    /// (wood grain and moire, or noise once jittered); this catches them at the same step, for
    /// one 2D lookup instead of a 1D one per sample. Off: the transfer function at the sample
    /// alone (the thesis's post-classification) (default: on).
    bool preintegration = true;
    /// Jump over 8^3-voxel bricks the transfer function makes fully transparent: the ray caster
    /// skips their samples, and the light-volume sweep the medium samples of voxels surrounded
    /// by them. The samples taken, and so the image and the light volume, are the same as
    /// without it (default: on).
    bool emptySpaceSkipping = true;
    /// The field between voxel centres, in every pass: trilinear, or the smooth cubic B-spline
    /// that removes the voxel staircase's terraces at about 3x the cost of a ray-cast frame
    /// (default: Trilinear; see VolumeReconstruction).
    VolumeReconstruction reconstruction = VolumeReconstruction::Trilinear;
    /// Entries of the transfer-function lookup table, 2..65536 (default: 256).
    int transferFunctionEntries = 256;
    // Shading (every mode but EmissionAbsorption):
    float ambient = 0.25f;           ///< ambient fraction of the TF colour (default: 0.25)
    float diffuse = 0.85f;           ///< diffuse fraction of the TF colour (default: 0.85)
    /// Self-illumination: this fraction of the TF colour is added whatever the light (default: 0).
    float emission = 0.0f;
    // Gradient highlights (Gradient, ScatteringGradient):
    glm::vec3 specular{0.3f};        ///< specular colour (default: 0.3)
    float shininess = 32.0f;         ///< Blinn-Phong exponent, > 0 (default: 32)
    /// Gradient magnitude (value change per voxel, 0..1 scale) at which shading is fully on;
    /// weaker gradients fade to the unshaded colour (default: 0.02).
    float gradientThreshold = 0.02f;
    /// Gradient modes read the gradient from a volume computed once per data set (central
    /// differences per voxel and, for 8- and 16-bit data, the value itself: RGBA8, 4 bytes per
    /// voxel, 64 MiB for 256^3 of 8-bit data, RGBA16 and 8 bytes for the rest; the gradient the
    /// on-the-fly path computes, to half an 8-bit data value, from one texel instead of six,
    /// and the same texel gives the sample's value). If it does not fit
    /// the GPU (limits or memory budget), a warning says so and the gradients are computed on the
    /// fly (default: on).
    bool gradientVolume = true;
    // Light volume (Scattering, ScatteringGradient):
    /// Light-volume resolution relative to the data, in (0, 1] (default: 1, as the thesis).
    float lightVolumeScale = 1.0f;
    /// For interactive light editing on slow devices: the first render() after a change of
    /// what the light volume depends on (lights, transfer function, volume, model transform,
    /// clip, these options) builds it at this resolution scale instead, and the next render()
    /// that changes none of it builds it at lightVolumeScale. 0, or a value at or above
    /// lightVolumeScale, builds it at lightVolumeScale at once. lightVolumePreviewed() says
    /// which the last frame drew. Measured in sss-bench --table 5.4 (its error against the
    /// full light volume and its time) (default: 0, off).
    float lightVolumePreviewScale = 0.0f;
    /// How far towards the light, in light-volume texels (0..16), each sample reads the light
    /// volume; the light is then carried back to the sample through the data at one-voxel
    /// steps. Interpolating the light volume next to a dense or thin structure mixes in the dark
    /// voxels inside it; reading it clear of the structure removes that error (rings and too
    /// little light on lit surfaces) at the cost of that many extra samples per light. Measured
    /// on llvmpipe against the CPU reference (sss-bench --accuracy light-volume): 4 texels
    /// brings bucky, bonsai and the engine to 5-6 % at step 0.25 (default: 4).
    float lightVolumeReach = 4.0f;
    /// Slices each compute dispatch of the light-volume sweep advances at most, 1..16, or 0 for
    /// the measured choice (docs/light-volume-sweep.md): 4 for the physical model's
    /// intensity-only sweep on hardware GPUs (1.16-1.19x faster on an H100), else 1. Each
    /// dispatch waits for the whole GPU; with several slices per dispatch each workgroup
    /// recomputes the margins of its tile that its later slices look up. Two or more give the
    /// same light volume texel for texel; one filters with the texture unit (within 1e-2).
    /// Lights whose sideways reach per slice is too wide (inside the volume, or a blended sweep
    /// nearly along its slices) always take one (default: 0).
    int lightSweepSlices = 0;
    /// Sweep or ray doubling, or picked per device (default: Auto; see LightPropagation). The
    /// eye pass always sweeps.
    LightPropagation lightPropagation = LightPropagation::Auto;
    /// When the light volume does not fit the GPU (default: Reduce, with a warning).
    LightVolumeFallback lightVolumeFallback = LightVolumeFallback::Reduce;
    /// Henyey-Greenstein g in (-1, 1): the forward cone over which the light's colour is blurred
    /// holds half of the phase function's energy; g <= 0 gives the widest cone, 60 degrees
    /// (default: 0.5, about 47 degrees).
    float anisotropy = 0.5f;
    /// The paper's shading or physical single scattering (default: Paper; see VolumeModel).
    VolumeModel model = VolumeModel::Paper;
    /// The optional second pass towards the viewer: the light each voxel scatters is propagated
    /// from the far side towards the eye with the same cone blur, and each sample gains
    /// diffuse * eyePassStrength * TF colour * that blurred light from behind it (forward
    /// scattering towards the viewer, a second-order term). View-dependent: rerun whenever the
    /// view direction changes (default: off).
    bool eyePass = false;
    float eyePassStrength = 1.0f;  ///< >= 0 (default: 1)
    // Multiple scattering (VolumeShading::Scattering with VolumeModel::Physical only):
    /// Progressive GPU path tracing of all orders of scattering instead of the light volume's
    /// single scattering: the quantity renderVolumePathTraced() computes in its
    /// MultipleScattering mode (same medium, camera rays, lights and HG phase with g =
    /// anisotropy), by the same estimator (delta tracking against a majorant per 8^3 brick,
    /// next-event estimation with ratio tracking, Russian roulette). Each render() adds
    /// samplesPerFrame paths per pixel to a running mean that the renderer keeps while nothing
    /// changes (camera, target size, lights, transfer function, volume, model transform, these
    /// options) and restarts otherwise; accumulatedSamples() says how many it holds. A change of
    /// the lights' colour or intensity alone, alike for every light (one light's, or all scaled
    /// by one factor per channel), keeps the mean and scales it, unless it lights a channel that
    /// was dark in every light. Rays go through pixel centres (as the CPU's); the first frame
    /// shows its first samples, noisy.
    /// Meshes of a hybrid scene clip the camera rays and, with HybridOptions::meshShadowsInVolumes,
    /// block the lights' next-event terms where their shadow maps say so (light scattered by the
    /// medium passes through them); a change of those maps restarts the mean (default: off).
    bool multipleScattering = false;
    /// Paths per pixel each render() adds in the multiple-scattering mode, 1..4096 (default: 1).
    int samplesPerFrame = 1;
    /// Scatterings after which a path ends, >= 1: 1 is single scattering (default: 100000, as
    /// VolumePathTracerOptions::maxBounces; Russian roulette ends paths long before).
    int maxBounces = 100000;
    // Multiple-scattering cache (VolumeShading::Scattering or ScatteringGradient with
    // VolumeModel::Physical; docs/multiple-scattering.md):
    /// Adds the light scattered more than once to the light volume's single scattering, from a
    /// view-independent cache: per cell of a grid over the box, the fluence of the light that has
    /// scattered at least once, its first and second angular moments, and the slope of the light
    /// scattered once against the direct light; each sample scatters it towards the eye with the
    /// phase function, its fluence moved by its own direct light along that slope. Photons from the
    /// lights fill it by the path tracer's estimator (delta tracking, HG scattering, Russian
    /// roulette; maxBounces and anisotropy apply), cachePhotonsPerFrame per render()
    /// until it holds cachePhotons; camera moves reuse it, and a change of the lights, transfer
    /// function, volume, model transform, clip or these options restarts it (a change of the
    /// lights' radiance alone keeps and scales it, as the path tracer's mean). In a hybrid scene
    /// with HybridOptions::meshShadowsInVolumes, a photon stops at a mesh between its light and
    /// its first scattering (the meshes' shadow maps), and a change of those maps restarts it; light
    /// scattered by the medium passes through meshes, as the path tracer's. Its angular model holds for moderate anisotropy: within
    /// 3-7 % of the path tracer for |g| up to 0.5, 10-80 % off for g 0.65-0.9, depending on the
    /// view (a warning is logged above |g| 0.6; docs/multiple-scattering.md) (default: off).
    bool multipleScatteringCache = false;
    /// Cells of the cache along the box's longest side, the other sides in proportion, at most
    /// one per voxel and at most 32 voxels wide, 1..1024. Measured once refined against the path
    /// tracer (relRMSE): bonsai 10.8 % at 64 and 8.6 % at 128, engine 21.4 % and 17.9 %; first
    /// frames after a light change 14.5 and 15.2 %, 27.6 and 29.2 %. Memory: about 385 bytes per
    /// cell, 100 MiB at 64^3, 800 MiB at 128^3. The photon sums, 184 bytes per cell, take at
    /// most four storage-buffer bindings of GL_MAX_SHADER_STORAGE_BLOCK_SIZE each: where more
    /// cells are asked (llvmpipe: more than 142^3) the resolution is lowered, with a warning
    /// (default: 64).
    int cacheResolution = 64;
    /// Photons each render() adds while the cache refines, 1..2^24 (default: 65536).
    int cachePhotonsPerFrame = 1 << 16;
    /// Photons after which the cache stops refining and frames trace none, 1..2^30
    /// (default: 2^21).
    int cachePhotons = 1 << 21;
    /// Where the cache's light towards the viewer is evaluated: once per cell and camera move, or
    /// per shaded sample (default: Auto; see CacheViewEvaluation).
    CacheViewEvaluation cacheViewEvaluation = CacheViewEvaluation::Auto;
    /// The ray caster: fragment or compute, or picked per device (default: Auto; see RayCaster).
    RayCaster rayCaster = RayCaster::Auto;
    /// Wait for the GPU after each pass so RenderStats times are GPU times (default: off).
    bool finishEachPass = false;
    /// Write GL timestamps around each pass; RenderStats then holds each pass's GPU time too,
    /// collected without waiting a frame or more later (PassStats::lastGpuMs) (default: off).
    bool gpuPassTimes = false;
};

/// Throws Error(InvalidArgument) naming the first field of `options` that breaks its documented
/// range. The renderer checks its options with it; front ends call it before creating a context.
void validate(const VolumeRenderOptions& options);

/// Draws one volume into a RenderTarget, compositing premultiplied colour over what the target
/// holds (clear it to the background first). Needs a current GlContext.
class VolumeScatteringRenderer {
public:
    /// Throws Error(InvalidArgument) naming the bad option.
    explicit VolumeScatteringRenderer(const VolumeRenderOptions& options = {});
    ~VolumeScatteringRenderer();
    VolumeScatteringRenderer(VolumeScatteringRenderer&&) noexcept;
    VolumeScatteringRenderer& operator=(VolumeScatteringRenderer&&) noexcept;

    /// Uploads the volume. It occupies Volume::worldBounds() transformed by `model`.
    void setVolume(const Volume& volume, const glm::mat4& model = glm::mat4(1.0f));
    void setModelTransform(const glm::mat4& model);
    void setTransferFunction(const TransferFunction& tf);
    /// At most 8 lights; used by gradient shading.
    void setLights(std::vector<Light> lights);
    void setOptions(const VolumeRenderOptions& options);
    const VolumeRenderOptions& options() const;
    /// Clip planes and a crop box (sss/volume_clip.h); throws Error(InvalidArgument) naming the
    /// field. A clip whose cut matter casts no shadows rebuilds the light volumes.
    void setClip(const VolumeClip& clip);
    const VolumeClip& clip() const;

    /// Throws Error(InvalidArgument) if no volume is set, Error(GpuLimit) if the scene does not
    /// fit the GPU (see LightVolumeFallback for the light volumes).
    void render(const Camera& camera, RenderTarget& target);

    /// The light-volume resolution relative to the data that the last light-volume build used:
    /// options().lightVolumeScale unless LightVolumeFallback::Reduce had to lower it or the build
    /// was a preview (VolumeRenderOptions::lightVolumePreviewScale) (0 before the first build).
    float lightVolumeScaleInUse() const;
    /// True when the last render() drew with a preview light volume
    /// (VolumeRenderOptions::lightVolumePreviewScale): the next render() builds the full one.
    bool lightVolumePreviewed() const;
    /// Bytes of GPU memory the gradient volume holds (0 when there is none: gradient modes
    /// unused, VolumeRenderOptions::gradientVolume off, or it did not fit).
    std::size_t gradientVolumeBytes() const;
    /// Paths per pixel in the multiple-scattering mode's running mean (0 in the other modes,
    /// and after anything that restarts it, until the next render()).
    int accumulatedSamples() const;
    /// Photons in the multiple-scattering cache (0 when it is off, and after anything that
    /// restarts it, until the next render()).
    std::uint64_t cachedPhotons() const;

    const RenderStats& stats() const;

private:
    friend struct detail::VolumeRendererAccess;
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

}  // namespace sss

SSS_END_API
