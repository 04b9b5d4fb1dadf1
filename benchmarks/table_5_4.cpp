// Thesis Table 5.4: volume scattering with the light volume at data resolution.
// change = a light change (light-volume propagation + ray cast); fixed = ray cast with the
// light volume; ea = emission-absorption; ea_gradient = gradient Phong; fixed_gradient =
// scattering plus gradient highlights (ray cast only); *_without_skipping: the change and the
// light volume with empty-space skipping off. change_preview: the light change with
// lightVolumePreviewScale (the frame after the edit; the next one costs a change), timed
// interleaved with emission-absorption frames of a second renderer, and its image's relRMSE
// against the full light volume's frame. cache_*: the physical model with the multiple-scattering
// cache (docs/multiple-scattering.md) at the table's settings otherwise: a camera move
// (cache_fixed, beside physical single scattering without the cache and emission-absorption
// frames) and a light change (cache_change: the light volume, the cells' moments, the first
// photons and the frame, beside emission-absorption frames), all interleaved.

#include "bench.h"

#include <sss/image_compare.h>

#include <glm/gtc/matrix_transform.hpp>

#include <map>

namespace {

constexpr const char* kTable = "5.4";

struct ThesisRow {
    double change, fixed, ea, eaGradient, fixedGradient;
};

const std::map<std::string, ThesisRow>& thesisRows() {
    static const std::map<std::string, ThesisRow> rows = {
        {"bucky", {6.04, 1.41, 1.31, 1.61, 1.73}},
        {"bonsai", {34.99, 8.86, 3.05, 9.49, 16.47}},
        {"engine", {34.79, 7.98, 2.81, 8.88, 14.55}},
    };
    return rows;
}

// The scale the viewer's "preview light edits" uses (apps/viewer/viewer_panels.cpp).
constexpr float kPreviewScale = 0.25f;

// Light changes of `renderer` (the key light and its nudged twin in turn), interleaved with
// frames of `ea`: {changes, EA frames}.
std::vector<Measurement> lightChangesBeside(BenchmarkContext& bench, sss::VolumeScatteringRenderer& renderer,
                                            sss::VolumeScatteringRenderer& ea, const FramedVolume& scene,
                                            const std::string& changeId, const std::string& eaId) {
    const sss::DirectionalLight other = nudged(scene.key);
    bool useOther = false;
    return bench.measureInterleaved(
        {[&](sss::RenderTarget& t) {
             useOther = !useOther;
             renderer.setLights({useOther ? other : scene.key});
             renderer.render(scene.camera, t);
         },
         [&](sss::RenderTarget& t) { ea.render(scene.camera, t); }},
        {changeId, eaId});
}

struct PreviewCost {
    Measurement change, ea;  // interleaved
    double relRmse = 0.0;    // of the preview frame against the full light volume's
};

// A light change drawn with a preview light volume, beside emission-absorption frames.
PreviewCost measurePreview(BenchmarkContext& bench, const FramedVolume& scene, const std::string& id) {
    sss::VolumeRenderOptions options = thesisVolumeOptions(bench.options(), sss::VolumeShading::Scattering);
    options.lightVolumePreviewScale = kPreviewScale;
    sss::VolumeScatteringRenderer preview(options);
    sss::VolumeScatteringRenderer ea(thesisVolumeOptions(bench.options(), sss::VolumeShading::EmissionAbsorption));
    showVolume(preview, scene);
    showVolume(ea, scene);
    std::vector<Measurement> m = lightChangesBeside(bench, preview, ea, scene, id + "-change-preview", id + "-ea-beside-preview");
    sss::RenderTarget target(bench.options().width, bench.options().height);
    auto draw = [&] {
        target.clear(glm::vec4(0.0f));
        preview.render(scene.camera, target);
        return target.readColor();
    };
    preview.setLights({nudged(scene.key)});
    draw();
    preview.setLights({scene.key});
    const sss::Image previewFrame = draw();
    const sss::Image fullFrame = draw();
    return {std::move(m[0]), std::move(m[1]), sss::computeErrorMetrics(previewFrame, fullFrame).relRmse};
}

struct CacheCost {
    Measurement fixed, single, eaBesideFixed;  // interleaved
    Measurement change, eaBesideChange;        // interleaved
};

CacheCost measureCache(BenchmarkContext& bench, const FramedVolume& scene, const std::string& id) {
    sss::VolumeRenderOptions single = thesisVolumeOptions(bench.options(), sss::VolumeShading::Scattering);
    single.model = sss::VolumeModel::Physical;
    sss::VolumeRenderOptions cached = single;
    cached.multipleScatteringCache = true;
    // A camera move reads the finest level, as once refined, whatever the photons: one frame's
    // photons fill this budget.
    sss::VolumeRenderOptions filled = cached;
    filled.cachePhotons = filled.cachePhotonsPerFrame;
    sss::VolumeScatteringRenderer fixedRenderer(filled), singleRenderer(single), changeRenderer(cached);
    sss::VolumeScatteringRenderer ea(thesisVolumeOptions(bench.options(), sss::VolumeShading::EmissionAbsorption));
    for (sss::VolumeScatteringRenderer* r : {&fixedRenderer, &singleRenderer, &changeRenderer, &ea}) showVolume(*r, scene);
    // Each frame a camera move: the cache's light towards the viewer is evaluated anew
    // (FluenceCache::evaluateView), as it is while the user turns the view.
    auto moving = [&](sss::VolumeScatteringRenderer& r) {
        return [&r, &scene, frame = 0](sss::RenderTarget& t) mutable { r.render(moved(scene.camera, frame++), t); };
    };
    std::vector<Measurement> fixed = bench.measureInterleaved(
        {moving(fixedRenderer), moving(singleRenderer), moving(ea)},
        {id + "-cache-fixed", id + "-physical-fixed", id + "-ea-beside-cache"});
    std::vector<Measurement> change =
        lightChangesBeside(bench, changeRenderer, ea, scene, id + "-cache-change", id + "-ea-beside-cache-change");
    return {std::move(fixed[0]), std::move(fixed[1]), std::move(fixed[2]), std::move(change[0]), std::move(change[1])};
}

}  // namespace

void runTable54(BenchmarkContext& bench) {
    const bool quick = bench.options().quick;
    const bool thesisViewport = bench.options().width == kThesisWidth && bench.options().height == kThesisHeight;
    forEachShownVolume(bench, kTable, {"bucky", "bonsai", "engine", "cthead"},
                       [&](const std::string& model, const FramedVolume& scene, sss::VolumeScatteringRenderer& renderer) {
        const sss::Camera& camera = scene.camera;
        const sss::DirectionalLight& key = scene.key;
        const std::string id = std::string(kTable) + "-" + model;
        auto withShading = [&](sss::VolumeShading shading) {
            // The thesis's configuration (full-resolution light volume, step 1, post-classification).
            renderer.setOptions(thesisVolumeOptions(bench.options(), shading));
        };
        withShading(sss::VolumeShading::Scattering);
        ChangeAndFixedPasses passes{PassRecorder(renderer.stats()), PassRecorder(renderer.stats())};
        const auto [change, fixed] =
            measureChangeAndFixed(bench, renderer, camera, key, id, bench.options().passes ? &passes : nullptr);
        // The same light change without empty-space skipping (same images): what skipping saves,
        // in the ray cast and in the light-volume sweep.
        sss::VolumeRenderOptions unskipped = thesisVolumeOptions(bench.options(), sss::VolumeShading::Scattering);
        unskipped.emptySpaceSkipping = false;
        renderer.setOptions(unskipped);
        const auto [changeUnskipped, fixedUnskipped] =
            measureChangeAndFixed(bench, renderer, camera, key, id + "-without-skipping");
        const PreviewCost preview = measurePreview(bench, scene, id);
        const CacheCost cache = measureCache(bench, scene, id);
        withShading(sss::VolumeShading::ScatteringGradient);
        const Measurement fixedGradient =
            bench.measure([&](sss::RenderTarget& t) { renderer.render(camera, t); }, id + "-fixed-gradient");
        withShading(sss::VolumeShading::EmissionAbsorption);
        const Measurement ea = bench.measure([&](sss::RenderTarget& t) { renderer.render(camera, t); }, id + "-ea");
        withShading(sss::VolumeShading::Gradient);
        const Measurement eaGradient =
            bench.measure([&](sss::RenderTarget& t) { renderer.render(camera, t); }, id + "-ea-gradient");

        const glm::ivec3 d = scene.volume.dims();
        Record r;
        r.table = kTable;
        r.model = model;
        r.mode = "scattering";
        r.dataSize = dimsText(d);
        r.params = "tf=" + scene.preset + " (median = fixed)";
        r.width = bench.options().width;
        r.height = bench.options().height;
        r.measurement = fixed;
        r.details = {{"change_ms", change.stats.medianMs},
                     {"fixed_ms", fixed.stats.medianMs},
                     {"ea_ms", ea.stats.medianMs},
                     {"ea_gradient_ms", eaGradient.stats.medianMs},
                     {"fixed_gradient_ms", fixedGradient.stats.medianMs},
                     {"light_volume_ms", change.stats.medianMs - fixed.stats.medianMs},
                     {"change_without_skipping_ms", changeUnskipped.stats.medianMs},
                     {"light_volume_without_skipping_ms", changeUnskipped.stats.medianMs - fixedUnskipped.stats.medianMs},
                     {"change_preview_ms", preview.change.stats.medianMs},
                     {"ea_beside_preview_ms", preview.ea.stats.medianMs},
                     {"preview_scale", kPreviewScale},
                     {"preview_rel_rmse", preview.relRmse},
                     {"cache_fixed_ms", cache.fixed.stats.medianMs},
                     {"physical_fixed_ms", cache.single.stats.medianMs},
                     {"ea_beside_cache_ms", cache.eaBesideFixed.stats.medianMs},
                     {"cache_change_ms", cache.change.stats.medianMs},
                     {"ea_beside_cache_change_ms", cache.eaBesideChange.stats.medianMs},
                     {"change_spread_ms", {change.stats.minMs, change.stats.maxMs}},
                     {"fixed_spread_ms", {fixed.stats.minMs, fixed.stats.maxMs}},
                     {"dims", {d.x, d.y, d.z}},
                     {"transfer_function", scene.preset}};
        if (const auto it = thesisRows().find(model); it != thesisRows().end() && thesisViewport && !quick) {
            r.thesisMs = it->second.fixed;
            r.details["thesis_gtx660"] = {{"change_ms", it->second.change},
                                          {"fixed_ms", it->second.fixed},
                                          {"ea_ms", it->second.ea},
                                          {"ea_gradient_ms", it->second.eaGradient},
                                          {"fixed_gradient_ms", it->second.fixedGradient}};
        }
        const Record row = r;
        bench.addRecord(std::move(r));
        if (bench.options().passes) {
            passes.change.addRecords(bench, row, "change");
            passes.fixed.addRecords(bench, row, "fixed");
        }
    });
}
