// The light-volume sweep against the slices each dispatch advances it (1 = one dispatch per
// slice, filtered lookups), and ray doubling, side by side in one run: the rebuild's GPU time (timestamps around
// the pass, mean over the timed change frames) and wall time (change minus fixed frames), and its
// dispatch count, per volume and model (the paper's sweep gathers a chromaticity cone, whose taps reach further per slice and so
// allow fewer slices per dispatch; the physical model's sweep carries the intensity alone). The
// light volume is the same whatever the slices (tests/gl/test_volume_scattering.cpp); ray
// doubling's is within tests/gl/test_light_doubling.cpp's bounds of it.

#include "bench.h"

#include <sss/option_names.h>

namespace {

constexpr const char* kTable = "light-sweep";

}  // namespace

void runLightSweepTable(BenchmarkContext& bench) {
    const bool quick = bench.options().quick;
    // 0 slices: ray doubling.
    std::vector<int> slices = quick ? std::vector<int>{1, 16} : std::vector<int>{1, 2, 4, 8, 16};
    slices.push_back(0);
    forEachShownVolume(bench, kTable, {"bonsai", "engine"},
                       [&](const std::string& model, const FramedVolume& scene, sss::VolumeScatteringRenderer& renderer) {
        for (sss::VolumeModel volumeModel : {sss::VolumeModel::Paper, sss::VolumeModel::Physical}) {
            double oneSliceMs = 0.0;
            for (int n : slices) {
                sss::VolumeRenderOptions options = thesisVolumeOptions(bench.options(), sss::VolumeShading::Scattering);
                options.model = volumeModel;
                options.lightPropagation = n > 0 ? sss::LightPropagation::Sweep : sss::LightPropagation::Doubling;
                options.lightSweepSlices = n;
                options.gpuPassTimes = true;
                renderer.setOptions(options);
                const std::string how = n > 0 ? std::to_string(n) : std::string("doubling");
                const std::string id = std::string(kTable) + "-" + model + "-" + std::string(sss::enumName(volumeModel)) +
                                       "-" + how;
                ChangeAndFixedPasses passes{PassRecorder(renderer.stats()), PassRecorder(renderer.stats())};
                const auto [change, fixed] = measureChangeAndFixed(bench, renderer, scene.camera, scene.key, id, &passes);
                const std::optional<double> gpuMs = passes.change.gpuMs("light-volume");
                const sss::PassStats* lightVolume = renderer.stats().find("light-volume");
                Record r;
                r.table = kTable;
                r.model = model;
                r.mode = "light-volume";
                r.dataSize = dimsText(scene.volume.dims());
                r.params = std::string(sss::enumName(volumeModel)) +
                           (n > 0 ? ", at most " + how + " slices per dispatch" : ", ray doubling") + " (median = change)";
                r.width = bench.options().width;
                r.height = bench.options().height;
                r.measurement = change;
                const double lightVolumeMs = change.stats.medianMs - fixed.stats.medianMs;
                r.details = {{"volume_model", sss::enumName(volumeModel)},
                             {"propagation", sss::enumName(options.lightPropagation)},
                             {"slices_per_dispatch", n},
                             {"dispatches", lightVolume ? lightVolume->lastDispatches : 0},
                             {"light_volume_gpu_ms", gpuMs ? nlohmann::ordered_json(*gpuMs) : nullptr},
                             {"light_volume_ms", lightVolumeMs},
                             {"fixed_ms", fixed.stats.medianMs}};
                const double passMs = gpuMs.value_or(lightVolumeMs);
                if (n == 1) oneSliceMs = passMs;
                else r.details["speedup_over_one_slice"] = oneSliceMs / passMs;
                bench.addRecord(std::move(r));
            }
        }
    });
}
