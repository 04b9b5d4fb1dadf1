// Thesis Table 5.4: volume scattering with the light volume at data resolution.
// change = a light change (light-volume propagation + ray cast); fixed = ray cast with the
// light volume; ea = emission-absorption; ea_gradient = gradient Phong; fixed_gradient =
// scattering plus gradient highlights (ray cast only); *_without_skipping: the change and the
// light volume with empty-space skipping off.

#include "bench.h"

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
