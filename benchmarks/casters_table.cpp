// Fragment against compute ray casting, side by side in one run: per volume, each mode with the
// thesis's ray casting (step 1, post-classification) and emission-absorption and fixed
// scattering with the library's defaults (step 0.5, pre-integration). The two casters give the
// same image (tests/gl/test_ray_caster.cpp); this says which is faster on this device, the
// measurement RayCaster::Auto's choice rests on.

#include "bench.h"

#include <sss/option_names.h>

namespace {

constexpr const char* kTable = "casters";

struct ModeCase {
    sss::VolumeShading shading;
    bool thesis;  // the thesis's ray casting, else the library's defaults
};

sss::VolumeRenderOptions optionsFor(const Options& run, const ModeCase& m, sss::RayCaster caster) {
    sss::VolumeRenderOptions o = m.thesis ? thesisVolumeOptions(run, m.shading) : sss::VolumeRenderOptions{};
    o.shading = m.shading;
    o.rayCaster = caster;
    return o;
}

}  // namespace

void runCastersTable(BenchmarkContext& bench) {
    const std::vector<ModeCase> modes = {{sss::VolumeShading::EmissionAbsorption, true},
                                         {sss::VolumeShading::Gradient, true},
                                         {sss::VolumeShading::Scattering, true},
                                         {sss::VolumeShading::EmissionAbsorption, false},
                                         {sss::VolumeShading::Scattering, false}};
    // What every row's frame costs before anything is drawn: the target's clear.
    const double clearMs = bench.measureClearOnly().stats.medianMs;
    forEachShownVolume(bench, kTable, {"bucky", "bonsai", "engine"},
                       [&](const std::string& model, const FramedVolume& scene, sss::VolumeScatteringRenderer& renderer) {
        const glm::ivec3 d = scene.volume.dims();
        for (const ModeCase& m : modes) {
            const std::string settings = m.thesis ? "thesis" : "defaults";
            double fragmentMs = 0.0;
            for (sss::RayCaster caster : {sss::RayCaster::Fragment, sss::RayCaster::Compute}) {
                const sss::VolumeRenderOptions options = optionsFor(bench.options(), m, caster);
                renderer.setOptions(options);
                Record r;
                r.table = kTable;
                r.model = model;
                r.mode = std::string(sss::enumName(m.shading));
                r.dataSize = dimsText(d);
                r.params = std::string(sss::enumName(caster)) + ", " + settings + " (step " +
                           std::to_string(options.stepSize).substr(0, 4) + ")";
                r.width = bench.options().width;
                r.height = bench.options().height;
                r.measurement = bench.measure([&](sss::RenderTarget& t) { renderer.render(scene.camera, t); },
                                              std::string(kTable) + "-" + model + "-" + r.mode + "-" + settings + "-" +
                                                  std::string(sss::enumName(caster)));
                r.details = {{"ray_caster", sss::enumName(caster)},
                             {"settings", settings},
                             {"step_voxels", options.stepSize},
                             {"preintegration", options.preintegration},
                             {"transfer_function", scene.preset},
                             {"clear_ms", clearMs}};
                if (caster == sss::RayCaster::Fragment) fragmentMs = r.measurement.stats.medianMs;
                else r.details["compute_over_fragment"] = r.measurement.stats.medianMs / fragmentMs;
                bench.addRecord(std::move(r));
            }
        }
    });
}
