// Time against error: render the same small scene at many settings, time each on the GPU, and
// measure its error against the CPU double-precision reference (sss/mesh_reference.h,
// sss/volume_reference.h). "ms" is the time of a frame that recomputes everything the swept
// parameters affect (a light change: for meshes light buffer + one map frame + combine; for
// volumes light volume + ray cast); fixed_ms is the frame with nothing to recompute.

#include "bench.h"
#include "plot.h"

#include <glm/gtc/matrix_transform.hpp>

#include <chrono>
#include <cstdio>
#include <iostream>

namespace {

const unsigned kPalette[] = {0x1f77b4, 0xff7f0e, 0x2ca02c, 0xd62728, 0x9467bd, 0x8c564b, 0xe377c2, 0x7f7f7f};

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

sss::Image renderOnce(BenchmarkContext& bench, const std::function<void(sss::RenderTarget&)>& render) {
    sss::RenderTarget target(bench.options().width, bench.options().height);
    target.clear({0, 0, 0, 0});
    render(target);
    return target.readColor();
}

PlotSpec meshSweep(BenchmarkContext& bench) {
    const Options& o = bench.options();
    const bool quick = o.quick;
    // The accuracy test's scene: a 4 cm potato sphere (20 mm per unit), one directional light.
    const sss::Mesh sphere = sss::makeUvSphere(48, 32);
    const sss::ScatteringMaterial potato = sss::materialPreset("potato");
    const double mmPerUnit = 20.0;
    sss::Camera camera;
    camera.setDistance(3.2f);
    camera.setYaw(20.0f);
    camera.setPitch(10.0f);
    const sss::DirectionalLight key{.direction = {-0.6f, -0.5f, -1.0f}};

    auto start = std::chrono::steady_clock::now();
    sss::MeshReferenceOptions ro;
    ro.millimetresPerUnit = mmPerUnit;
    ro.targetRelativeError = quick ? 0.05 : 0.01;
    const sss::MeshReferenceResult reference =
        sss::renderMeshReference(sphere, glm::mat4(1.0f), potato, {key}, camera, o.width, o.height, ro);
    std::cerr << "sss-bench: mesh reference " << o.width << "x" << o.height << " in " << secondsSince(start)
              << " s, its own relRmse ~" << reference.relativeRmseEstimate << "\n";

    const std::vector<int> cameraCounts = quick ? std::vector<int>{4, 8} : std::vector<int>{4, 8, 16};
    const std::vector<int> sampleCounts = quick ? std::vector<int>{8} : std::vector<int>{6, 12, 24, 48};
    const std::vector<int> resolutions = quick ? std::vector<int>{128} : std::vector<int>{256, 512};
    PlotSpec plot{"mesh scattering: time against error (CPU reference)", "time per light change (ms)",
                  "relative RMSE", {}};
    for (int resolution : resolutions)
        for (int cameras : cameraCounts) {
            PlotSeries series{"K " + std::to_string(cameras) + ", maps " + std::to_string(resolution), {},
                              kPalette[plot.series.size() % 8]};
            for (int samples : sampleCounts) {
                sss::MeshRenderOptions mo;
                mo.shading = sss::MeshShading::Scattering;
                mo.cameras = cameras;
                mo.samples = samples;
                mo.mapResolution = mo.lightMapResolution = resolution;
                mo.accumulationFrames = 1;
                mo.millimetresPerUnit = mmPerUnit;
                mo.specular = 0.0f;
                sss::MeshScatteringRenderer renderer(mo);
                renderer.setMesh(sphere);
                renderer.setScatteringMaterial(potato);
                renderer.setLights({key});
                const std::string id = "sweep-mesh-k" + std::to_string(cameras) + "-n" + std::to_string(samples) +
                                       "-r" + std::to_string(resolution);
                // Error first, on a fresh renderer's first (single-frame) result.
                const sss::Image image = renderOnce(bench, [&](sss::RenderTarget& t) { renderer.render(camera, t); });
                const sss::ErrorMetrics error = sss::computeErrorMetrics(image, reference.image);
                const auto [change, fixed] = measureChangeAndFixed(bench, renderer, camera, key, id);

                Record r;
                r.table = "error-sweep";
                r.model = "sphere";
                r.mode = "sss";
                r.dataSize = std::to_string(sphere.triangleCount()) + " tri";
                r.params = "K=" + std::to_string(cameras) + " N=" + std::to_string(samples) + " maps=" +
                           std::to_string(resolution) + " relRMSE=" + std::to_string(error.relRmse);
                r.width = o.width;
                r.height = o.height;
                r.measurement = change;
                r.details = {{"sweep", "mesh"},
                             {"cameras", cameras},
                             {"samples", samples},
                             {"map_resolution", resolution},
                             {"ms", change.stats.medianMs},
                             {"fixed_ms", fixed.stats.medianMs},
                             {"rel_rmse", error.relRmse},
                             {"psnr_db", error.psnr},
                             {"max_abs_error", error.maxAbsError},
                             {"reference_rel_rmse", reference.relativeRmseEstimate},
                             {"material", "potato"},
                             {"millimetres_per_unit", mmPerUnit}};
                bench.addRecord(std::move(r));
                series.points.emplace_back(change.stats.medianMs, error.relRmse);
            }
            plot.series.push_back(std::move(series));
        }
    return plot;
}

PlotSpec volumeSweep(BenchmarkContext& bench) {
    const Options& o = bench.options();
    const bool quick = o.quick;
    const sss::Volume volume = sss::makeBlobsVolume(quick ? 32 : 64);
    const sss::TransferFunction tf({{0.0f, {0, 0, 0}, 0.0f},
                                    {0.2f, {0.9f, 0.4f, 0.1f}, 0.0f},
                                    {0.5f, {1.0f, 0.8f, 0.3f}, 0.15f},
                                    {1.0f, {0.4f, 0.7f, 1.0f}, 0.6f}});
    const sss::Camera camera = framedCamera(volume.worldBounds());
    const sss::DirectionalLight key = keyLight(camera);
    const glm::vec4 background{0.1f, 0.1f, 0.12f, 1.0f};  // BenchmarkContext's clear colour

    auto start = std::chrono::steady_clock::now();
    sss::VolumeReferenceOptions ro;
    ro.shading = sss::ReferenceShading::Scattering;
    ro.background = glm::dvec4(background);
    const sss::ConvergedReference reference = sss::renderVolumeReferenceConverged(
        volume, tf, 256, glm::mat4(1.0f), {key}, camera, o.width, o.height, ro, quick ? 1e-3 : 1e-4, 0.5, 1.0 / 32.0);
    std::cerr << "sss-bench: volume reference " << o.width << "x" << o.height << " in " << secondsSince(start)
              << " s, step " << reference.stepVoxels << " voxels, last change " << reference.lastChange << "\n";

    const std::vector<float> scales = quick ? std::vector<float>{0.5f, 1.0f} : std::vector<float>{0.25f, 0.5f, 1.0f};
    const std::vector<float> steps = quick ? std::vector<float>{1.0f, 0.5f} : std::vector<float>{2.0f, 1.0f, 0.5f, 0.25f};
    const std::vector<float> terminations = quick ? std::vector<float>{0.99f} : std::vector<float>{0.95f, 0.99f, 1.0f};
    PlotSpec plot{"volume scattering: time against error (CPU reference)", "time per light change (ms)",
                  "relative RMSE", {}};
    for (float termination : terminations)
        for (float scale : scales) {
            char label[64];
            std::snprintf(label, sizeof label, "LV %.2f, ET %.2f", scale, termination);
            PlotSeries series{label, {}, kPalette[plot.series.size() % 8]};
            for (float step : steps) {
                sss::VolumeRenderOptions vo;
                vo.shading = sss::VolumeShading::Scattering;
                vo.stepSize = step;
                vo.earlyTermination = termination;
                vo.lightVolumeScale = scale;
                sss::VolumeScatteringRenderer renderer(vo);
                renderer.setVolume(volume);
                renderer.setTransferFunction(tf);
                renderer.setLights({key});
                char idBuffer[96];
                std::snprintf(idBuffer, sizeof idBuffer, "sweep-volume-lv%.2f-step%.2f-et%.2f", scale, step, termination);
                sss::RenderTarget target(o.width, o.height);
                target.clear(background);
                renderer.render(camera, target);
                const sss::ErrorMetrics error = sss::computeErrorMetrics(target.readColor(), reference.image);
                const auto [change, fixed] = measureChangeAndFixed(bench, renderer, camera, key, idBuffer);

                Record r;
                r.table = "error-sweep";
                r.model = "blobs";
                r.mode = "scattering";
                const glm::ivec3 d = volume.dims();
                r.dataSize = std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z);
                char params[128];
                std::snprintf(params, sizeof params, "LV=%.2f step=%.2f ET=%.2f relRMSE=%.4f", scale, step, termination,
                              error.relRmse);
                r.params = params;
                r.width = o.width;
                r.height = o.height;
                r.measurement = change;
                r.details = {{"sweep", "volume"},
                             {"light_volume_scale", scale},
                             {"step_voxels", step},
                             {"early_termination", termination},
                             {"ms", change.stats.medianMs},
                             {"fixed_ms", fixed.stats.medianMs},
                             {"rel_rmse", error.relRmse},
                             {"psnr_db", error.psnr},
                             {"max_abs_error", error.maxAbsError},
                             {"reference_step_voxels", reference.stepVoxels}};
                bench.addRecord(std::move(r));
                series.points.emplace_back(change.stats.medianMs, error.relRmse);
            }
            plot.series.push_back(std::move(series));
        }
    return plot;
}

}  // namespace

PlotSpec runErrorSweep(BenchmarkContext& bench, const std::string& which) {
    return which == "mesh" ? meshSweep(bench) : volumeSweep(bench);
}
