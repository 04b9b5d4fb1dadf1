// The light-volume sweep against the slices each dispatch advances it (1 = one dispatch per
// slice, filtered lookups), side by side in one run: the rebuild's GPU time (timestamps around
// the pass, mean over the timed change frames) and wall time (change minus fixed frames), and its
// dispatch count, per volume and model (the paper's sweep gathers a chromaticity cone, whose taps reach further per slice and so
// allow fewer slices per dispatch; the physical model's sweep carries the intensity alone). The
// light volume is the same whatever the slices (tests/gl/test_volume_scattering.cpp).

#include "bench.h"

#include <sss/option_names.h>

namespace {

constexpr const char* kTable = "light-sweep";

}  // namespace

void runLightSweepTable(BenchmarkContext& bench) {
    const bool quick = bench.options().quick;
    const std::vector<int> slices = quick ? std::vector<int>{1, 16} : std::vector<int>{1, 2, 4, 8, 16};
    forEachShownVolume(bench, kTable, {"bonsai", "engine"},
                       [&](const std::string& model, const FramedVolume& scene, sss::VolumeScatteringRenderer& renderer) {
        for (sss::VolumeModel volumeModel : {sss::VolumeModel::Paper, sss::VolumeModel::Physical}) {
            double oneSliceMs = 0.0;
            for (int n : slices) {
                sss::VolumeRenderOptions options = thesisVolumeOptions(bench.options(), sss::VolumeShading::Scattering);
                options.model = volumeModel;
                options.lightSweepSlices = n;
                options.gpuPassTimes = true;
                renderer.setOptions(options);
                const std::string id = std::string(kTable) + "-" + model + "-" + std::string(sss::enumName(volumeModel)) +
                                       "-" + std::to_string(n);
                ChangeAndFixedPasses passes{PassRecorder(renderer.stats()), PassRecorder(renderer.stats())};
                const auto [change, fixed] = measureChangeAndFixed(bench, renderer, scene.camera, scene.key, id, &passes);
                const std::optional<double> gpuMs = passes.change.gpuMs("light-volume");
                const sss::PassStats* lightVolume = renderer.stats().find("light-volume");
                Record r;
                r.table = kTable;
                r.model = model;
                r.mode = "light-volume";
                r.dataSize = dimsText(scene.volume.dims());
                r.params = std::string(sss::enumName(volumeModel)) + ", at most " + std::to_string(n) +
                           " slices per dispatch (median = change)";
                r.width = bench.options().width;
                r.height = bench.options().height;
                r.measurement = change;
                const double lightVolumeMs = change.stats.medianMs - fixed.stats.medianMs;
                r.details = {{"volume_model", sss::enumName(volumeModel)},
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
