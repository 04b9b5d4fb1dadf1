// Accuracy against physics (sss-bench --accuracy slab): the subsurface profiles and the GPU
// renderer measured against the slab random walk (sss/random_walk.h), per material, channel and
// incidence angle. Radiance leaving near the normal per unit irradiance on the surface:
//  - random_walk: simulateSlab's cone radiance (isotropic walk with the preset's reduced
//    coefficients and eta, smooth dielectric), with its standard error;
//  - dipole / calibrated: profileSlabRadiance() of each profile, averaged over the same cone;
//  - gpu: the renderer (default options, calibrated profile, no specular) on a wide, thick slab
//    seen head-on, mean of the centre pixels, divided by the irradiance cos(theta).
#include "accuracy.h"
#include "volume_accuracy.h"

#include "bench.h"

#include "plot.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <numbers>
#include <optional>
#include <sstream>

namespace {

constexpr double kConeHalfAngleDeg = 15.0;  // wide enough for 1 % walk error at 400k paths
const char* const kChannel[] = {"R", "G", "B"};

glm::dvec3 coneAverage(const sss::DipoleConstants& c, double cosIncidence) {
    return sss::profileSlabConeRadiance(c, cosIncidence, kConeHalfAngleDeg);
}

// The GPU's radiance at the middle of a wide, thick slab seen head-on, per unit irradiance.
glm::dvec3 gpuSlab(const sss::ScatteringMaterial& material, double incidenceDeg, sss::ScatteringProfile profile) {
    // 2 x 2 x 1 units at 100 mm per unit: 20 cm wide, 10 cm thick, many transport lengths of
    // every preset (ketchup R, the widest, has 1 / sigma_tr = 4.8 mm and a 14 mm disk).
    const sss::Mesh slab = sss::makeSlab({2.0f, 2.0f, 1.0f});
    sss::MeshRenderOptions o;
    o.shading = sss::MeshShading::Scattering;
    o.specular = 0.0f;
    o.millimetresPerUnit = 100.0;
    o.profile = profile;
    sss::MeshScatteringRenderer renderer(o);
    renderer.setMesh(slab);
    renderer.setScatteringMaterial(material);
    const double theta = incidenceDeg * std::numbers::pi / 180.0;
    renderer.setLights({sss::DirectionalLight{
        .direction = glm::vec3(static_cast<float>(-std::sin(theta)), 0.0f, static_cast<float>(-std::cos(theta)))}});
    sss::Camera camera;  // looks at the +z face from +z
    camera.setProjectionType(sss::Projection::Orthographic);
    camera.setOrthoHeight(0.5f);
    camera.setDistance(3.0f);
    constexpr int kSide = 64;
    sss::RenderTarget target(kSide, kSide);
    do {
        target.clear({0, 0, 0, 0});
        renderer.render(camera, target);
    } while (!renderer.converged());
    const sss::Image image = target.readColor();
    glm::dvec3 sum(0.0);
    int n = 0;
    for (int y = kSide / 4; y < 3 * kSide / 4; ++y)
        for (int x = kSide / 4; x < 3 * kSide / 4; ++x) {
            const glm::vec4 p = image.at(x, y);
            sum += glm::dvec3(p.r, p.g, p.b);
            ++n;
        }
    return sum / (n * std::cos(theta));
}

std::string percent(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%+.1f %%", 100.0 * v);
    return buf;
}

}  // namespace

AccuracyReport runSlabAccuracy(const AccuracyOptions& options) {
    AccuracyReport report;
    report.json = nlohmann::ordered_json::array();
    const std::vector<std::string> materials =
        options.quick ? std::vector<std::string>{"potato", "ketchup"}
                      : std::vector<std::string>{"cream", "potato", "marble", "skimmilk", "ketchup", "skin1", "apple",
                                                 "chicken1"};
    const std::vector<double> angles = options.quick ? std::vector<double>{0.0, 45.0} : std::vector<double>{0.0, 45.0, 75.0};
    sss::SlabRandomWalkOptions walkOptions;
    walkOptions.paths = options.quick ? 50000 : 400000;
    walkOptions.coneHalfAngleDeg = kConeHalfAngleDeg;
    std::ostringstream md;
    md << "# Slab accuracy: profiles and GPU against the random walk\n\n"
       << "Radiance leaving within " << kConeHalfAngleDeg
       << " degrees of the normal, per unit irradiance on the surface (sr^-1), semi-infinite medium, "
          "collimated light at the incidence angle. Random walk: "
       << walkOptions.paths
       << " paths per channel (x20 for ketchup; isotropic, reduced coefficients, smooth dielectric); error "
          "columns are (model - walk) / walk; exact: the isotropic half-space's exact value (H-function and adding "
          "equation), which the walk estimates, and the last column the calibrated profile against it. GPU: "
       << options.renderer << ", default options, calibrated profile, 20 x 20 x 10 cm slab seen head-on.\n\n"
       << "| material | ch | incidence | walk | +- | exact | dipole | calibrated | gpu | dipole err | calibrated err | gpu err | gpu vs calibrated | calibrated vs exact |\n"
       << "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    // Bar chart: per material, the worst channel's |error| at 0 and 45 degrees.
    PlotSeries dipoleSeries{"dipole", {}, 0xd62728, false}, calibratedSeries{"calibrated", {}, 0x1f77b4, false};
    std::vector<std::string> categories;
    for (const std::string& name : materials) {
        categories.push_back(name);
        dipoleSeries.points.push_back({0.0, 0.0});
        calibratedSeries.points.push_back({0.0, 0.0});
        const sss::ScatteringMaterial m = sss::materialPreset(name);
        const sss::DipoleConstants dipole = sss::deriveDipoleConstants(m, 1.0, sss::ScatteringProfile::Dipole);
        const sss::DipoleConstants calibrated = sss::deriveDipoleConstants(m, 1.0, sss::ScatteringProfile::Calibrated);
        for (double angle : angles) {
            const auto start = std::chrono::steady_clock::now();
            // Low-albedo media (ketchup) return little light in few events: more paths, same cost.
            sss::SlabRandomWalkOptions o = walkOptions;
            if (std::max({dipole.alphaPrime.x, dipole.alphaPrime.y, dipole.alphaPrime.z}) < 0.95) o.paths *= 20;
            const sss::SlabRandomWalkResult walk = sss::simulateSlab(m, angle, o);
            const double cosI = std::cos(angle * std::numbers::pi / 180.0);
            const glm::dvec3 d = coneAverage(dipole, cosI), c = coneAverage(calibrated, cosI);
            const glm::dvec3 gpu = options.gpu ? gpuSlab(m, angle, sss::ScatteringProfile::Calibrated) : glm::dvec3(0.0);
            std::cerr << "sss-bench: accuracy slab " << name << " " << angle << " deg: "
                      << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s\n";
            for (int ch = 0; ch < 3; ++ch) {
                const double w = walk.channels[ch].coneRadiance.value, se = walk.channels[ch].coneRadiance.standardError;
                const double relD = d[ch] / w - 1.0, relC = c[ch] / w - 1.0, relG = gpu[ch] / w - 1.0;
                // The walk's exact value (isotropic half-space, no noise): what it estimates.
                const double exact =
                    sss::isotropicHalfSpaceReflectance(dipole.alphaPrime[ch], m.eta, angle, kConeHalfAngleDeg).coneRadiance;
                const double relExactC = c[ch] / exact - 1.0, relExactD = d[ch] / exact - 1.0;
                const double gpuVsModel = gpu[ch] / c[ch] - 1.0;
                report.json.push_back({{"material", name},
                                       {"channel", kChannel[ch]},
                                       {"incidence_deg", angle},
                                       {"random_walk", w},
                                       {"random_walk_stderr", se},
                                       {"random_walk_single", walk.channels[ch].coneRadianceSingle.value},
                                       {"exact", exact},
                                       {"rel_error_dipole_vs_exact", relExactD},
                                       {"rel_error_calibrated_vs_exact", relExactC},
                                       {"dipole", d[ch]},
                                       {"calibrated", c[ch]},
                                       {"gpu", options.gpu ? nlohmann::ordered_json(gpu[ch]) : nlohmann::ordered_json(nullptr)},
                                       {"rel_error_dipole", relD},
                                       {"rel_error_calibrated", relC},
                                       {"rel_error_gpu", options.gpu ? nlohmann::ordered_json(relG) : nlohmann::ordered_json(nullptr)},
                                       {"rel_error_gpu_vs_calibrated",
                                        options.gpu ? nlohmann::ordered_json(gpuVsModel) : nlohmann::ordered_json(nullptr)},
                                       {"cone_half_angle_deg", kConeHalfAngleDeg},
                                       {"paths", o.paths}});
                md << "| " << name << " | " << kChannel[ch] << " | " << angle << " | " << fixed(w, 5) << " | "
                   << fixed(se, 5) << " | " << fixed(exact, 5) << " | " << fixed(d[ch], 5) << " | " << fixed(c[ch], 5) << " | "
                   << (options.gpu ? fixed(gpu[ch], 5) : "–") << " | " << percent(relD) << " | " << percent(relC)
                   << " | " << (options.gpu ? percent(relG) : "–") << " | " << (options.gpu ? percent(gpuVsModel) : "–")
                   << " | " << percent(relExactC) << " |\n";
                if (angle < 60.0) {
                    // |error| + 0.1 % so that the log axis keeps exact matches.
                    double& worstD = dipoleSeries.points.back().second;
                    double& worstC = calibratedSeries.points.back().second;
                    worstD = std::max(worstD, 100.0 * std::abs(relD) + 0.1);
                    worstC = std::max(worstC, 100.0 * std::abs(relC) + 0.1);
                }
            }
        }
    }
    md << "\nPlot: per material, the worst channel's |error| in % (log axis) at incidence 0 and 45 degrees.\n";
    report.markdown = md.str();
    report.plot.title = "slab radiance error against the random walk";
    report.plot.xLabel = "material (worst channel, incidence 0 and 45 degrees)";
    report.plot.yLabel = "|error| % (+0.1)";
    report.plot.series = {dipoleSeries, calibratedSeries};
    report.plot.categories = categories;
    return report;
}

namespace {

struct MeshScene {
    std::string name;
    sss::Mesh mesh;
    std::string material;
    double millimetresPerUnit;
    sss::Camera camera;
    sss::DirectionalLight light;
};

sss::Image renderGpuMesh(const MeshScene& scene, sss::ScatteringProfile profile, int width, int height) {
    sss::MeshRenderOptions o;
    o.shading = sss::MeshShading::Scattering;
    o.specular = 0.0f;  // the walk has no surface reflection
    o.millimetresPerUnit = scene.millimetresPerUnit;
    o.profile = profile;
    sss::MeshScatteringRenderer renderer(o);
    renderer.setMesh(scene.mesh);
    renderer.setScatteringMaterial(sss::materialPreset(scene.material));
    renderer.setLights({scene.light});
    sss::RenderTarget target(width, height);
    do {
        target.clear({0, 0, 0, 0});
        renderer.render(scene.camera, target);
    } while (!renderer.converged());
    return target.readColor();
}

}  // namespace

AccuracyReport runMeshAccuracy(BenchmarkContext& bench, const AccuracyOptions& options) {
    AccuracyReport report;
    report.json = nlohmann::ordered_json::array();
    const int width = options.quick ? 32 : options.width, height = options.quick ? 24 : options.height;
    const float aspect = float(width) / float(height);
    std::vector<MeshScene> scenes;
    {
        // 4 mm of potato at 20 mm per unit, lit only from behind (the golden test's slab).
        MeshScene slab{"potato-slab-backlit", sss::makeSlab({1.6f, 1.0f, 0.2f}), "potato", 20.0, {}, {}};
        slab.camera.setDistance(2.5f);
        slab.light.direction = {0.2f, -0.3f, 1.0f};  // travels towards the viewer, slightly from above
        scenes.push_back(std::move(slab));
    }
    if (!options.quick) {
        if (std::optional<sss::Mesh> bunny = loadThesisMesh(bench, "accuracy-mesh", "bunny")) {
            // Radius 0.1 units at 150 mm per unit: a 3 cm bunny, where skin1's light reaches through the ears.
            MeshScene front{"bunny-front", *bunny, "skin1", 150.0, framedCamera(bunny->bounds()), {}};
            front.camera.frameTight(bunny->bounds(), aspect);
            front.light = keyLight(front.camera);
            MeshScene back = front;
            back.name = "bunny-backlit";
            // From behind the bunny, above: light travels towards the viewer.
            const glm::vec3 towardsViewer = glm::normalize(front.camera.position() - front.camera.target());
            back.light.direction = glm::normalize(towardsViewer + glm::vec3(0.0f, -0.6f, 0.0f));
            scenes.push_back(std::move(front));
            scenes.push_back(std::move(back));
        }
    }
    std::ostringstream md;
    md << "# Mesh accuracy: GPU renders against the mesh random walk\n\n"
       << width << " x " << height << ", no specular, default options (K 8, N 24, maps 512, 8 frames), "
       << options.renderer << ". Random walk (renderMeshRandomWalk): " << (options.quick ? 8 : options.pathsPerPixel)
       << " paths per pixel and channel; walk noise = its own expected relRMSE. rel_rmse over the covered pixels.\n\n"
       << "| scene | material | profile | rel_rmse | walk noise | mean ratio R / G / B | gpu s | walk s |\n"
       << "|---|---|---|---:|---:|---|---:|---:|\n";
    PlotSeries series[2] = {{"dipole", {}, 0xd62728, false}, {"calibrated", {}, 0x1f77b4, false}};
    for (const MeshScene& scene : scenes) {
        sss::MeshRandomWalkOptions w;
        w.pathsPerPixel = options.quick ? 8 : options.pathsPerPixel;
        w.millimetresPerUnit = scene.millimetresPerUnit;
        auto start = std::chrono::steady_clock::now();
        const sss::MeshRandomWalkResult walk = sss::renderMeshRandomWalk(
            scene.mesh, glm::mat4(1.0f), sss::materialPreset(scene.material), {scene.light}, scene.camera, width, height, w);
        const double walkSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::cerr << "sss-bench: accuracy mesh " << scene.name << ": walk " << walkSeconds << " s, noise "
                  << walk.relativeRmseEstimate << "\n";
        if (!options.imageDir.empty()) {
            std::filesystem::create_directories(options.imageDir);
            sss::toDisplay(walk.image, {}).savePng(options.imageDir / ("accuracy-mesh-" + scene.name + "-walk.png"));
        }
        for (int p = 0; p < 2; ++p) {
            const sss::ScatteringProfile profile = p == 0 ? sss::ScatteringProfile::Dipole : sss::ScatteringProfile::Calibrated;
            start = std::chrono::steady_clock::now();
            const sss::Image gpu = renderGpuMesh(scene, profile, width, height);
            const double gpuSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            const sss::ErrorMetrics m = sss::computeErrorMetrics(gpu, walk.image);
            glm::dvec3 sumGpu(0.0), sumWalk(0.0);
            for (int y = 0; y < height; ++y)
                for (int x = 0; x < width; ++x) {
                    if (walk.image.at(x, y).a <= 0.0f) continue;
                    sumGpu += glm::dvec3(gpu.at(x, y));
                    sumWalk += glm::dvec3(walk.image.at(x, y));
                }
            const glm::dvec3 ratio = sumGpu / glm::max(sumWalk, glm::dvec3(1e-30));
            const std::string profileName(sss::toString(profile));
            report.json.push_back({{"scene", scene.name},
                                   {"material", scene.material},
                                   {"profile", profileName},
                                   {"rel_rmse", m.relRmse},
                                   {"walk_noise_rel_rmse", walk.relativeRmseEstimate},
                                   {"mean_ratio", {ratio.x, ratio.y, ratio.z}},
                                   {"width", width},
                                   {"height", height},
                                   {"paths_per_pixel", w.pathsPerPixel},
                                   {"gpu_seconds", gpuSeconds},
                                   {"walk_seconds", walkSeconds}});
            md << "| " << scene.name << " | " << scene.material << " | " << profileName << " | " << fixed(100.0 * m.relRmse, 1)
               << " % | " << fixed(100.0 * walk.relativeRmseEstimate, 1) << " % | " << fixed(ratio.x, 3) << " / "
               << fixed(ratio.y, 3) << " / " << fixed(ratio.z, 3) << " | " << fixed(gpuSeconds, 1) << " | "
               << fixed(walkSeconds, 1) << " |\n";
            series[p].points.push_back({0.0, 100.0 * m.relRmse});
            if (!options.imageDir.empty())
                sss::toDisplay(gpu, {}).savePng(options.imageDir / ("accuracy-mesh-" + scene.name + "-" + profileName + ".png"));
        }
    }
    report.markdown = md.str();
    report.plot.title = "mesh images: relRMSE against the random walk";
    report.plot.xLabel = "scene";
    report.plot.yLabel = "relRMSE %";
    report.plot.series = {series[0], series[1]};
    for (const MeshScene& scene : scenes) report.plot.categories.push_back(scene.name);
    return report;
}

namespace volume_accuracy {

// The best single factor k minimising |k test - reference| over all pixels and channels: how far
// a model is off in shape once its overall brightness (the paper model has no physical units)
// is forgiven.
double bestScale(const sss::Image& test, const sss::Image& reference) {
    double tr = 0.0, tt = 0.0;
    for (int y = 0; y < test.height(); ++y)
        for (int x = 0; x < test.width(); ++x)
            for (int c = 0; c < 3; ++c) {
                tr += double(test.at(x, y)[c]) * reference.at(x, y)[c];
                tt += double(test.at(x, y)[c]) * test.at(x, y)[c];
            }
    return tt > 0.0 ? tr / tt : 1.0;
}

sss::Image scaled(sss::Image image, double k) {
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            glm::vec4 p = image.at(x, y);
            image.at(x, y) = glm::vec4(glm::vec3(p) * static_cast<float>(k), p.a);
        }
    return image;
}

glm::dvec3 meanRatio(const sss::Image& test, const sss::Image& reference) {
    glm::dvec3 t(0.0), r(0.0);
    for (int y = 0; y < test.height(); ++y)
        for (int x = 0; x < test.width(); ++x) {
            t += glm::dvec3(test.at(x, y));
            r += glm::dvec3(reference.at(x, y));
        }
    return t / glm::max(r, glm::dvec3(1e-30));
}

// The view both volume accuracy modes share: from 30 degrees aside and 20 above, framed tightly,
// one directional light from above, behind and to the right of the viewer.
sss::Camera volumeAccuracyCamera(const sss::Volume& volume, int width, int height) {
    sss::Camera camera;
    camera.setYaw(30.0f);
    camera.setPitch(20.0f);
    camera.frameTight(volume.worldBounds(), float(width) / float(height));
    return camera;
}

sss::DirectionalLight volumeAccuracyLight() {
    return {.direction = glm::normalize(glm::vec3(-0.6f, -0.7f, -0.4f))};
}

namespace {
// The truth's expected relRMSE from its standard errors (VolumePathTracerResult::relativeRmseEstimate).
double relativeNoise(const sss::Image& mean, const sss::Image& standardError) {
    double se = 0.0, m = 0.0;
    for (int y = 0; y < mean.height(); ++y)
        for (int x = 0; x < mean.width(); ++x)
            for (int c = 0; c < 3; ++c) {
                se += double(standardError.at(x, y)[c]) * standardError.at(x, y)[c];
                m += double(mean.at(x, y)[c]) * mean.at(x, y)[c];
            }
    return m > 0.0 ? std::sqrt(se / m) : 0.0;
}

}  // namespace

PathTracedTruth cachedPathTraced(BenchmarkContext& bench, const std::string& name, const sss::Volume& volume,
                                 const sss::TransferFunction& tf, const sss::DirectionalLight& light,
                                 const sss::Camera& camera, int width, int height,
                                 const sss::VolumePathTracerOptions& options) {
    std::optional<sss::VolumePathTracerResult> traced;
    auto trace = [&]() -> const sss::VolumePathTracerResult& {
        if (!traced)
            traced = sss::renderVolumePathTraced(volume, tf, 256, glm::mat4(1.0f), {light}, camera, width, height, options);
        return *traced;
    };
    const std::string tagged = name + "-" + viewAndLightTag(camera, light);
    PathTracedTruth truth;
    truth.image = cachedReference(bench.options(), tagged + ".exr", [&] { return trace().image; });
    truth.relativeRmseEstimate = relativeNoise(
        truth.image, cachedReference(bench.options(), tagged + "-stderr.exr", [&] { return trace().standardError; }));
    return truth;
}

// One frame of `renderer` into the cleared `target`, waited for: its milliseconds.
double timedFrameMs(sss::VolumeScatteringRenderer& renderer, const sss::Camera& camera, sss::RenderTarget& target) {
    target.clear({0, 0, 0, 0});
    const auto t0 = std::chrono::steady_clock::now();
    renderer.render(camera, target);
    sss::finishGpuWork();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

TimedImage renderVolumeTimed(const sss::Volume& volume, const sss::TransferFunction& tf, const sss::DirectionalLight& light,
                             const sss::VolumeRenderOptions& options, const sss::Camera& camera, int width, int height,
                             bool rebuild) {
    sss::VolumeScatteringRenderer renderer(options);
    renderer.setVolume(volume);
    renderer.setTransferFunction(tf);
    renderer.setLights({light});
    sss::RenderTarget target(width, height);
    target.clear({0, 0, 0, 0});
    renderer.render(camera, target);
    std::vector<double> times;
    for (int r = 0; r < 3; ++r) {
        if (rebuild) renderer.setLights({r % 2 == 0 ? nudged(light) : light});
        times.push_back(timedFrameMs(renderer, camera, target));
    }
    std::sort(times.begin(), times.end());
    if (rebuild) {
        renderer.setLights({light});
        target.clear({0, 0, 0, 0});
        renderer.render(camera, target);
    }
    return {target.readColor(), times[1]};
}

}  // namespace volume_accuracy

namespace {

using namespace volume_accuracy;

// Median of three timed frames of `renderer`, each waited for and each a camera move (the cache's
// light towards the viewer evaluated anew).
double fixedFrameMs(sss::VolumeScatteringRenderer& renderer, const sss::Camera& camera, sss::RenderTarget& target) {
    std::vector<double> times;
    for (int r = 0; r < 3; ++r) times.push_back(timedFrameMs(renderer, moved(camera, r), target));
    std::sort(times.begin(), times.end());
    return times[1];
}

// The multiple-scattering cache after a light change: the first frame (light volume and the
// first photons), then frames until the cache holds its photons, each timed and its error
// against the truth read back outside the clock; then fixed frames, and an emission-absorption
// frame of the same scene in the same run.
struct CacheRun {
    double firstFrameError = 0.0, refinedError = 0.0, rebuildMs = 0.0, msTo10 = -1.0, msTo5 = -1.0, totalMs = 0.0;
    double fixedMs = 0.0, eaMs = 0.0, truthNoiseShare = 0.0;
    glm::dvec3 ratio{0.0};
    std::uint64_t photons = 0;
    sss::Image image{1, 1};
};

CacheRun runScatteringCache(const sss::Volume& volume, const sss::TransferFunction& tf, const sss::DirectionalLight& light,
                            const sss::VolumeRenderOptions& options, const sss::Camera& camera, int width, int height,
                            const sss::Image& truth) {
    CacheRun run;
    sss::VolumeScatteringRenderer renderer(options);
    renderer.setVolume(volume);
    renderer.setTransferFunction(tf);
    renderer.setLights({nudged(light)});
    sss::RenderTarget target(width, height);
    target.clear({0, 0, 0, 0});
    renderer.render(camera, target);  // compiles the programs: not part of a light change
    renderer.setLights({light});
    const auto budget = static_cast<std::uint64_t>(options.cachePhotons);
    for (bool first = true; first || renderer.cachedPhotons() < budget; first = false) {
        const double ms = timedFrameMs(renderer, camera, target);
        run.totalMs += ms;
        run.image = target.readColor();
        const double error = sss::computeErrorMetrics(run.image, truth).relRmse;
        if (first) run.firstFrameError = error, run.rebuildMs = ms;
        if (run.msTo10 < 0.0 && error <= 0.10) run.msTo10 = run.totalMs;
        if (run.msTo5 < 0.0 && error <= 0.05) run.msTo5 = run.totalMs;
        run.refinedError = error;
    }
    run.photons = renderer.cachedPhotons();
    run.ratio = meanRatio(run.image, truth);
    run.fixedMs = fixedFrameMs(renderer, camera, target);
    sss::VolumeScatteringRenderer ea{sss::VolumeRenderOptions{}};
    ea.setVolume(volume);
    ea.setTransferFunction(tf);
    ea.setLights({light});
    target.clear({0, 0, 0, 0});
    ea.render(camera, target);
    run.eaMs = fixedFrameMs(ea, camera, target);
    return run;
}

}  // namespace

AccuracyReport runVolumeAccuracy(BenchmarkContext& bench, const AccuracyOptions& options) {
    AccuracyReport report;
    report.json = nlohmann::ordered_json::array();
    const int width = options.quick ? 32 : (options.width == 96 ? 128 : options.width);
    const int height = options.quick ? 18 : (options.height == 72 ? 72 : options.height);
    const int spp = options.quick ? 16 : 4 * options.pathsPerPixel;  // truth noise about 2 %
    constexpr float kG = 0.5f;  // Henyey-Greenstein g everywhere (the renderer's default anisotropy)
    struct Scene {
        std::string name;
        sss::Volume volume;
        sss::TransferFunction tf;
    };
    std::vector<Scene> scenes;
    // A uniform, nearly white, high-albedo box: where multiple scattering dominates.
    scenes.push_back({"high-albedo-box",
                      sss::Volume::fromData({32, 32, 32}, sss::VoxelType::UInt8, std::vector<uint8_t>(32 * 32 * 32, 200)),
                      sss::TransferFunction({{0.0f, {0.95f, 0.9f, 0.8f}, 0.08f}, {1.0f, {0.95f, 0.9f, 0.8f}, 0.08f}})});
    for (const std::string model : {"bucky", "bonsai", "engine"}) {
        if (options.quick && model != "bucky") continue;
        auto loaded = loadThesisVolume(bench, "accuracy-volume", options.quick ? "blobs" : model);
        if (!loaded) continue;
        scenes.push_back({options.quick ? "blobs" : model, std::move(loaded->first),
                          sss::TransferFunction::preset(loaded->second)});
    }
    std::ostringstream md;
    md << "# Volume accuracy: light volume, physical single scattering and the GPU path tracer against path-traced truth\n\n"
       << width << " x " << height << ", one directional light (intensity 1), Henyey-Greenstein g = " << kG
       << ", GPU at default options (step 0.5, pre-integrated, jitter, early termination 0.99), no anti-aliasing, "
       << options.renderer << ". Truth: renderVolumePathTraced, " << spp
       << " paths per pixel, single scattering and full multiple scattering. relRMSE over all pixels (black "
          "background); 'scaled': after the best single factor (the paper model has no physical units).\n\n"
       << "| scene | method | vs single | vs single, scaled | vs multiple | vs multiple, scaled | mean ratio to multiple R / G / B | ms |\n"
       << "|---|---|---:|---:|---:|---:|---|---:|\n";
    std::ostringstream truthMd;
    truthMd << "\n| scene | multiple / single R / G / B | truth noise single / multiple | path tracing s single / multiple (~0: --reference-cache) |\n"
            << "|---|---|---:|---:|\n";
    std::ostringstream gpuMd;
    gpuMd << "\nMultiple scattering on the GPU (gpu-path-traced: VolumeRenderOptions::multipleScattering, 8 paths "
             "per pixel and frame) against the multiple-scattering truth: relRMSE at the last frame (also without "
             "the truth's own noise, sqrt(e^2 - noise^2)), and the GPU time (frames only, each waited for) until "
             "the relRMSE first fell to 10 % and 5 %. Frames stop at the truth's path count or after "
          << (options.quick ? 5 : 120) << " s.\n\n"
          << "| scene | paths per pixel | vs multiple | without truth noise | mean ratio R / G / B | to 10 % | to 5 % | ms per frame |\n"
          << "|---|---:|---:|---:|---|---|---|---:|\n";
    std::ostringstream cacheMd;
    cacheMd << "\nThe multiple-scattering cache (multiple-scattering-cache: VolumeRenderOptions::multipleScatteringCache, "
               "physical model, defaults but the cells) after a light change, against the multiple-scattering truth: "
               "the first frame (light volume and the first photons), then frames until the cache holds its photons "
               "(error also without the truth's noise); fixed frame (camera moves: nothing rebuilt) and "
               "emission-absorption frame of the same scene in the same run, ms; each frame waited for.\n\n"
            << "| scene | cells | photons | first frame | refined | mean ratio R / G / B | rebuild ms | to 10 % | to 5 % | "
               "fixed ms | EA ms | fixed / EA | rebuild / EA |\n"
            << "|---|---:|---:|---:|---:|---|---:|---|---|---:|---:|---:|---:|\n";
    PlotSeries series[3] = {{"paper light volume (scaled)", {}, 0xd62728, false},
                            {"physical single", {}, 0x1f77b4, false},
                            {"GPU path traced vs multiple", {}, 0x2ca02c, false}};
    int index = 0;
    for (const Scene& scene : scenes) {
        ++index;
        const sss::Camera camera = volumeAccuracyCamera(scene.volume, width, height);
        const sss::DirectionalLight light = volumeAccuracyLight();
        sss::VolumePathTracerOptions po;
        po.samplesPerPixel = spp;
        po.g = kG;
        po.mode = sss::VolumeScatteringMode::SingleScattering;
        // The truths, kept in --reference-cache under names that hold what they depend on.
        const std::string truthName = "volume-truth-" + scene.name + "-" + std::to_string(width) + "x" +
                                      std::to_string(height) + "-" + std::to_string(spp) + "-g" + fixed(kG, 2);
        auto start = std::chrono::steady_clock::now();
        const PathTracedTruth single =
            cachedPathTraced(bench, truthName + "-single", scene.volume, scene.tf, light, camera, width, height, po);
        const double singleSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        po.mode = sss::VolumeScatteringMode::MultipleScattering;
        start = std::chrono::steady_clock::now();
        const PathTracedTruth multiple =
            cachedPathTraced(bench, truthName + "-multiple", scene.volume, scene.tf, light, camera, width, height, po);
        const double multipleSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::cerr << "sss-bench: accuracy volume " << scene.name << ": path tracing " << singleSeconds << " + "
                  << multipleSeconds << " s\n";
        const glm::dvec3 gain = meanRatio(multiple.image, single.image);
        truthMd << "| " << scene.name << " | " << fixed(gain.x, 2) << " / " << fixed(gain.y, 2) << " / " << fixed(gain.z, 2)
                << " | " << fixed(100.0 * single.relativeRmseEstimate, 1) << " % / "
                << fixed(100.0 * multiple.relativeRmseEstimate, 1) << " % | " << fixed(singleSeconds, 1) << " / "
                << fixed(multipleSeconds, 1) << " |\n";
        if (!options.imageDir.empty()) {
            std::filesystem::create_directories(options.imageDir);
            sss::toDisplay(single.image, {}).savePng(options.imageDir / ("accuracy-volume-" + scene.name + "-truth-single.png"));
            sss::toDisplay(multiple.image, {}).savePng(options.imageDir / ("accuracy-volume-" + scene.name + "-truth-multiple.png"));
        }
        for (int m = 0; m < 2; ++m) {
            const bool physical = m == 1;
            sss::VolumeRenderOptions o;
            o.shading = sss::VolumeShading::Scattering;
            o.anisotropy = kG;
            o.model = physical ? sss::VolumeModel::Physical : sss::VolumeModel::Paper;
            const TimedImage timed = renderVolumeTimed(scene.volume, scene.tf, light, o, camera, width, height, false);
            const sss::Image& gpu = timed.image;
            const double eSingle = sss::computeErrorMetrics(gpu, single.image).relRmse;
            const double eMultiple = sss::computeErrorMetrics(gpu, multiple.image).relRmse;
            const double eSingleScaled = sss::computeErrorMetrics(scaled(gpu, bestScale(gpu, single.image)), single.image).relRmse;
            const double eMultipleScaled =
                sss::computeErrorMetrics(scaled(gpu, bestScale(gpu, multiple.image)), multiple.image).relRmse;
            const glm::dvec3 ratio = meanRatio(gpu, multiple.image);
            const std::string method = physical ? "physical-single" : "paper-light-volume";
            report.json.push_back({{"scene", scene.name},
                                   {"method", method},
                                   {"rel_rmse_single", eSingle},
                                   {"rel_rmse_single_scaled", eSingleScaled},
                                   {"rel_rmse_multiple", eMultiple},
                                   {"rel_rmse_multiple_scaled", eMultipleScaled},
                                   {"mean_ratio", {ratio.x, ratio.y, ratio.z}},
                                   {"ms", timed.medianMs},
                                   {"width", width},
                                   {"height", height},
                                   {"truth_paths_per_pixel", spp},
                                   {"truth_noise_single", single.relativeRmseEstimate},
                                   {"truth_noise_multiple", multiple.relativeRmseEstimate}});
            md << "| " << scene.name << " | " << method << " | " << fixed(100.0 * eSingle, 1) << " % | "
               << fixed(100.0 * eSingleScaled, 1) << " % | " << fixed(100.0 * eMultiple, 1) << " % | "
               << fixed(100.0 * eMultipleScaled, 1) << " % | " << fixed(ratio.x, 3) << " / " << fixed(ratio.y, 3)
               << " / " << fixed(ratio.z, 3) << " | " << fixed(timed.medianMs, 1) << " |\n";
            series[m].points.push_back({double(index), 100.0 * (physical ? eSingle : eSingleScaled)});
            if (!options.imageDir.empty())
                sss::toDisplay(gpu, {}).savePng(options.imageDir / ("accuracy-volume-" + scene.name + "-" + method + ".png"));
        }
        for (const int resolution : {64, 128}) {
            sss::VolumeRenderOptions o;
            o.shading = sss::VolumeShading::Scattering;
            o.model = sss::VolumeModel::Physical;
            o.multipleScatteringCache = true;
            o.anisotropy = kG;
            o.cacheResolution = resolution;
            if (options.quick) o.cachePhotons = o.cachePhotonsPerFrame;
            const CacheRun run = runScatteringCache(scene.volume, scene.tf, light, o, camera, width, height, multiple.image);
            auto orNull = [](double v) { return v < 0.0 ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(v); };
            const double eCorrected = std::sqrt(std::max(0.0, run.refinedError * run.refinedError -
                                                                  multiple.relativeRmseEstimate * multiple.relativeRmseEstimate));
            const std::string method = "multiple-scattering-cache";
            report.json.push_back({{"scene", scene.name},
                                   {"method", method},
                                   {"cache_resolution", resolution},
                                   {"photons", run.photons},
                                   {"photons_per_frame", o.cachePhotonsPerFrame},
                                   {"rel_rmse_single", sss::computeErrorMetrics(run.image, single.image).relRmse},
                                   {"rel_rmse_multiple", run.refinedError},
                                   {"rel_rmse_multiple_without_truth_noise", eCorrected},
                                   {"rel_rmse_multiple_first_frame", run.firstFrameError},
                                   {"mean_ratio", {run.ratio.x, run.ratio.y, run.ratio.z}},
                                   {"ms", run.fixedMs},
                                   {"fixed_ms", run.fixedMs},
                                   {"ea_ms", run.eaMs},
                                   {"rebuild_ms", run.rebuildMs},
                                   {"ms_to_10_percent", orNull(run.msTo10)},
                                   {"ms_to_5_percent", orNull(run.msTo5)},
                                   {"ms_total", run.totalMs},
                                   {"width", width},
                                   {"height", height},
                                   {"truth_paths_per_pixel", spp},
                                   {"truth_noise_multiple", multiple.relativeRmseEstimate}});
            auto when = [](double ms) { return ms < 0.0 ? std::string("not reached") : fixed(ms / 1000.0, 2) + " s"; };
            cacheMd << "| " << scene.name << " | " << resolution << " | " << run.photons << " | "
                    << fixed(100.0 * run.firstFrameError, 1) << " % | " << fixed(100.0 * run.refinedError, 1) << " % ("
                    << fixed(100.0 * eCorrected, 1) << " %) | " << fixed(run.ratio.x, 3) << " / " << fixed(run.ratio.y, 3)
                    << " / " << fixed(run.ratio.z, 3) << " | " << fixed(run.rebuildMs, 0) << " | " << when(run.msTo10)
                    << " | " << when(run.msTo5) << " | " << fixed(run.fixedMs, 1) << " | " << fixed(run.eaMs, 1) << " | "
                    << fixed(run.fixedMs / run.eaMs, 2) << " | " << fixed(run.rebuildMs / run.eaMs, 1) << " |\n";
            if (!options.imageDir.empty())
                sss::toDisplay(run.image, {}).savePng(options.imageDir / ("accuracy-volume-" + scene.name + "-" + method +
                                                                          "-" + std::to_string(resolution) + ".png"));
        }
        {
            // The progressive GPU path tracer (VolumeRenderOptions::multipleScattering): frames
            // of kPathsPerFrame paths per pixel until the truth's path count or the time budget;
            // the clock runs over the frames only (each waits for the GPU), not the read-backs
            // that measure the error after each.
            constexpr int kPathsPerFrame = 8;
            // The engine's long paths in a bright, dense medium need about 1100 paths per pixel
            // for 5 % (3 minutes on a busy llvmpipe, results/accuracy-volume-engine-path-trace-
            // llvmpipe.md): it gets a larger budget than the others.
            const bool longPaths = scene.name == "engine";
            const double budgetMs = options.quick ? 5e3 : longPaths ? 480e3 : 120e3;
            sss::VolumeRenderOptions o;
            o.shading = sss::VolumeShading::Scattering;
            o.model = sss::VolumeModel::Physical;
            o.multipleScattering = true;
            o.anisotropy = kG;
            o.samplesPerFrame = kPathsPerFrame;
            sss::VolumeScatteringRenderer renderer(o);
            renderer.setVolume(scene.volume);
            renderer.setTransferFunction(scene.tf);
            renderer.setLights({light});
            sss::RenderTarget target(width, height);
            double elapsedMs = 0.0, msTo10 = -1.0, msTo5 = -1.0;
            int pathsTo10 = -1, pathsTo5 = -1;
            std::vector<double> frameMs;
            sss::Image gpu(width, height);
            double eMultiple = 0.0;
            while (renderer.accumulatedSamples() < spp && elapsedMs < budgetMs) {
                target.clear({0, 0, 0, 0});
                const auto t0 = std::chrono::steady_clock::now();
                renderer.render(camera, target);
                sss::finishGpuWork();
                const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
                // The first frame compiles the program and builds the majorants: not a frame's cost.
                if (renderer.accumulatedSamples() > kPathsPerFrame) frameMs.push_back(ms);
                elapsedMs += ms;
                gpu = target.readColor();
                eMultiple = sss::computeErrorMetrics(gpu, multiple.image).relRmse;
                if (msTo10 < 0.0 && eMultiple <= 0.10) msTo10 = elapsedMs, pathsTo10 = renderer.accumulatedSamples();
                if (msTo5 < 0.0 && eMultiple <= 0.05) msTo5 = elapsedMs, pathsTo5 = renderer.accumulatedSamples();
            }
            std::sort(frameMs.begin(), frameMs.end());
            const double medianMs = frameMs.empty() ? elapsedMs : frameMs[frameMs.size() / 2];
            const double eSingle = sss::computeErrorMetrics(gpu, single.image).relRmse;
            const glm::dvec3 ratio = meanRatio(gpu, multiple.image);
            // The truth's own noise is part of the measured error; this is the GPU image's share.
            const double eCorrected = std::sqrt(std::max(0.0, eMultiple * eMultiple -
                                                                  multiple.relativeRmseEstimate * multiple.relativeRmseEstimate));
            const std::string method = "gpu-path-traced";
            auto orNull = [](double v) { return v < 0.0 ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(v); };
            report.json.push_back({{"scene", scene.name},
                                   {"method", method},
                                   {"rel_rmse_single", eSingle},
                                   {"rel_rmse_multiple", eMultiple},
                                   {"rel_rmse_multiple_without_truth_noise", eCorrected},
                                   {"mean_ratio", {ratio.x, ratio.y, ratio.z}},
                                   {"ms", medianMs},
                                   {"paths_per_frame", kPathsPerFrame},
                                   {"paths_per_pixel", renderer.accumulatedSamples()},
                                   {"budget_ms", budgetMs},
                                   {"ms_total", elapsedMs},
                                   {"ms_to_10_percent", orNull(msTo10)},
                                   {"paths_to_10_percent", pathsTo10},
                                   {"ms_to_5_percent", orNull(msTo5)},
                                   {"paths_to_5_percent", pathsTo5},
                                   {"width", width},
                                   {"height", height},
                                   {"truth_paths_per_pixel", spp},
                                   {"truth_noise_single", single.relativeRmseEstimate},
                                   {"truth_noise_multiple", multiple.relativeRmseEstimate}});
            auto when = [](double ms, int paths) {
                return ms < 0.0 ? std::string("not reached") : fixed(ms / 1000.0, 1) + " s (" + std::to_string(paths) + " paths)";
            };
            gpuMd << "| " << scene.name << " | " << renderer.accumulatedSamples()
                  << (longPaths && !options.quick ? " (budget " + fixed(budgetMs / 1000.0, 0) + " s)" : std::string())
                  << " | " << fixed(100.0 * eMultiple, 1)
                  << " % | " << fixed(100.0 * eCorrected, 1) << " % | " << fixed(ratio.x, 3) << " / " << fixed(ratio.y, 3)
                  << " / " << fixed(ratio.z, 3) << " | " << when(msTo10, pathsTo10) << " | " << when(msTo5, pathsTo5)
                  << " | " << fixed(medianMs, 1) << " |\n";
            series[2].points.push_back({double(index), 100.0 * eMultiple});
            if (!options.imageDir.empty())
                sss::toDisplay(gpu, {}).savePng(options.imageDir / ("accuracy-volume-" + scene.name + "-" + method + ".png"));
        }
    }
    md << truthMd.str();
    md << cacheMd.str();
    md << gpuMd.str();
    md << "\nScenes in the plot, left to right: ";
    for (size_t i = 0; i < scenes.size(); ++i) md << (i ? ", " : "") << i + 1 << " = " << scenes[i].name;
    md << ".\n";
    report.markdown = md.str();
    report.plot.title = "volume images: relRMSE against path-traced single (light volume) and multiple scattering (GPU path tracer)";
    report.plot.xLabel = "scene (see the Markdown)";
    report.plot.yLabel = "relRMSE %";
    report.plot.series = {series[0], series[1], series[2]};
    return report;
}

// The light volume against its own model, evaluated exactly: the GPU image of each volume model
// (paper: ambient 0, diffuse 1, so only the light volume's light shows; physical: single
// scattering) against the CPU reference of the same model (sss/volume_reference.h: shadow rays
// at quarter-voxel steps instead of the light volume). Three GPU settings: the defaults (step
// 0.5, pre-integrated, jitter, early termination 0.99), the thesis's ray casting (step 1,
// post-classification) and an exact ray (step 0.25, no jitter), which leaves the light volume as
// the only difference.
AccuracyReport runLightVolumeAccuracy(BenchmarkContext& bench, const AccuracyOptions& options) {
    constexpr int kConeWalks = 32;  // noise ~0.4 % of the image (bonsai: 0.5 % at 16 walks)
    AccuracyReport report;
    report.json = nlohmann::ordered_json::array();
    const int width = options.quick ? 32 : (options.width == 96 ? 160 : options.width);
    const int height = options.quick ? 18 : (options.height == 72 ? 90 : options.height);
    constexpr float kG = 0.5f;
    struct Scene {
        std::string name;
        sss::Volume volume;
        sss::TransferFunction tf;
    };
    std::vector<Scene> scenes;
    for (const std::string model : {"bucky", "bonsai", "engine"}) {
        if (options.quick && model != "bucky") continue;
        if (!bench.wanted(model)) continue;
        auto loaded = loadThesisVolume(bench, "accuracy-light-volume", options.quick ? "blobs" : model);
        if (!loaded) continue;
        scenes.push_back({options.quick ? "blobs" : model, std::move(loaded->first), sss::TransferFunction::preset(loaded->second)});
    }
    std::ostringstream md;
    md << "# The light volume against its own model, evaluated with shadow rays\n\n"
       << width << " x " << height << ", one directional light, g = " << kG << ", " << options.renderer
       << ". Reference: the CPU reference of the same model (view step 0.25 voxel, shadow rays at 0.25 voxel). "
          "Paper model with ambient 0 and diffuse 1; its reference gathers the chromaticity c over the light "
          "volume's cone (VolumeReferenceOptions::chromaticityConeScale = 1, "
       << (options.quick ? 8 : kConeWalks)
       << " random walks per sample); the last column compares with c along the straight shadow ray "
          "instead. 'default': GPU defaults (step 0.5, pre-integrated "
          "classification, jitter, early termination 0.99); 'thesis': the thesis's ray casting (step 1, "
          "post-classification, jitter); 'exact ray': step 0.25, post-classification, no jitter, no early "
          "termination; 'LV s, step t' (physical model only): the defaults with the light volume at scale s "
          "and the ray step t voxels. ms: "
          "one light change (light volume and ray cast), median of 3.\n\n"
       << "| scene | model | GPU settings | relRMSE | mean ratio R / G / B | ms | relRMSE, straight c |\n"
          "|---|---|---|---:|---|---:|---:|\n";
    // The plot: the physical model's time against error, one series per scene and ray step over
    // the light-volume scales (the paper model's reference follows the scale, so it is left out).
    struct FrontPoint {
        float scale;
        double ms, errorPercent;
    };
    std::map<std::pair<std::string, float>, std::vector<FrontPoint>> front;  // (scene, step) -> points
    for (const Scene& scene : scenes) {
        const sss::Camera camera = volumeAccuracyCamera(scene.volume, width, height);
        const sss::DirectionalLight light = volumeAccuracyLight();
        for (const sss::VolumeModel model : {sss::VolumeModel::Paper, sss::VolumeModel::Physical}) {
            const bool physical = model == sss::VolumeModel::Physical;
            const std::string modelName = physical ? "physical" : "paper";
            // The paper model's reference gathers c over the light volume's cone, as the GPU does;
            // the straight-c reference (the cone's thin-slice limit) is kept beside it for comparison.
            const sss::VolumeRenderOptions gpuDefaults;
            const int coneWalks = options.quick ? 8 : kConeWalks;
            auto referenceImage = [&](bool cone) {
                const std::string coneName = cone ? "-cone" + std::to_string(coneWalks) : "";
                return cachedReference(bench.options(),
                                       "light-volume-reference-" + scene.name + "-" + modelName + coneName + "-" +
                                           std::to_string(width) + "x" + std::to_string(height) + "-" +
                                           viewAndLightTag(camera, light) + ".exr",
                                       [&] {
                                           sss::VolumeReferenceOptions ro;
                                           ro.shading = sss::ReferenceShading::Scattering;
                                           ro.model = model;
                                           ro.anisotropy = kG;
                                           ro.ambient = 0.0;
                                           ro.diffuse = 1.0;
                                           ro.stepVoxels = 0.25;
                                           ro.shadowStepVoxels = 0.25;
                                           ro.background = glm::dvec4(0.0);
                                           if (cone) {
                                               ro.chromaticityConeScale = gpuDefaults.lightVolumeScale;
                                               ro.chromaticityWalks = coneWalks;
                                           }
                                           return sss::renderVolumeReference(scene.volume, scene.tf, 256, glm::mat4(1.0f),
                                                                             {light}, camera, width, height, ro);
                                       });
            };
            const sss::Image reference = referenceImage(!physical);
            const std::optional<sss::Image> straightReference =
                physical ? std::nullopt : std::optional<sss::Image>(referenceImage(false));
            // Besides the defaults, the thesis's ray casting and an exact ray: for the physical model,
            // the defaults at other light-volume scales and ray steps, the time-against-error front on
            // real data (the paper model's cone, and so its reference, follows the scale).
            struct Settings {
                std::string name;
                float lightVolumeScale = 1.0f;
                float step = 0.5f;
            };
            std::vector<Settings> settingsList = {{"default"}, {"thesis"}, {"exact ray"}};
            if (physical && !options.quick)
                for (float scale : {1.0f, 0.5f, 0.25f})
                    for (float step : {1.0f, 0.5f, 0.25f})
                        if (scale != 1.0f || step != 0.5f)
                            settingsList.push_back({"LV " + fixed(scale, 2) + ", step " + fixed(step, 2), scale, step});
            for (const Settings& setting : settingsList) {
                const std::string& settings = setting.name;
                const bool exactRay = settings == "exact ray";
                const bool scaled = settings.rfind("LV ", 0) == 0;
                sss::VolumeRenderOptions o =
                    settings == "thesis" ? thesisVolumeOptions(bench.options(), sss::VolumeShading::Scattering) : sss::VolumeRenderOptions{};
                o.shading = sss::VolumeShading::Scattering;
                o.model = model;
                o.lightPropagation = bench.options().lightPropagation;
                o.anisotropy = kG;
                o.ambient = 0.0f;
                o.diffuse = 1.0f;
                if (scaled) {
                    o.lightVolumeScale = setting.lightVolumeScale;
                    o.stepSize = setting.step;
                }
                if (exactRay) {
                    o.stepSize = 0.25f;
                    o.preintegration = false;
                    o.jitter = false;
                    o.earlyTermination = 1.0f;
                }
                const TimedImage timed = renderVolumeTimed(scene.volume, scene.tf, light, o, camera, width, height, true);
                const sss::Image& gpu = timed.image;
                const double e = sss::computeErrorMetrics(gpu, reference).relRmse;
                const double eStraight =
                    straightReference ? sss::computeErrorMetrics(gpu, *straightReference).relRmse : e;
                const glm::dvec3 ratio = meanRatio(gpu, reference);
                std::cerr << "sss-bench: light volume " << scene.name << " " << modelName << " " << settings
                          << ": relRMSE " << e << " (straight c: " << eStraight << ")\n";
                report.json.push_back({{"scene", scene.name},
                                       {"method", physical ? "physical-single" : "paper-light-volume"},
                                       {"model", modelName},
                                       {"settings", settings},
                                       {"light_volume_scale", o.lightVolumeScale},
                                       {"step_voxels", o.stepSize},
                                       {"rel_rmse", e},
                                       {"rel_rmse_straight_c", eStraight},
                                       {"mean_ratio", {ratio.x, ratio.y, ratio.z}},
                                       {"ms", timed.medianMs},
                                       {"width", width},
                                       {"height", height}});
                md << "| " << scene.name << " | " << modelName << " | " << settings << " | " << fixed(100.0 * e, 1)
                   << " % | " << fixed(ratio.x, 3) << " / " << fixed(ratio.y, 3) << " / " << fixed(ratio.z, 3) << " | "
                   << fixed(timed.medianMs, 1) << " | "
                   << (physical ? std::string("-") : fixed(100.0 * eStraight, 1) + " %") << " |\n";
                if (physical && (settings == "default" || scaled))
                    front[{scene.name, o.stepSize}].push_back({o.lightVolumeScale, timed.medianMs, 100.0 * e});
                if (!options.imageDir.empty()) {
                    std::filesystem::create_directories(options.imageDir);
                    sss::toDisplay(gpu, {}).savePng(options.imageDir / ("light-volume-" + scene.name + "-" + modelName + "-" +
                                                                        (exactRay ? "exact"
                                                                                  : scaled ? "lv" + fixed(setting.lightVolumeScale, 2) +
                                                                                                 "-step" + fixed(setting.step, 2)
                                                                                           : settings) +
                                                                        ".png"));
                    if (exactRay)
                        sss::toDisplay(reference, {}).savePng(options.imageDir /
                                                              ("light-volume-" + scene.name + "-" + modelName + "-reference.png"));
                }
            }
        }
    }
    md << "\nPlot: the physical model's relRMSE against the time of a light change, one line per scene and "
          "ray step through the light-volume scales 0.25, 0.5 and 1 (right: finer).\n";
    report.markdown = md.str();
    report.plot.title = "physical light volume: time per light change against error (CPU reference)";
    report.plot.xLabel = "light change: light volume + ray cast (ms)";
    report.plot.yLabel = "relRMSE %";
    // One hue per scene, lighter for the coarser and darker for the finer step.
    const unsigned colours[][3] = {{0x9ecae1, 0x1f77b4, 0x08306b}, {0xfdae6b, 0xff7f0e, 0x7f2704}, {0xa1d99b, 0x2ca02c, 0x00441b}};
    for (size_t sceneIndex = 0; sceneIndex < scenes.size(); ++sceneIndex) {
        const float steps[] = {1.0f, 0.5f, 0.25f};
        for (int k = 0; k < 3; ++k) {
            auto it = front.find({scenes[sceneIndex].name, steps[k]});
            if (it == front.end()) continue;
            std::vector<FrontPoint> points = it->second;
            std::sort(points.begin(), points.end(), [](const FrontPoint& a, const FrontPoint& b) { return a.scale < b.scale; });
            PlotSeries series{scenes[sceneIndex].name + ", step " + fixed(steps[k], 2), {}, colours[sceneIndex % 3][k]};
            for (const FrontPoint& p : points) series.points.push_back({p.ms, p.errorPercent});
            report.plot.series.push_back(std::move(series));
        }
    }
    return report;
}
