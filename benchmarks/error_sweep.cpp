// Time against error: render the same small scene at many settings, time each on the GPU, and
// measure its error against the CPU double-precision reference (sss/mesh_reference.h,
// sss/volume_reference.h). "ms" is the time of a frame that recomputes everything the swept
// parameters affect (a light change: for meshes light buffer + one map frame + combine; for
// volumes light volume + ray cast); fixed_ms is the frame with nothing to recompute.

#include "bench.h"
#include "plot.h"

#include <glm/gtc/matrix_transform.hpp>

#include <chrono>
#include <functional>
#include <cstdio>
#include <iostream>

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

sss::Image renderOnce(BenchmarkContext& bench, const std::function<void(sss::RenderTarget&)>& render) {
    sss::RenderTarget target(bench.options().width, bench.options().height);
    target.clear({0, 0, 0, 0});
    render(target);
    return target.readColor();
}


// The meshes users render: bunny, Buddha and dragon at 400x226 (marble, default options, no
// specular, linear), converged maps against a converged CPU reference. Concave models are where
// the combine pass's visibility test fails, which the sphere cannot show. With `plot`, each mesh
// adds two series of converge time against error: the maps and the vertex estimate.
void realMeshRows(BenchmarkContext& bench, PlotSpec* plot) {
    const Options& o = bench.options();
    constexpr int kWidth = 400, kHeight = 226;
    const sss::ScatteringMaterial marble = sss::materialPreset("marble");
    for (const std::string model : {"bunny", "buddha", "dragon"}) {
        if (!bench.wanted(model)) continue;
        const std::optional<sss::Mesh> mesh = loadThesisMesh(bench, "error-sweep", model);
        if (!mesh) continue;
        const sss::Camera camera = framedCamera(mesh->bounds());
        const sss::DirectionalLight key = keyLight(camera);
        const std::string name = "mesh-reference-" + model + "-marble-" + std::to_string(kWidth) + "x" +
                                 std::to_string(kHeight) + "-" + viewAndLightTag(camera, key) + ".exr";
        const sss::Image reference = cachedReference(o, name, [&] {
            sss::MeshReferenceOptions ro;
            ro.targetRelativeError = 0.02;
            ro.absoluteError = 1e-4;
            return sss::renderMeshReference(*mesh, glm::mat4(1.0f), marble, {key}, camera, kWidth, kHeight, ro).image;
        });
        // The paper's maps at K = 8 and 16 (N = 24), then the evaluate-once vertex estimate
        // (MeshCombine::VertexEstimate, no maps) at N = 24, 96 and 384 samples per frame.
        struct Config {
            int cameras = 8, samples = 24;
            bool vertexEstimate = false;
            std::string name() const {
                return vertexEstimate ? "vertex-estimate-n" + std::to_string(samples) : "k" + std::to_string(cameras);
            }
        };
        PlotSeries mapsSeries{model + ": maps, K 8 / 16", {}, kPlotPalette[(plot ? plot->series.size() : 0) % 8]};
        PlotSeries estimateSeries{model + ": vertex estimate", {},
                                  kPlotPalette[(plot ? plot->series.size() + 1 : 0) % 8]};
        for (const Config config : {Config{8}, Config{16}, Config{8, 24, true}, Config{8, 48, true}, Config{8, 96, true},
                                    Config{8, 384, true}}) {
            const int cameras = config.cameras;
            sss::MeshRenderOptions mo;
            mo.shading = sss::MeshShading::Scattering;
            mo.cameras = cameras;
            mo.samples = config.samples;
            mo.combine = config.vertexEstimate ? sss::MeshCombine::VertexEstimate : sss::MeshCombine::PerPixel;
            mo.specular = 0.0f;
            sss::MeshScatteringRenderer renderer(mo);
            renderer.setMesh(*mesh);
            renderer.setScatteringMaterial(marble);
            renderer.setLights({key});
            sss::RenderTarget target(kWidth, kHeight);
            const double convergeMs = renderUntilConverged(renderer, camera, target);
            const sss::Image image = target.readColor();
            const sss::ErrorMetrics error = sss::computeErrorMetrics(image, reference);
            if (!o.imageDir.empty()) {
                std::filesystem::create_directories(o.imageDir);
                sss::toDisplay(image).savePng(o.imageDir / ("error-sweep-" + model + "-" + config.name() + ".png"));
                sss::toDisplay(reference).savePng(o.imageDir / ("error-sweep-" + model + "-reference.png"));
                // Linear radiance as compared, for error maps of one's own.
                image.saveExr(o.imageDir / ("error-sweep-" + model + "-" + config.name() + ".exr"));
                reference.saveExr(o.imageDir / ("error-sweep-" + model + "-reference.exr"));
                // Where the specks are: red over the reference's grey.
                sss::Image specks = reference;
                auto luminance = [](glm::vec4 c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; };
                for (int y = 0; y < kHeight; ++y)
                    for (int x = 0; x < kWidth; ++x) {
                        const float ref = luminance(reference.at(x, y));
                        if (reference.at(x, y).a > 0.0f && luminance(image.at(x, y)) < 0.5f * ref)
                            specks.at(x, y) = {1.0f, 0.0f, 0.0f, 1.0f};
                    }
                sss::toDisplay(specks).savePng(o.imageDir / ("error-sweep-" + model + "-" + config.name() + "-specks.png"));
            }
            const std::string id = "real-mesh-" + model + "-" + config.name();
            Measurement fixed = bench.measure([&](sss::RenderTarget& t) { renderer.render(camera, t); }, id + "-fixed");
            Record r;
            r.table = "error-sweep";
            r.model = model;
            r.mode = "sss";
            r.dataSize = std::to_string(mesh->triangleCount()) + " tri";
            r.params = (config.vertexEstimate ? "vertex-estimate N=" + std::to_string(config.samples)
                                              : "K=" + std::to_string(cameras) + " defaults") +
                       " relRMSE=" + std::to_string(error.relRmse) + " specks=" + std::to_string(error.speckShare);
            r.width = kWidth;
            r.height = kHeight;
            r.measurement = fixed;
            r.details = {{"sweep", "mesh-real"},
                         {"method", config.vertexEstimate ? "vertex-estimate" : "maps"},
                         {"cameras", config.vertexEstimate ? 0 : cameras},
                         {"samples", mo.samples},
                         {"map_resolution", mo.mapResolution},
                         {"converge_ms", convergeMs},
                         {"ms", convergeMs},  // regeneration: every accumulated frame
                         {"fixed_ms", fixed.stats.medianMs},
                         {"rel_rmse", error.relRmse},
                         {"speck_share", error.speckShare},
                         {"psnr_db", error.psnr},
                         {"material", "marble"}};
            (config.vertexEstimate ? estimateSeries : mapsSeries).points.emplace_back(convergeMs, error.relRmse);
            std::cerr << "sss-bench: " << model << " " << config.name() << " relRMSE " << error.relRmse << " specks "
                      << error.speckShare << " converged in " << convergeMs << " ms\n";
            bench.addRecord(std::move(r));
        }
        if (plot) {
            plot->series.push_back(std::move(mapsSeries));
            plot->series.push_back(std::move(estimateSeries));
        }
    }
}

PlotSpec meshSweep(BenchmarkContext& bench) {
    const Options& o = bench.options();
    const bool quick = o.quick;
    PlotSpec plot{"mesh scattering: time against error (CPU reference)", "time per light change (ms)",
                  "relative RMSE", {}};
    if (!bench.wanted("sphere")) {
        // Real meshes only: their front is the plot (regeneration time against error).
        if (!quick) {
            plot = {"real meshes: regeneration time against error (CPU reference)",
                    "time to regenerate: light buffer + 8 frames (ms)", "relative RMSE", {}};
            realMeshRows(bench, &plot);
            meshScaleSweep(bench, &plot);
        }
        return plot;
    }
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
    // One configuration: its first (single-frame) image's error on a fresh renderer, then the
    // time of a light change and of a fixed frame.
    auto run = [&](const sss::MeshRenderOptions& mo, const std::string& method, PlotSeries& series) {
        const bool estimate = mo.combine == sss::MeshCombine::VertexEstimate;
        sss::MeshScatteringRenderer renderer(mo);
        renderer.setMesh(sphere);
        renderer.setScatteringMaterial(potato);
        renderer.setLights({key});
        const std::string what = (estimate ? "vertex-estimate" : "k" + std::to_string(mo.cameras)) + "-n" +
                                 std::to_string(mo.samples) + "-r" + std::to_string(mo.mapResolution);
        const sss::Image image = renderOnce(bench, [&](sss::RenderTarget& t) { renderer.render(camera, t); });
        const sss::ErrorMetrics error = sss::computeErrorMetrics(image, reference.image);
        const auto [change, fixed] = measureChangeAndFixed(bench, renderer, camera, key, "sweep-mesh-" + what);

        Record r;
        r.table = "error-sweep";
        r.model = "sphere";
        r.mode = "sss";
        r.dataSize = std::to_string(sphere.triangleCount()) + " tri";
        r.params = (estimate ? "vertex-estimate" : "K=" + std::to_string(mo.cameras)) + " N=" +
                   std::to_string(mo.samples) + (estimate ? " light buffer=" : " maps=") +
                   std::to_string(mo.mapResolution) + " relRMSE=" + std::to_string(error.relRmse);
        r.width = o.width;
        r.height = o.height;
        r.measurement = change;
        r.details = {{"sweep", "mesh"},
                     {"method", method},
                     {"cameras", estimate ? 0 : mo.cameras},
                     {"samples", mo.samples},
                     {"map_resolution", mo.mapResolution},
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
    };
    for (int resolution : resolutions) {
        sss::MeshRenderOptions mo;
        mo.shading = sss::MeshShading::Scattering;
        mo.combine = sss::MeshCombine::PerPixel;  // the paper's maps; the estimate's series follows
        mo.mapResolution = mo.lightMapResolution = resolution;
        mo.accumulationFrames = 1;
        mo.millimetresPerUnit = mmPerUnit;
        mo.specular = 0.0f;
        for (int cameras : cameraCounts) {
            PlotSeries series{"K " + std::to_string(cameras) + ", maps " + std::to_string(resolution), {},
                              kPlotPalette[plot.series.size() % 8]};
            for (int samples : sampleCounts) {
                mo.cameras = cameras;
                mo.samples = samples;
                run(mo, "maps", series);
            }
            plot.series.push_back(std::move(series));
        }
        // Evaluate-once: the radiosity at the sphere's vertices, no maps (the resolution is the
        // light buffer's).
        PlotSeries series{"vertex estimate, light buffer " + std::to_string(resolution), {},
                          kPlotPalette[plot.series.size() % 8]};
        mo.combine = sss::MeshCombine::VertexEstimate;
        for (int samples : quick ? std::vector<int>{8} : std::vector<int>{24, 96, 384}) {
            mo.samples = samples;
            run(mo, "vertex-estimate", series);
        }
        plot.series.push_back(std::move(series));
    }
    if (!quick) {  // other axes than the sphere's: records only
        realMeshRows(bench, nullptr);
        meshScaleSweep(bench);
    }
    return plot;
}

// Scenes where the light volume showed artefacts: rings on opaque and thin structures (the
// shell with ct-bone lit from the side, opaque blobs), banding at reduced light-volume
// resolution (the bonsai at scale 0.25). 400x226, scattering, GPU step 0.5 voxel, against the
// CPU reference at 1/8 voxel (view) and 1/4 voxel (shadow rays).
void lightVolumeArtefactRows(BenchmarkContext& bench) {
    const Options& o = bench.options();
    constexpr int kWidth = 400, kHeight = 226;
    struct Case {
        std::string name;
        std::optional<sss::Volume> volume;
        sss::TransferFunction tf;
        glm::vec3 lightDirection;
        float lightVolumeScale;
    };
    std::vector<Case> cases;
    if (bench.wanted("shell"))
        cases.push_back({"shell", sss::makeShellVolume(), sss::TransferFunction::preset("ct-bone"), {1.0f, -0.4f, -0.2f}, 1.0f});
    if (bench.wanted("opaque-blobs"))
        cases.push_back({"opaque-blobs", sss::makeBlobsVolume(64),
                         sss::TransferFunction({{0.0f, {0.9f, 0.8f, 0.7f}, 0.0f}, {0.25f, {0.9f, 0.8f, 0.7f}, 0.0f},
                                                {0.3f, {0.9f, 0.8f, 0.7f}, 1.0f}, {1.0f, {0.9f, 0.8f, 0.7f}, 1.0f}}),
                         {-0.6f, -0.8f, -0.3f}, 1.0f});
    if (bench.wanted("bonsai"))
        if (auto bonsai = loadThesisVolume(bench, "error-sweep", "bonsai"))
            for (float scale : {1.0f, 0.25f})
                cases.push_back({scale == 1.0f ? "bonsai" : "bonsai-lv0.25", bonsai->first,
                                 sss::TransferFunction::preset("bonsai"), {-1.0f, -1.0f, -0.3f}, scale});
    const glm::vec4 background{0.0f, 0.0f, 0.0f, 1.0f};
    for (Case& c : cases) {
        const sss::Volume& volume = *c.volume;
        const sss::Camera camera = framedCamera(volume.worldBounds());
        const sss::DirectionalLight light{.direction = c.lightDirection};
        const std::string refName = c.name.substr(0, c.name.find("-lv"));
        const sss::Image reference = cachedReference(
            o, "volume-reference-" + refName + "-" + std::to_string(kWidth) + "x" + std::to_string(kHeight) + "-" +
                   viewAndLightTag(camera, light) + ".exr",
            [&] {
                sss::VolumeReferenceOptions ro;
                ro.shading = sss::ReferenceShading::Scattering;
                ro.background = glm::dvec4(background);
                return sss::renderVolumeReference(volume, c.tf, 256, glm::mat4(1.0f), {light}, camera, kWidth, kHeight, ro);
            });
        sss::VolumeRenderOptions vo;
        vo.shading = sss::VolumeShading::Scattering;
        vo.stepSize = 0.5f;
        vo.earlyTermination = 1.0f;
        vo.lightVolumeScale = c.lightVolumeScale;
        sss::VolumeScatteringRenderer renderer(vo);
        renderer.setVolume(volume);
        renderer.setTransferFunction(c.tf);
        renderer.setLights({light});
        sss::RenderTarget target(kWidth, kHeight);
        target.clear(background);
        renderer.render(camera, target);
        const sss::Image image = target.readColor();
        const sss::ErrorMetrics error = sss::computeErrorMetrics(image, reference);
        if (!o.imageDir.empty()) {
            std::filesystem::create_directories(o.imageDir);
            sss::toDisplay(image).savePng(o.imageDir / ("error-sweep-" + c.name + ".png"));
            sss::toDisplay(reference).savePng(o.imageDir / ("error-sweep-" + refName + "-reference.png"));
        }
        std::cerr << "sss-bench: " << c.name << " relRMSE " << error.relRmse << "\n";
        const std::string id = "light-volume-" + c.name;
        Measurement fixed = bench.measure([&](sss::RenderTarget& t) { renderer.render(camera, t); }, id + "-fixed");
        Record r;
        r.table = "error-sweep";
        r.model = c.name;
        r.mode = "scattering";
        const glm::ivec3 d = volume.dims();
        r.dataSize = dimsText(d);
        r.params = "LV=" + std::to_string(c.lightVolumeScale) + " step=0.5 relRMSE=" + std::to_string(error.relRmse);
        r.width = kWidth;
        r.height = kHeight;
        r.measurement = fixed;
        r.details = {{"sweep", "light-volume-artefacts"},
                     {"light_volume_scale", c.lightVolumeScale},
                     {"step_voxels", 0.5},
                     {"preintegration", vo.preintegration},
                     {"fixed_ms", fixed.stats.medianMs},
                     {"rel_rmse", error.relRmse},
                     {"psnr_db", error.psnr}};
        bench.addRecord(std::move(r));
    }
}

PlotSpec volumeSweep(BenchmarkContext& bench) {
    const Options& o = bench.options();
    const bool quick = o.quick;
    if (!bench.wanted("blobs")) {
        if (!quick) lightVolumeArtefactRows(bench);
        return {"volume scattering: time against error (CPU reference)", "time per light change (ms)", "relative RMSE", {}};
    }
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
    // Pre-integrated classification (the default) at every setting; the thesis's
    // post-classification beside it at early termination 0.99.
    for (const bool preintegration : {true, false})
    for (float termination : terminations)
        for (float scale : scales) {
            if (!preintegration && termination != 0.99f) continue;
            char label[64];
            std::snprintf(label, sizeof label, "LV %.2f, ET %.2f%s", scale, termination, preintegration ? "" : ", post");
            PlotSeries series{label, {}, kPlotPalette[plot.series.size() % 8]};
            for (float step : steps) {
                sss::VolumeRenderOptions vo;
                vo.shading = sss::VolumeShading::Scattering;
                vo.stepSize = step;
                vo.earlyTermination = termination;
                vo.lightVolumeScale = scale;
                vo.preintegration = preintegration;
                sss::VolumeScatteringRenderer renderer(vo);
                renderer.setVolume(volume);
                renderer.setTransferFunction(tf);
                renderer.setLights({key});
                char idBuffer[96];
                std::snprintf(idBuffer, sizeof idBuffer, "sweep-volume-lv%.2f-step%.2f-et%.2f%s", scale, step, termination,
                              preintegration ? "" : "-post");
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
                r.dataSize = dimsText(d);
                char params[128];
                std::snprintf(params, sizeof params, "LV=%.2f step=%.2f ET=%.2f %s relRMSE=%.4f", scale, step,
                              termination, preintegration ? "pre-integrated" : "post-classified", error.relRmse);
                r.params = params;
                r.width = o.width;
                r.height = o.height;
                r.measurement = change;
                r.details = {{"sweep", "volume"},
                             {"light_volume_scale", scale},
                             {"step_voxels", step},
                             {"early_termination", termination},
                             {"preintegration", preintegration},
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
    if (!quick) lightVolumeArtefactRows(bench);
    return plot;
}

}  // namespace

PlotSpec runErrorSweep(BenchmarkContext& bench, const std::string& which) {
    return which == "mesh" ? meshSweep(bench) : volumeSweep(bench);
}
