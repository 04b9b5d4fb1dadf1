#include "sss/volume_scattering_renderer.h"

#include "util/format.h"

#include "core/light_geometry.h"
#include "gl/texture.h"
#include "lighting/light_uniforms.h"
#include "lighting/texture_units.h"
#include "sss/error.h"
#include "sss/option_table.h"
#include "sss/log.h"
#include "sss/timing.h"
#include "frame/pass_timer.h"
#include "gl/device.h"
#include "volume/empty_space.h"
#include "volume/gradient_volume_pass.h"
#include "volume/gpu_volume.h"
#include "volume/eye_pass.h"
#include "volume/fluence_cache.h"
#include "volume/light_volume_pass.h"
#include "volume/path_trace_pass.h"
#include "volume/preintegration.h"
#include "volume/step_classification.h"
#include "volume/ray_cast_pass.h"
#include "volume/renderer_access.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cstdint>
#include <tuple>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>

namespace sss {
namespace {

// The multiple-scattering cache's angular model is measured within 3-7 % of the path tracer for
// |g| up to 0.5 and 10-80 % off from 0.65 to 0.9 (docs/multiple-scattering.md, "Strong forward or
// backward scattering"): beyond this the renderer warns.
constexpr float kCacheAnisotropyMeasured = 0.6f;

// Everything the light volumes depend on; they are rebuilt only when this changes.
struct LightVolumeInputs {
    std::uint64_t volumeGeneration = 0;
    std::uint64_t transferFunctionRevision = 0;
    int transferFunctionEntries = 0;
    std::vector<Light> lights;
    glm::mat4 model{1.0f};
    detail::LightVolumeSettings settings;  // as asked: the scale before any fallback
    VolumeClip clip;                       // the cut matter casts no shadows (by default)
    bool operator==(const LightVolumeInputs&) const = default;
};

// Everything the path tracer's running mean depends on; it restarts when this changes.
struct PathTraceInputsKey {
    std::uint64_t volumeGeneration = 0;
    std::uint64_t transferFunctionRevision = 0;
    int transferFunctionEntries = 0;
    std::vector<Light> lights;
    glm::mat4 model{1.0f}, view{1.0f}, projection{1.0f};
    glm::ivec2 size{0};
    float anisotropy = 0.0f;
    int maxBounces = 0;
    VolumeClip clip;
    VolumeReconstruction reconstruction = VolumeReconstruction::Trilinear;
    std::uint64_t meshShadows = 0;  // detail::meshShadowRevision: the meshes block the lights
    bool operator==(const PathTraceInputsKey&) const = default;
};

// Everything the multiple-scattering cache depends on; it restarts when this changes.
struct FluenceCacheKey {
    std::uint64_t volumeGeneration = 0;
    std::uint64_t transferFunctionRevision = 0;
    int transferFunctionEntries = 0;
    std::vector<Light> lights;
    glm::mat4 model{1.0f};
    float anisotropy = 0.0f;
    int maxBounces = 0;
    VolumeClip clip;
    glm::ivec3 cells{0};
    VolumeReconstruction reconstruction = VolumeReconstruction::Trilinear;
    float lightVolumeScale = 0.0f;  // the cache regresses on the light volumes (FluenceCache)
    std::uint64_t meshShadows = 0;  // detail::meshShadowRevision: the meshes block the lights
    bool operator==(const FluenceCacheKey&) const = default;
};

// What the cache's cells' weights and direct-light moments depend on: all but the scattering (and
// the lights' radiance, which FluenceCache::lights() holds).
auto densityInputsOf(const FluenceCacheKey& k) {
    return std::tie(k.volumeGeneration, k.transferFunctionRevision, k.transferFunctionEntries, k.lights, k.model,
                    k.clip, k.cells, k.reconstruction, k.lightVolumeScale, k.meshShadows);
}

}  // namespace

std::string_view toString(VolumeModel model) { return model == VolumeModel::Physical ? "physical" : "paper"; }

std::optional<VolumeModel> parseVolumeModel(std::string_view name) {
    if (name == "paper") return VolumeModel::Paper;
    if (name == "physical") return VolumeModel::Physical;
    return std::nullopt;
}

void validate(const VolumeRenderOptions& o) {
    validateOptionRanges(o);
    if (o.stepSize < 0.01f)
        throw Error(ErrorKind::InvalidArgument, "VolumeRenderOptions", "stepSize",
                    "must be at least 0.01 voxels (smaller steps cannot finish), got " + detail::formatNumber(o.stepSize));
    if (o.multipleScattering && (o.shading != VolumeShading::Scattering || o.model != VolumeModel::Physical))
        throw Error(ErrorKind::InvalidArgument, "VolumeRenderOptions", "multipleScattering",
                    "needs shading Scattering and model Physical (it path-traces the physical model)");
    if (o.multipleScatteringCache &&
        (!detail::usesLightVolume(o.shading) || o.model != VolumeModel::Physical || o.multipleScattering))
        throw Error(ErrorKind::InvalidArgument, "VolumeRenderOptions", "multipleScatteringCache",
                    "needs a light-volume shading (Scattering or ScatteringGradient) and model Physical, without "
                    "multipleScattering (the cache adds to the physical model's single scattering)");
}

struct VolumeScatteringRenderer::Impl {
    VolumeRenderOptions options;
    TransferFunction transferFunction;
    gl::Texture transferFunctionTable;
    gl::Texture transferFunctionOpacity;  // its opacities alone (RayCastInputs)
    std::vector<Light> lights{DirectionalLight{}};
    glm::mat4 model{1.0f};
    VolumeClip clip;
    const VolumeClip* clipOrNull() const { return clip.clipsNothing() ? nullptr : &clip; }
    // What the light volumes see of the clip: nothing when the cut matter still casts shadows.
    const VolumeClip* lightClip() const { return clip.clippedMatterCastsShadows ? nullptr : clipOrNull(); }
    std::optional<detail::GpuVolume> volume;
    std::optional<detail::OccupancyGrid> occupancy;
    std::uint64_t volumeGeneration = 0;
    std::optional<detail::RayCastPass> rayCast;  // built for the current shading mode
    std::optional<detail::LightVolumePass> lightVolumePass;  // built on first use
    std::vector<gl::Texture> lightVolumes;                  // one per light
    // Kept apart from lightVolumes, so that neither is reallocated when the other is built.
    std::vector<gl::Texture> previewLightVolumes;
    std::optional<LightVolumeInputs> lightVolumeInputs;     // what lightVolumes were built from
    float lightVolumeScaleInUse = 0.0f;                     // as built: a fallback's or a preview's
    // options.lightVolumePreviewScale: a preview built in the current frame stays for the rest of
    // it (a hybrid compositor updates the light volumes before render()); the next frame with the
    // same inputs replaces a shown one.
    enum class Preview { None, ThisFrame, Shown } preview = Preview::None;
    const std::vector<gl::Texture>& shownLightVolumes() const {
        return preview == Preview::None ? lightVolumes : previewLightVolumes;
    }
    float lightVolumeReachInUse() const {
        return preview == Preview::None ? options.lightVolumeReach
                                        : options.lightVolumeReach * lightVolumeScaleInUse / options.lightVolumeScale;
    }
    // Eye pass (optional): the voxels' scattered light, carried towards the viewer.
    std::optional<detail::EyePass> eyePass;
    std::optional<detail::GradientVolumePass> gradientPass;
    std::optional<gl::Texture> gradientVolume;  // for the current data, built on first use
    bool gradientVolumeFailed = false;          // did not fit: gradients on the fly for this data
    bool warnedCacheAnisotropy = false;         // once per renderer

    void warnIfCacheAnisotropyUnmeasured() {
        if (!options.multipleScatteringCache || std::abs(options.anisotropy) <= kCacheAnisotropyMeasured ||
            warnedCacheAnisotropy)
            return;
        warnedCacheAnisotropy = true;
        log(LogLevel::Warning, "VolumeRenderOptions: multipleScatteringCache with anisotropy " +
                                   detail::formatNumber(options.anisotropy) +
                                   ": the cache's angular model measured 10-80 % off the path tracer for |g| 0.65-0.9 "
                                   "(within 7 % up to 0.5; docs/multiple-scattering.md, \"Strong forward or backward "
                                   "scattering\"); multipleScattering has no such limit");
    }
    // What the classification tables for the ray step (pre-integrated or step-corrected) are
    // built from: the TF revision, its entries and the step.
    using StepTableKey = std::tuple<std::uint64_t, int, float>;
    StepTableKey stepTableKey() const {
        return {transferFunction.revision(), options.transferFunctionEntries, options.stepSize};
    }
    // Pre-integrated classification: the table and the key it was built for.
    gl::Texture preintegrationTable;
    gl::Texture preintegratedOpacity;  // its layer 0's opacity alone (RayCastInputs::opacityTable)
    std::optional<StepTableKey> preintegrationKey;

    // Built with the data and transfer function (and when the step changes), not at the first
    // frame, so its memory is taken when the data is set up. If it does not fit the GPU, a
    // warning says so and rays classify each sample alone until the inputs change.
    void updatePreintegration() {
        if (!options.preintegration || options.multipleScattering || !volume) return;  // the path tracer needs none
        const StepTableKey key = stepTableKey();
        if (preintegrationKey == key) return;
        preintegrationKey = key;
        const detail::PassTimer::Mark mark = passTimer.begin(passTiming());
        const int size = detail::preintegrationSize(options.transferFunctionEntries);
        preintegrationTable = {};  // free the old tables before allocating their successors
        preintegratedOpacity = {};
        try {
            const std::vector<glm::vec4> table =
                detail::preintegrate(transferFunction.table(options.transferFunctionEntries), size, options.stepSize);
            gl::Texture built = detail::uploadPreintegration(table, size);
            // Layer 0's opacities; both tables or neither.
            preintegratedOpacity = detail::uploadOpacities(table, glm::ivec2(size), GL_R16F, "pre-integrated opacity");
            preintegrationTable = std::move(built);
        } catch (const Error& e) {
            if (e.kind() != ErrorKind::GpuLimit) throw;
            log(LogLevel::Warning, std::string(e.what()) + "; each sample is classified alone instead (no pre-integration)");
            return;
        }
        passTimer.end("preintegration", mark, passTiming());
    }
    // Whether the ray caster integrates segments: asked for and the table fitted.
    bool preintegrated() const {
        return options.preintegration && !options.multipleScattering && static_cast<bool>(preintegrationTable);
    }

    // Post-classification's transfer function with opacities corrected for the ray step, and
    // the key it was built for. Built when rays classify samples alone.
    gl::Texture stepTransferFunction;
    std::optional<StepTableKey> stepTransferFunctionKey;
    void updateStepTransferFunction() {
        const StepTableKey key = stepTableKey();
        if (stepTransferFunctionKey == key) return;
        stepTransferFunction = detail::uploadStepClassification(
            detail::stepClassification(transferFunction.table(options.transferFunctionEntries), options.stepSize));
        stepTransferFunctionKey = key;
    }

    // Whether the ray caster reads precomputed gradients; builds them once per data set.
    bool updateGradientVolume() {
        if (!detail::usesGradient(options.shading) || !options.gradientVolume) return false;
        if (gradientVolume) return true;
        if (gradientVolumeFailed) return false;
        try {
            if (!gradientPass) gradientPass.emplace();
            passTimer.time("gradient-volume", passTiming(), [&] { gradientVolume = gradientPass->run(*volume); });
            return true;
        } catch (const Error& e) {
            if (e.kind() != ErrorKind::GpuLimit) throw;
            gradientVolumeFailed = true;
            log(LogLevel::Warning, std::string(e.what()) + "; gradients are computed on the fly instead");
            return false;
        }
    }
    std::optional<std::tuple<LightVolumeInputs, std::vector<Light>, float, glm::vec3, float, float, VolumeClip, std::uint64_t>>
        eyeInputs;
    const detail::MeshShadowMaps* meshShadows = nullptr;    // set by HybridCompositor
    // Multiple scattering: the path tracer, its running sums and what they were built from.
    std::optional<detail::PathTracePass> pathTrace;
    gl::Texture pathSums;                                   // RGBA32F sums of (radiance, hit)
    int pathSamples = 0;                                    // paths per pixel in pathSums
    std::optional<PathTraceInputsKey> pathKey;
    std::vector<Light> pathLights;                          // the radiance pathSums were traced with
    gl::Texture majorants;                                  // per brick, for the current TF
    std::optional<std::tuple<std::uint64_t, std::uint64_t, int, VolumeReconstruction>> majorantKey;

    void updateMajorants() {
        const auto tableKey = std::make_tuple(volumeGeneration, transferFunction.revision(),
                                              options.transferFunctionEntries, options.reconstruction);
        if (majorantKey == tableKey) return;
        majorants = detail::brickMajorants(*occupancy, volume->voxelLength);
        majorantKey = tableKey;
    }

    // The multiple-scattering cache: restarted when its inputs change, refined by each frame
    // until it holds options.cachePhotons.
    std::optional<detail::FluenceCache> fluenceCache;
    std::optional<FluenceCacheKey> fluenceKey;
    // The cache's cells at options.cacheResolution, fewer where its buffers would not fit the
    // device's storage-buffer bindings (warned once per volume and resolution).
    std::optional<std::pair<std::uint64_t, int>> cacheCellsWarned;
    std::optional<std::int64_t> storageBlockBytes;  // asked of the context once
    glm::ivec3 fluenceCacheCells() {
        if (!storageBlockBytes) storageBlockBytes = gl::storageBlockLimit();
        const glm::ivec3 asked = detail::fluenceCacheCells(volume->dims, volume->box.size(), options.cacheResolution,
                                                           std::numeric_limits<std::int64_t>::max());
        const std::int64_t maxCells = detail::maxFluenceCacheCells(*storageBlockBytes);
        if (std::int64_t{asked.x} * asked.y * asked.z <= maxCells) return asked;
        const glm::ivec3 cells =
            detail::fluenceCacheCells(volume->dims, volume->box.size(), options.cacheResolution, maxCells);
        const auto warnKey = std::make_pair(volumeGeneration, options.cacheResolution);
        if (cacheCellsWarned != warnKey) {
            const auto text = [](glm::ivec3 c) {
                return std::to_string(c.x) + " x " + std::to_string(c.y) + " x " + std::to_string(c.z);
            };
            log(LogLevel::Warning, "VolumeRenderOptions: cacheResolution " + std::to_string(options.cacheResolution) +
                                       " needs " + text(asked) + " cells, more than the " + std::to_string(maxCells) +
                                       " this device's storage buffers hold (GL_MAX_SHADER_STORAGE_BLOCK_SIZE " +
                                       std::to_string(*storageBlockBytes) + " bytes); the cache uses " + text(cells));
            cacheCellsWarned = warnKey;
        }
        return cells;
    }
    void updateFluenceCache() {
        const glm::ivec3 cells = fluenceCacheCells();
        // Keyed on where the lights' light goes, not on how much of it: a change of radiance that
        // scales every light alike keeps the cache, and the ray caster scales what it reads.
        FluenceCacheKey key{volumeGeneration, transferFunction.revision(), options.transferFunctionEntries,
                            detail::withUnitRadiance(lights), model, options.anisotropy, options.maxBounces, clip, cells,
                            options.reconstruction, lightVolumeScaleInUse,
                            detail::meshShadowRevision(meshShadows, lights.size())};
        const bool restart = fluenceKey != key || !detail::commonRadianceScale(fluenceCache->lights(), lights);
        const auto photons = static_cast<std::uint64_t>(options.cachePhotons);
        if (!restart && fluenceCache->photons() >= photons) return;  // refined: nothing to trace
        const detail::PassTimer::Mark mark = passTimer.begin(passTiming());
        updateMajorants();
        // The density pass's direct-light moments are weighted by the lights' radiance.
        const bool sameDensityInputs = fluenceKey && densityInputsOf(*fluenceKey) == densityInputsOf(key) &&
                                       fluenceCache->lights() == lights;
        if (!fluenceCache || fluenceCache->reconstruction() != options.reconstruction) {
            fluenceCache.emplace(options.reconstruction);
            fluenceKey.reset();
        }
        // Photons added to a kept cache carry the radiance of its restart, as those before them.
        const std::vector<Light> traced = restart ? lights : fluenceCache->lights();
        const detail::FluenceCacheInputs inputs{.volume = *volume,
                                                .transferFunction = transferFunctionTable,
                                                .majorants = majorants,
                                                .model = model,
                                                .lights = traced,
                                                .anisotropy = options.anisotropy,
                                                .maxBounces = options.maxBounces,
                                                .clip = clipOrNull(),
                                                .lightVolumes = &shownLightVolumes(),
                                                .meshShadows = meshShadows};
        if (restart) {
            fluenceCache->restart(inputs, cells, sameDensityInputs);
            fluenceKey = std::move(key);
        }
        const std::uint64_t left = photons - std::min(photons, fluenceCache->photons());
        fluenceCache->add(inputs, static_cast<int>(std::min<std::uint64_t>(left, options.cachePhotonsPerFrame)), photons);
        passTimer.end("scattering-cache", mark, passTiming());
    }

    // Whether the ray caster evaluates the cache's light towards the viewer per sample: decided
    // on the cache's finest cells (not the level read, which would switch the program while the
    // cache refines) and the target's pixels.
    bool cachePerSample(const RenderTarget& target) {
        if (!detail::usesScatteringCache(options)) return false;
        const glm::dvec3 cells(fluenceCacheCells());
        return detail::cacheEvaluatedPerSample(options.cacheViewEvaluation, softwareDevice(), cells.x * cells.y * cells.z,
                                               static_cast<double>(target.width()) * target.height());
    }

    // The cache's light towards the camera: evaluated again when the camera or the cache changed.
    void updateFluenceView(const Camera& camera) {
        const detail::FluenceViewInputs in{
            .viewer = detail::modelSpaceViewer(camera, model),
            .anisotropy = options.anisotropy};
        if (fluenceCache->viewOutdated(in))
            passTimer.time("scattering-cache-view", passTiming(), [&] { fluenceCache->evaluateView(in); });
    }

    void renderPathTraced(const Camera& camera, RenderTarget& target) {
        const detail::PassTimer::Mark mark = passTimer.begin(passTiming());
        updateMajorants();
        // As the cache: a change of radiance that scales every light alike keeps the paths traced.
        PathTraceInputsKey key{volumeGeneration, transferFunction.revision(), options.transferFunctionEntries,
                               detail::withUnitRadiance(lights), model, camera.view(),
                               camera.projection(target.aspect()), glm::ivec2(target.width(), target.height()),
                               options.anisotropy, options.maxBounces, clip, options.reconstruction,
                               detail::meshShadowRevision(meshShadows, lights.size())};
        if (pathKey != key || !detail::commonRadianceScale(pathLights, lights)) {
            if (!pathSums || pathSums.size() != glm::ivec3(key.size, 1))
                pathSums = gl::Texture::create2D(GL_RGBA32F, key.size.x, key.size.y, "path-tracer sums");
            const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
            glClearTexImage(pathSums.id(), 0, GL_RGBA, GL_FLOAT, zero);
            pathSamples = 0;
            pathKey = std::move(key);
            pathLights = lights;
        }
        if (!pathTrace || pathTrace->reconstruction() != options.reconstruction)
            pathTrace.emplace(detail::PathTraceBounds{}, options.reconstruction);
        copyDepth(target);
        pathTrace->accumulate({.volume = *volume,
                               .transferFunction = transferFunctionTable,
                               .majorants = majorants,
                               .sceneDepth = sceneDepth,
                               .model = model,
                               .lights = pathLights,
                               .options = options,
                               .camera = camera,
                               .aspect = target.aspect(),
                               .firstSample = static_cast<unsigned>(pathSamples),
                               .clip = clipOrNull(),
                               .meshShadows = meshShadows},
                              pathSums);
        pathSamples += options.samplesPerFrame;
        target.bindForDrawing();
        pathTrace->composite(pathSums, pathSamples, *detail::commonRadianceScale(pathLights, lights));
        passTimer.end("path-trace", mark, passTiming());
    }
    gl::Texture sceneDepth;                      // copy of the target's depth, sampled by rays

    // Sampling the depth attachment of the framebuffer being drawn would be a feedback loop,
    // so the ray caster reads a copy.
    void copyDepth(const RenderTarget& target) {
        const glm::ivec3 size(target.width(), target.height(), 1);
        if (!sceneDepth || sceneDepth.size() != size) {
            sceneDepth = gl::Texture::create2D(GL_DEPTH_COMPONENT32F, size.x, size.y, "volume scene depth");
            sceneDepth.setFilter(GL_NEAREST, GL_NEAREST);
        }
        glCopyImageSubData(target.depthTextureId(), GL_TEXTURE_2D, 0, 0, 0, 0, sceneDepth.id(), GL_TEXTURE_2D, 0,
                           0, 0, 0, size.x, size.y, 1);
    }

    void updateLightVolumes() {
        // The physical model reads the intensity alone (grey extinction), and so do the meshes it
        // shadows in a hybrid scene: the sweep leaves the chromaticity out.
        const LightVolumeInputs inputs{volumeGeneration,
                                       transferFunction.revision(),
                                       options.transferFunctionEntries,
                                       detail::asLightVolumeLights(lights),  // the eye applies the radiance and a spot's cone
                                       model,
                                       {.resolutionScale = options.lightVolumeScale,
                                        .anisotropy = options.anisotropy,
                                        .chromaticity = options.model != VolumeModel::Physical,
                                        .maxSlicesPerDispatch = options.lightSweepSlices,
                                        .reconstruction = options.reconstruction,
                                        .propagation = options.lightPropagation},
                                       lightClip() ? clip : VolumeClip{}};
        const detail::LightVolumeSettings& asked = inputs.settings;
        const bool changed = lightVolumeInputs != inputs;
        // View-independent: camera moves cost nothing.
        if (!changed && preview != Preview::Shown) return;
        const bool buildPreview =
            changed && options.lightVolumePreviewScale > 0.0f && options.lightVolumePreviewScale < asked.resolutionScale;
        if (!lightVolumePass) lightVolumePass.emplace();
        const detail::PassTimer::Mark mark = passTimer.begin(passTiming());
        detail::LightVolumeSettings settings = asked;
        if (buildPreview) {
            settings.resolutionScale = options.lightVolumePreviewScale;
            settings.blendSweeps = false;  // the next frame's light volume blends them
        }
        float& scale = settings.resolutionScale;
        std::vector<gl::Texture>& built = buildPreview ? previewLightVolumes : lightVolumes;
        std::uint64_t dispatches = 0;
        for (;;) {
            try {
                built.resize(lights.size());
                dispatches = 0;
                for (size_t i = 0; i < lights.size(); ++i) {
                    lightVolumePass->run({.volume = *volume,
                                          .transferFunction = transferFunctionTable,
                                          .occupiedNeighbourhoods =
                                              options.emptySpaceSkipping ? &occupancy->occupiedNeighbourhoods() : nullptr,
                                          .clip = lightClip()},
                                         inputs.lights[i], model, settings, built[i]);  // what they are keyed on
                    dispatches += static_cast<std::uint64_t>(lightVolumePass->lastLayout().dispatches());
                }
                break;
            } catch (const Error& e) {
                const glm::ivec3 dims = detail::lightVolumeDims(volume->dims, scale);
                if (e.kind() != ErrorKind::GpuLimit || options.lightVolumeFallback == LightVolumeFallback::Fail ||
                    std::max({dims.x, dims.y, dims.z}) <= 1)
                    throw;
                // Free what was allocated before trying the smaller size.
                built.clear();
                if (eyePass) eyePass->release();
                scale *= 0.5f;
                const glm::ivec3 reduced = detail::lightVolumeDims(volume->dims, scale);
                log(LogLevel::Warning, std::string(e.what()) + "; the light volume falls back to " +
                                           std::to_string(reduced.x) + "x" + std::to_string(reduced.y) + "x" +
                                           std::to_string(reduced.z) + " (lightVolumeScale " + detail::formatNumber(scale) +
                                           "; LightVolumeFallback::Fail makes this an error)");
            }
        }
        lightVolumeScaleInUse = scale;
        const char* pass = buildPreview ? "light-volume-preview" : "light-volume";
        passTimer.end(pass, mark, passTiming());
        stats.recordDispatches(pass, dispatches);
        lightVolumeInputs = inputs;
        preview = buildPreview ? Preview::ThisFrame : Preview::None;
        if (options.lightVolumePreviewScale == 0.0f) previewLightVolumes.clear();
    }

    void updateEyePass(const Camera& camera) {
        const auto inputs = std::make_tuple(*lightVolumeInputs, lights, lightVolumeScaleInUse, camera.forward(),
                                            options.ambient + options.emission, options.diffuse, clip,
                                            detail::meshShadowRevision(meshShadows, lights.size()));
        if (eyeInputs == inputs) return;
        const detail::PassTimer::Mark mark = passTimer.begin(passTiming());
        if (!eyePass) eyePass.emplace();
        eyePass->run({*volume, transferFunctionTable, shownLightVolumes(), lights, model, camera.forward(),
                      options.ambient + options.emission, options.diffuse,
                      {.resolutionScale = lightVolumeScaleInUse, .anisotropy = options.anisotropy,
                       .maxSlicesPerDispatch = options.lightSweepSlices, .reconstruction = options.reconstruction},
                      options.emptySpaceSkipping ? &occupancy->occupiedNeighbourhoods() : nullptr, clipOrNull(),
                      meshShadows});
        passTimer.end("eye-pass", mark, passTiming());
        eyeInputs = inputs;
    }
    RenderStats stats;
    detail::PassTimer passTimer{stats};
    // Asked of the context once: the ray caster's automatic choice depends on it.
    std::optional<bool> isSoftwareDevice;
    bool softwareDevice() {
        if (!isSoftwareDevice) isSoftwareDevice = gl::currentDeviceIsSoftware();
        return *isSoftwareDevice;
    }
    detail::PassTiming passTiming() const { return {options.finishEachPass, options.gpuPassTimes}; }

    void uploadTransferFunction() {
        const std::vector<glm::vec4> table = transferFunction.table(options.transferFunctionEntries);
        if (!transferFunctionTable || transferFunctionTable.size().x != static_cast<int>(table.size())) {
            transferFunctionTable = gl::Texture::create2D(GL_RGBA32F, static_cast<int>(table.size()), 1, "transfer function");
        }
        transferFunctionTable.upload(GL_RGBA, GL_FLOAT, table.data());
        transferFunctionOpacity = {};  // free the old table before allocating its successor
        transferFunctionOpacity = detail::uploadOpacities(table, glm::ivec2(static_cast<int>(table.size()), 1), GL_R32F,
                                                          "transfer function opacity");
        if (occupancy) occupancy->update(table, volume->valueScaleOffset, options.reconstruction);
        updatePreintegration();
    }
};

VolumeScatteringRenderer::VolumeScatteringRenderer(const VolumeRenderOptions& options) {
    validate(options);
    m_impl = std::make_unique<Impl>();
    m_impl->options = options;
    m_impl->warnIfCacheAnisotropyUnmeasured();
    m_impl->uploadTransferFunction();
}

VolumeScatteringRenderer::~VolumeScatteringRenderer() = default;
VolumeScatteringRenderer::VolumeScatteringRenderer(VolumeScatteringRenderer&&) noexcept = default;
VolumeScatteringRenderer& VolumeScatteringRenderer::operator=(VolumeScatteringRenderer&&) noexcept = default;

void VolumeScatteringRenderer::setVolume(const Volume& volume, const glm::mat4& model) {
    m_impl->volume = detail::GpuVolume::upload(volume);
    m_impl->gradientVolume.reset();  // recomputed for the new data when a gradient mode needs it
    m_impl->gradientVolumeFailed = false;
    m_impl->occupancy.emplace(volume);
    m_impl->uploadTransferFunction();  // also derives the occupancy for the current TF
    ++m_impl->volumeGeneration;
    m_impl->model = model;
}

void VolumeScatteringRenderer::setModelTransform(const glm::mat4& model) { m_impl->model = model; }

void VolumeScatteringRenderer::setTransferFunction(const TransferFunction& tf) {
    m_impl->transferFunction = tf;
    m_impl->uploadTransferFunction();
}

void VolumeScatteringRenderer::setLights(std::vector<Light> lights) {
    detail::validateLights(lights, "VolumeScatteringRenderer::setLights");
    m_impl->lights = std::move(lights);
}

void VolumeScatteringRenderer::setClip(const VolumeClip& clip) {
    validate(clip, "VolumeScatteringRenderer::setClip");
    m_impl->clip = clip;
}

const VolumeClip& VolumeScatteringRenderer::clip() const { return m_impl->clip; }

void VolumeScatteringRenderer::setOptions(const VolumeRenderOptions& options) {
    validate(options);
    // The table, and the occupancy derived with it, depend on the reconstruction too.
    const bool tableChanged = options.transferFunctionEntries != m_impl->options.transferFunctionEntries ||
                              options.reconstruction != m_impl->options.reconstruction;
    m_impl->options = options;
    m_impl->warnIfCacheAnisotropyUnmeasured();
    if (tableChanged) m_impl->uploadTransferFunction();
    m_impl->updatePreintegration();  // the step or the switch may have changed
}

const VolumeRenderOptions& VolumeScatteringRenderer::options() const { return m_impl->options; }
const RenderStats& VolumeScatteringRenderer::stats() const { return m_impl->stats; }
float VolumeScatteringRenderer::lightVolumeScaleInUse() const { return m_impl->lightVolumeScaleInUse; }
bool VolumeScatteringRenderer::lightVolumePreviewed() const {
    return m_impl->preview != Impl::Preview::None && detail::usesLightVolume(m_impl->options.shading);
}
int VolumeScatteringRenderer::accumulatedSamples() const { return m_impl->pathSamples; }
std::uint64_t VolumeScatteringRenderer::cachedPhotons() const {
    return m_impl->fluenceCache ? m_impl->fluenceCache->photons() : 0;
}
std::size_t VolumeScatteringRenderer::gradientVolumeBytes() const {
    return m_impl->gradientVolume ? m_impl->gradientVolume->bytes() : 0;
}

void VolumeScatteringRenderer::render(const Camera& camera, RenderTarget& target) {
    // However this frame ends, a preview built for it has been shown.
    struct EndOfFrame {
        Impl& r;
        ~EndOfFrame() {
            if (r.preview == Impl::Preview::ThisFrame) r.preview = Impl::Preview::Shown;
        }
    } endOfFrame{*m_impl};
    if (!m_impl->volume)
        throw Error(ErrorKind::InvalidArgument, "VolumeScatteringRenderer::render: no volume set (call setVolume first)");
    if (m_impl->options.multipleScattering) {
        m_impl->renderPathTraced(camera, target);
        return;
    }
    m_impl->pathKey.reset();  // leaving the mode drops its running mean
    m_impl->pathSamples = 0;
    // Programs are compiled lazily, once per shading mode in use.
    // The eye pass is the paper's second-order term; the physical model leaves it out.
    const bool eyePass = detail::usesEyePass(m_impl->options);
    const bool gradients = m_impl->updateGradientVolume();
    m_impl->updatePreintegration();
    const bool preintegrated = m_impl->preintegrated();
    if (!preintegrated) m_impl->updateStepTransferFunction();
    const detail::GradientSource gradientSource =
        !gradients ? detail::GradientSource::OnTheFly
        : detail::gradientVolumeHoldsValues(*m_impl->volume) ? detail::GradientSource::VolumeWithValues
                                                               : detail::GradientSource::Volume;
    const detail::RayCastVariant variant =
        detail::RayCastVariant::of(m_impl->options, {.lights = m_impl->lights,
                                                     .model = m_impl->model,
                                                     .clip = m_impl->clipOrNull(),
                                                     .meshShadows = m_impl->meshShadows,
                                                     .gradients = gradientSource,
                                                     .preintegration = preintegrated,
                                                     .softwareDevice = m_impl->softwareDevice(),
                                                     .cachePerSample = m_impl->cachePerSample(target)});
    if (!m_impl->rayCast || m_impl->rayCast->variant() != variant) m_impl->rayCast.emplace(variant);
    if (detail::usesLightVolume(m_impl->options.shading)) m_impl->updateLightVolumes();
    if (eyePass) m_impl->updateEyePass(camera);
    const bool scatteringCache = detail::usesScatteringCache(m_impl->options);
    if (scatteringCache) {
        m_impl->updateFluenceCache();
        if (!variant.cachePerSample) m_impl->updateFluenceView(camera);
    } else {
        m_impl->fluenceKey.reset();  // leaving the mode drops the cache
        m_impl->fluenceCache.reset();
    }
    const detail::PassTimer::Mark mark = m_impl->passTimer.begin(m_impl->passTiming());
    // The fragment caster cannot sample the depth of the framebuffer it draws into: it reads a copy.
    if (!variant.compute) m_impl->copyDepth(target);
    target.bindForDrawing();
    const Impl& r = *m_impl;
    r.rayCast->run({.target = target,
                    .volume = *r.volume,
                    .transferFunction = r.transferFunctionTable,
                    .sceneDepth = variant.compute ? nullptr : &r.sceneDepth,
                    .occupancy = r.occupancy->texture(),
                    .lightVolumes = r.shownLightVolumes(),
                    .lightVolumeReach = r.lightVolumeReachInUse(),
                    .meshShadows = r.meshShadows,
                    .eyeVolume = eyePass ? &r.eyePass->eyeVolume() : nullptr,
                    .cache = scatteringCache ? &*r.fluenceCache : nullptr,
                    .gradientVolume = gradients ? &*r.gradientVolume : nullptr,
                    .preintegration = preintegrated ? &r.preintegrationTable : nullptr,
                    .stepTransferFunction = preintegrated ? nullptr : &r.stepTransferFunction,
                    .opacityTable = preintegrated ? &r.preintegratedOpacity : &r.transferFunctionOpacity,
                    .model = r.model,
                    .lights = r.lights,
                    .options = r.options,
                    .camera = camera,
                    .aspect = target.aspect(),
                    .clip = r.clipOrNull()});
    m_impl->passTimer.end("ray-cast", mark, m_impl->passTiming());
}

namespace detail {

void VolumeRendererAccess::setMeshShadows(VolumeScatteringRenderer& r, const MeshShadowMaps* shadows) {
    r.m_impl->meshShadows = shadows;
}

void VolumeRendererAccess::updateLightVolumes(VolumeScatteringRenderer& r) {
    if (r.m_impl->volume && usesLightVolume(r.m_impl->options.shading)) r.m_impl->updateLightVolumes();
}

std::optional<VolumeShadows> VolumeRendererAccess::shadows(const VolumeScatteringRenderer& r) {
    const auto& impl = *r.m_impl;
    if (!impl.volume || !usesLightVolume(impl.options.shading) || impl.shownLightVolumes().size() != impl.lights.size())
        return std::nullopt;
    // World -> model -> the box's [0,1]^3 texture space.
    const Bounds& box = impl.volume->box;
    const glm::mat4 modelToTexture = glm::scale(glm::mat4(1.0f), 1.0f / box.size()) *
                                     glm::translate(glm::mat4(1.0f), -box.min);
    return VolumeShadows{&impl.shownLightVolumes(), modelToTexture * glm::inverse(impl.model),
                         impl.stats.runs("light-volume") + impl.stats.runs("light-volume-preview")};
}

Bounds VolumeRendererAccess::worldBounds(const VolumeScatteringRenderer& r) {
    Bounds world;
    if (!r.m_impl->volume) return world;
    const Bounds& b = r.m_impl->volume->box;
    for (int i = 0; i < 8; ++i)
        world.extend(glm::vec3(r.m_impl->model * glm::vec4((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y,
                                                            (i & 4) ? b.max.z : b.min.z, 1.0f)));
    return world;
}

}  // namespace detail
}  // namespace sss
