// sss-bench --accuracy surfaces: opaque surfaces under a side light (docs/opaque-surfaces.md).
// The 64^3 shell (ct-bone), the same shell sampled at 128^3 and the bonsai, lit along
// (1, -0.4, -0.2), rendered on the GPU in both volume models (defaults, and reach 8) and measured
// against path-traced single scattering of the same data:
//  - rel_rmse: the physical model as it is, the paper model (ambient 0, diffuse 1) after its best
//    single factor; truth_noise: the truth's own expected relRMSE;
//  - ring_contrast: how much fine structure the lit surface carries, the RMS of the image minus
//    its Gaussian blur (sigma 1.5 pixels) over the mean, on the lit inside of the silhouette. It
//    is the rings' measure; the truth's own value says how much of it the data itself holds.
// The "cubic" rows (not for the 128^3 shell) take the cubic B-spline field on the GPU and in the truth.
#include "accuracy.h"
#include "bench.h"
#include "volume_accuracy.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>

using namespace volume_accuracy;

namespace {

double luminance(const glm::vec4& p) { return 0.2126 * p.r + 0.7152 * p.g + 0.0722 * p.b; }

// Separable Gaussian blur of the luminance, clamped at the edges.
std::vector<double> blurredLuminance(const sss::Image& image, double sigma) {
    const int w = image.width(), h = image.height(), radius = int(std::ceil(3.0 * sigma));
    std::vector<double> kernel(2 * radius + 1);
    double sum = 0.0;
    for (int k = -radius; k <= radius; ++k) sum += kernel[k + radius] = std::exp(-0.5 * k * k / (sigma * sigma));
    for (double& k : kernel) k /= sum;
    std::vector<double> lum(size_t(w) * h), rows(size_t(w) * h, 0.0), out(size_t(w) * h, 0.0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) lum[size_t(y) * w + x] = luminance(image.at(x, y));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int k = -radius; k <= radius; ++k)
                rows[size_t(y) * w + x] += kernel[k + radius] * lum[size_t(y) * w + std::clamp(x + k, 0, w - 1)];
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int k = -radius; k <= radius; ++k)
                out[size_t(y) * w + x] += kernel[k + radius] * rows[size_t(std::clamp(y + k, 0, h - 1)) * w + x];
    return out;
}

// The pixels the ring measure looks at: inside the truth's silhouette (full coverage over a
// 7 x 7 neighbourhood, so edges do not count as structure) and lit (luminance above a tenth of
// the lit pixels' 99th percentile).
std::vector<bool> litInterior(const sss::Image& truth) {
    const int w = truth.width(), h = truth.height();
    std::vector<double> lit;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (luminance(truth.at(x, y)) > 0.0) lit.push_back(luminance(truth.at(x, y)));
    std::vector<bool> mask(size_t(w) * h, false);
    if (lit.empty()) return mask;
    std::nth_element(lit.begin(), lit.begin() + lit.size() * 99 / 100, lit.end());
    const double threshold = 0.1 * lit[lit.size() * 99 / 100];
    for (int y = 3; y < h - 3; ++y)
        for (int x = 3; x < w - 3; ++x) {
            bool covered = true;
            for (int dy = -3; dy <= 3 && covered; ++dy)
                for (int dx = -3; dx <= 3 && covered; ++dx) covered = truth.at(x + dx, y + dy).a >= 0.99f;
            mask[size_t(y) * w + x] = covered && luminance(truth.at(x, y)) > threshold;
        }
    return mask;
}

double ringContrast(const sss::Image& image, const std::vector<bool>& mask) {
    const std::vector<double> blurred = blurredLuminance(image, 1.5);
    double residual = 0.0, mean = 0.0;
    int n = 0;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            const size_t i = size_t(y) * image.width() + x;
            if (!mask[i]) continue;
            const double l = luminance(image.at(x, y));
            residual += (l - blurred[i]) * (l - blurred[i]);
            mean += l;
            ++n;
        }
    return n > 0 && mean > 0.0 ? std::sqrt(residual / n) / (mean / n) : 0.0;
}

// makeShellVolume(64)'s object (outer radius 0.42, thickness 0.08, edges 1/64 of the side wide)
// sampled at 128^3: its edges span four voxels instead of two, so trilinear interpolation
// reconstructs them without the 64^3 shell's terraces. What the shell looks like when the data
// resolves it.
sss::Volume shellSampledAt128() {
    constexpr int n = 128;
    constexpr double outer = 0.42, inner = 0.34, edge = 1.0 / 64.0;
    auto smoothstep = [](double lo, double hi, double x) {
        const double t = std::clamp((x - lo) / (hi - lo), 0.0, 1.0);
        return t * t * (3.0 - 2.0 * t);
    };
    std::vector<uint8_t> bytes(size_t(n) * n * n);
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const double d = glm::length(glm::dvec3(x + 0.5, y + 0.5, z + 0.5) / double(n) - glm::dvec3(0.5));
                const double v = smoothstep(inner - edge, inner + edge, d) * (1.0 - smoothstep(outer - edge, outer + edge, d));
                bytes[(size_t(z) * n + y) * n + x] = uint8_t(std::lround(v * 255.0));
            }
    return sss::Volume::fromData({n, n, n}, sss::VoxelType::UInt8, std::move(bytes));
}

struct Scene {
    std::string name;
    sss::Volume volume;
    sss::TransferFunction tf;
};

std::vector<Scene> surfaceScenes(BenchmarkContext& bench, bool quick) {
    std::vector<Scene> scenes;
    if (bench.wanted("shell"))
        scenes.push_back({"shell", sss::makeShellVolume(quick ? 32 : 64), sss::TransferFunction::preset("ct-bone")});
    if (!quick && bench.wanted("shell-128"))
        scenes.push_back({"shell-128", shellSampledAt128(), sss::TransferFunction::preset("ct-bone")});
    if (!quick && bench.wanted("bonsai"))
        if (auto loaded = loadThesisVolume(bench, "accuracy-surfaces", "bonsai"))
            scenes.push_back({"bonsai", std::move(loaded->first), sss::TransferFunction::preset(loaded->second)});
    return scenes;
}

struct Settings {
    std::string name;
    sss::VolumeRenderOptions options;
};

std::vector<Settings> surfaceSettings() {
    std::vector<Settings> settings;
    settings.push_back({"default", {}});
    sss::VolumeRenderOptions reach8;
    reach8.lightVolumeReach = 8.0f;  // more of the light carried exactly, past the light volume
    settings.push_back({"reach 8", reach8});
    sss::VolumeRenderOptions cubic;
    cubic.reconstruction = sss::VolumeReconstruction::CubicBSpline;  // against a truth of the same field
    settings.push_back({"cubic", cubic});
    return settings;
}

// What a table row is measured against: path-traced single scattering of the scene, cached.
struct SurfaceTruth {
    sss::Image image{1, 1};
    double noise = 0.0;           // its own expected relRMSE
    std::vector<bool> litMask;    // where the ring contrast is measured
    double ringContrast = 0.0;
};

struct SurfaceView {
    sss::Camera camera;
    sss::DirectionalLight light;
    int width, height, paths;
    float g;
};

SurfaceTruth surfaceTruth(BenchmarkContext& bench, const Scene& scene, const SurfaceView& view,
                          sss::VolumeReconstruction reconstruction) {
    sss::VolumePathTracerOptions po;
    po.samplesPerPixel = view.paths;
    po.g = view.g;
    po.mode = sss::VolumeScatteringMode::SingleScattering;
    po.reconstruction = reconstruction;
    const bool cubic = reconstruction == sss::VolumeReconstruction::CubicBSpline;
    const std::string name = "surfaces-truth-" + scene.name + "-" + std::to_string(view.width) + "x" +
                             std::to_string(view.height) + "-" + std::to_string(view.paths) + (cubic ? "-cubic" : "");
    const volume_accuracy::PathTracedTruth traced = volume_accuracy::cachedPathTraced(
        bench, name, scene.volume, scene.tf, view.light, view.camera, view.width, view.height, po);
    SurfaceTruth truth;
    truth.image = traced.image;
    truth.noise = traced.relativeRmseEstimate;
    truth.litMask = litInterior(truth.image);
    truth.ringContrast = ringContrast(truth.image, truth.litMask);
    return truth;
}

struct SurfaceRecord {
    double error, rings, ms;
    sss::Image image{1, 1};
};

// One GPU render at `settings` in `model` against the truth.
SurfaceRecord measureSurface(const Scene& scene, const SurfaceView& view, const SurfaceTruth& truth,
                             sss::VolumeRenderOptions options, sss::VolumeModel model) {
    const bool physical = model == sss::VolumeModel::Physical;
    options.shading = sss::VolumeShading::Scattering;
    options.anisotropy = view.g;
    options.model = model;
    if (!physical) {  // the paper model's light alone, as its reference takes it
        options.ambient = 0.0f;
        options.diffuse = 1.0f;
    }
    const TimedImage timed =
        renderVolumeTimed(scene.volume, scene.tf, view.light, options, view.camera, view.width, view.height, false);
    sss::Image gpu = physical ? timed.image : scaled(timed.image, bestScale(timed.image, truth.image));
    const double error = sss::computeErrorMetrics(gpu, truth.image).relRmse;
    const double rings = ringContrast(gpu, truth.litMask);
    return {error, rings, timed.medianMs, std::move(gpu)};
}

}  // namespace

AccuracyReport runSurfaceAccuracy(BenchmarkContext& bench, const AccuracyOptions& options) {
    AccuracyReport report;
    report.json = nlohmann::ordered_json::array();
    const int width = options.quick ? 64 : (options.width == 96 ? 256 : options.width);
    const int height = options.quick ? 36 : (options.height == 72 ? 144 : options.height);
    SurfaceView view{{}, {.direction = glm::normalize(glm::vec3(1.0f, -0.4f, -0.2f))}, width, height,
                     options.quick ? 16 : 4 * options.pathsPerPixel, 0.5f};
    std::ostringstream md;
    md << "# Opaque surfaces under a side light: both volume models against path-traced single scattering\n\n"
       << width << " x " << height << ", one directional light travelling along (1, -0.4, -0.2), g = " << view.g << ", "
       << options.renderer << ". Truth: renderVolumePathTraced, single scattering, " << view.paths
       << " paths per pixel. relRMSE over all pixels: the physical model as it is, the paper model after its best "
          "single factor. Ring contrast: RMS of the luminance minus its Gaussian blur (sigma 1.5 pixels) over "
          "the mean luminance, on the lit inside of the truth's silhouette; the truth's own value is what the "
          "data holds (and its noise).\n\n"
       << "| scene | model | GPU settings | relRMSE | without truth noise | ring contrast | truth's ring contrast | ms |\n"
       << "|---|---|---|---:|---:|---:|---:|---:|\n";
    PlotSeries series[2] = {{"paper (scaled)", {}, 0xd62728, false}, {"physical", {}, 0x1f77b4, false}};
    if (!options.imageDir.empty()) std::filesystem::create_directories(options.imageDir);
    for (const Scene& scene : surfaceScenes(bench, options.quick)) {
        view.camera = volumeAccuracyCamera(scene.volume, width, height);
        std::map<sss::VolumeReconstruction, SurfaceTruth> truths;
        for (const Settings& s : surfaceSettings())
            for (const sss::VolumeModel model : {sss::VolumeModel::Paper, sss::VolumeModel::Physical}) {
                const sss::VolumeReconstruction field = s.options.reconstruction;
                const bool cubic = field == sss::VolumeReconstruction::CubicBSpline;
                // The cubic truth's CPU field reads 64 voxels a lookup (3.5x the trilinear truth's
                // time): not for the 128^3 shell, which stands for the same object.
                if (cubic && scene.name == "shell-128") continue;
                if (!truths.count(field)) {
                    truths.emplace(field, surfaceTruth(bench, scene, view, field));
                    if (!options.imageDir.empty())
                        truths.at(field).image.saveExr(options.imageDir / ("surfaces-" + scene.name + "-truth" +
                                                                           (cubic ? "-cubic" : "") + ".exr"));
                }
                const SurfaceTruth& truth = truths.at(field);
                const SurfaceRecord r = measureSurface(scene, view, truth, s.options, model);
                const bool physical = model == sss::VolumeModel::Physical;
                const std::string modelName = physical ? "physical" : "paper";
                report.json.push_back({{"scene", scene.name},
                                       {"model", modelName},
                                       {"settings", s.name},
                                       {"rel_rmse", r.error},
                                       {"truth_noise", truth.noise},
                                       {"ring_contrast", r.rings},
                                       {"truth_ring_contrast", truth.ringContrast},
                                       {"ms", r.ms}});
                const double withoutNoise = std::sqrt(std::max(0.0, r.error * r.error - truth.noise * truth.noise));
                md << "| " << scene.name << " | " << modelName << " | " << s.name << " | " << fixed(100.0 * r.error, 1)
                   << " % | " << fixed(100.0 * withoutNoise, 1) << " % | " << fixed(100.0 * r.rings, 2) << " % | "
                   << fixed(100.0 * truth.ringContrast, 2) << " % | " << fixed(r.ms, 1) << " |\n";
                if (s.name == "default") series[physical ? 1 : 0].points.push_back({double(report.json.size()), 100.0 * r.error});
                if (!options.imageDir.empty())
                    r.image.saveExr(options.imageDir / ("surfaces-" + scene.name + "-" + modelName + "-" + s.name + ".exr"));
            }
    }
    report.markdown = md.str();
    report.plot.title = "opaque surfaces: relRMSE against path-traced single scattering";
    report.plot.xLabel = "record";
    report.plot.yLabel = "relRMSE %";
    report.plot.series = {series[0], series[1]};
    return report;
}
