// The multiple-scattering cache (VolumeRenderOptions::multipleScatteringCache): single scattering
// from the light volume plus the cached light scattered more than once converges towards the
// CPU path tracer's full transport; within a cell, the light scattered once follows the direct
// light; an albedo-1 cube sends out the power it takes from the beam;
// a black medium or one bounce adds nothing; camera moves rebuild nothing; the sums do not
// depend on how photons are split into frames. Small images and volumes: llvmpipe.
#include "support/gl_test.h"
#include "support/scenes.h"

#include "gl/device.h"
#include "volume/fluence_cache.h"

#include <catch2/catch.hpp>
#include <sss/error.h>
#include <sss/image_compare.h>
#include <sss/log.h>
#include <sss/option_names.h>
#include <sss/procedural.h>
#include <sss/volume_path_tracer.h>
#include <sss/volume_scattering_renderer.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

using namespace sss;
using sss::test::channelSums;
using sss::test::meanRatio;
using sss::test::orbitCamera;

namespace {

constexpr int kWidth = 48, kHeight = 32;
constexpr float kAnisotropy = 0.5f;

// The GPU path tracer's test scene (test_volume_path_trace.cpp): 24^3 blobs, bright and of high
// albedo, where multiple scattering carries 2.6 times the single-scattered light.
const Volume& blobs() {
    static const Volume volume = makeBlobsVolume(24);
    return volume;
}
TransferFunction blobsTf(glm::vec3 albedo = {0.95f, 0.85f, 0.7f}) {
    return sss::test::highAlbedoBlobsTransferFunction(albedo);
}
const std::vector<Light> kLights{DirectionalLight{.direction = {-1.0f, -0.7f, -0.4f}, .intensity = 10.0f}};
Camera blobsCamera(float yaw = 30.0f) { return orbitCamera(blobs().worldBounds(), yaw, 20.0f); }

VolumeRenderOptions cached(int photons, int resolution = 64) {
    VolumeRenderOptions o;
    o.shading = VolumeShading::Scattering;
    o.model = VolumeModel::Physical;
    o.anisotropy = kAnisotropy;
    o.multipleScatteringCache = true;
    o.cacheResolution = resolution;
    o.cachePhotonsPerFrame = std::min(photons, 1 << 16);
    o.cachePhotons = photons;
    return o;
}

VolumePathTracerResult cpuPathTraced(const Volume& volume, const TransferFunction& tf, const Camera& camera,
                                     VolumeScatteringMode mode, int samples, double g = kAnisotropy) {
    VolumePathTracerOptions o;
    o.samplesPerPixel = samples;
    o.mode = mode;
    o.g = g;
    return renderVolumePathTraced(volume, tf, 256, glm::mat4(1.0f), kLights, camera, kWidth, kHeight, o);
}

struct Scene {
    VolumeScatteringRenderer renderer;
    RenderTarget target{kWidth, kHeight};
    Scene(const VolumeRenderOptions& options, const Volume& volume, const TransferFunction& tf) : renderer(options) {
        renderer.setVolume(volume);
        renderer.setTransferFunction(tf);
        renderer.setLights(kLights);
    }
    Image frame(const Camera& camera) {
        target.clear(glm::vec4(0.0f));
        renderer.render(camera, target);
        return target.readColor();
    }
    // Frames until the cache holds all its photons; the last frame's image.
    Image refined(const Camera& camera) {
        Image image = frame(camera);
        while (renderer.cachedPhotons() < static_cast<std::uint64_t>(renderer.options().cachePhotons))
            image = frame(camera);
        return image;
    }
};

// The bright cube (one cell per voxel at 16 cells) from the tests' orbit, and its path-traced
// full transport at g = kAnisotropy: computed once for the tests that share it.
struct BrightCubeView {
    Camera camera;
    VolumePathTracerResult truth;
};
const BrightCubeView& brightCubeView() {
    static const BrightCubeView view = [] {
        const Camera camera = orbitCamera(test::brightCube().worldBounds(), 30.0f, 20.0f);
        return BrightCubeView{camera, cpuPathTraced(test::brightCube(), test::brightCubeTransferFunction(), camera,
                                                    VolumeScatteringMode::MultipleScattering, 2048)};
    }();
    return view;
}

}  // namespace

TEST_CASE("the multiple-scattering cache converges towards the CPU path tracer's full transport",
          "[gl][volume][scattering-cache]") {
    test::GlTestScope gl;
    const Camera camera = blobsCamera();
    const VolumePathTracerResult truth =
        cpuPathTraced(blobs(), blobsTf(), camera, VolumeScatteringMode::MultipleScattering, 2048);
    const VolumePathTracerResult single =
        cpuPathTraced(blobs(), blobsTf(), camera, VolumeScatteringMode::SingleScattering, 512);
    // Multiple scattering carries more light than single scattering here.
    REQUIRE(meanRatio(truth.image, single.image) > 2.0);

    Scene scene(cached(1 << 20, 24), blobs(), blobsTf());
    const Image first = scene.frame(camera);
    REQUIRE(scene.renderer.cachedPhotons() == (1u << 16));
    const Image refined = scene.refined(camera);
    REQUIRE(scene.renderer.cachedPhotons() == (1u << 20));
    VolumeRenderOptions withoutCache = cached(1);
    withoutCache.multipleScatteringCache = false;
    Scene singleScene(withoutCache, blobs(), blobsTf());
    const double errorSingle = computeErrorMetrics(singleScene.frame(camera), truth.image).relRmse;
    const double errorFirst = computeErrorMetrics(first, truth.image).relRmse;
    const double errorRefined = computeErrorMetrics(refined, truth.image).relRmse;
    INFO("relRMSE against the full transport: single scattering " << errorSingle << ", first frame " << errorFirst
                                                                  << ", refined " << errorRefined << " (truth's noise "
                                                                  << truth.relativeRmseEstimate << ")");
    // Measured on llvmpipe: single scattering 69 %, first frame (2^16 photons) 10.9 %, refined
    // (2^20) 5.6 % with the truth's own 4.1 %, mean ratio 1.009 (with the fluence averaged without
    // the sigma weight it was 0.92, with the radiance taken as linear in direction 0.92, and
    // before the measured second band: first frame 11.8 %, refined 7.1 %, mean ratio 0.99).
    CHECK(errorSingle > 0.5);
    CHECK(errorFirst < 0.14);
    CHECK(errorRefined < 0.07);
    CHECK(errorRefined < errorFirst);
    CHECK(meanRatio(refined, truth.image) == Approx(1.0).margin(0.03));
    gl.requireNoErrors();
}

TEST_CASE("the cache's measured second angular band makes g 0.5 as accurate as g 0",
          "[gl][volume][scattering-cache]") {
    // A bright uniform cube (one cell per voxel): at g = 0 the eye reads the fluence alone, at
    // g = 0.5 also the radiance's shape. Taken as an HG lobe from the first moment alone, its
    // multiple-scattering part was 4 % dark at g = 0.5 (0.959 of the truth's, 1.017 at g = 0).
    test::GlTestScope gl;
    const Volume& cube = test::brightCube();
    const TransferFunction tf = test::brightCubeTransferFunction();
    const Camera camera = orbitCamera(cube.worldBounds(), 30.0f, 20.0f);
    double multiplePart[2] = {0.0, 0.0};
    for (int i = 0; i < 2; ++i) {
        const float g = i == 0 ? 0.0f : 0.5f;
        const VolumePathTracerResult truth = cpuPathTraced(cube, tf, camera, VolumeScatteringMode::MultipleScattering, 2048, g);
        const VolumePathTracerResult single = cpuPathTraced(cube, tf, camera, VolumeScatteringMode::SingleScattering, 2048, g);
        VolumeRenderOptions o = cached(1 << 20, 16);
        o.anisotropy = g;
        Scene scene(o, cube, tf);
        const Image image = scene.refined(camera);
        o.multipleScatteringCache = false;
        Scene singleScene(o, cube, tf);
        const Image singleImage = singleScene.frame(camera);
        multiplePart[i] = (meanRatio(image, single.image) - meanRatio(singleImage, single.image)) /
                          (meanRatio(truth.image, single.image) - 1.0);
    }
    INFO("multiple-scattering part against the truth's: g 0 " << multiplePart[0] << ", g 0.5 " << multiplePart[1]);
    // Measured on llvmpipe: 1.019 at g 0, 1.015 at g 0.5.
    CHECK(multiplePart[1] == Approx(1.0).margin(0.04));
    CHECK(std::abs(multiplePart[1] - multiplePart[0]) < 0.02);
    gl.requireNoErrors();
}

TEST_CASE("each channel's light is scattered towards the eye along that channel's own flow",
          "[gl][volume][scattering-cache]") {
    // The bucky look-alike with its own colours, whose channels' light flows differently: at
    // g = 0 the eye reads each channel's fluence alone, at g = 0.5 also the direction it flows in.
    test::GlTestScope gl;
    const Volume volume = makeBuckyLikeVolume(32);
    const TransferFunction tf = TransferFunction::preset("bucky");
    const Camera camera = orbitCamera(volume.worldBounds(), 30.0f, 20.0f);
    glm::dvec3 part[2];
    for (int i = 0; i < 2; ++i) {
        const float g = i == 0 ? 0.0f : 0.5f;
        const VolumePathTracerResult truth = cpuPathTraced(volume, tf, camera, VolumeScatteringMode::MultipleScattering, 2048, g);
        const VolumePathTracerResult single = cpuPathTraced(volume, tf, camera, VolumeScatteringMode::SingleScattering, 2048, g);
        VolumeRenderOptions o = cached(1 << 20, 32);
        o.anisotropy = g;
        Scene scene(o, volume, tf);
        const Image image = scene.refined(camera);
        o.multipleScatteringCache = false;
        Scene singleScene(o, volume, tf);
        const glm::dvec3 ours = channelSums(image) - channelSums(singleScene.frame(camera));
        part[i] = ours / (channelSums(truth.image) - channelSums(single.image));
    }
    const glm::dvec3 shift = glm::abs(part[1] - part[0]);
    INFO("multiple-scattering part per channel against the truth's: g 0 " << part[0].x << " / " << part[0].y << " / "
                                                                          << part[0].z << ", g 0.5 " << part[1].x << " / "
                                                                          << part[1].y << " / " << part[1].z);
    // Measured on llvmpipe: g 0 0.917 / 1.006 / 1.000, g 0.5 0.908 / 1.027 / 0.992, shifts summing
    // to 0.037; read along the mean channel's flux, g 0.5 gave 0.887 / 1.022 / 1.031, 0.077.
    CHECK(shift.x + shift.y + shift.z < 0.055);
    gl.requireNoErrors();
}

// A dense block of low albedo (optical depth 2.3 per voxel) lit from the viewer's side: the light
// scattered once lies within the first voxel of the lit faces, which is what the eye sees, while
// a cell holds the mean over its depth.
struct DenseBlockScene {
    static constexpr int kSide = 32;
    Volume volume = makeVolume();
    TransferFunction tf{{{0.0f, {0.8f, 0.6f, 0.4f}, 0.0f}, {0.5f, {0.8f, 0.6f, 0.4f}, 0.0f},
                         {0.51f, {0.8f, 0.6f, 0.4f}, 0.9f}, {1.0f, {0.8f, 0.6f, 0.4f}, 0.9f}}};
    Camera camera = orbitCamera(volume.worldBounds(), 30.0f, 20.0f);

    static Volume makeVolume() {
        std::vector<uint8_t> data(kSide * kSide * kSide, 0);
        for (int z = 6; z < 26; ++z)
            for (int y = 6; y < 26; ++y)
                for (int x = 6; x < 26; ++x) data[(z * kSide + y) * kSide + x] = 255;
        return Volume::fromData({kSide, kSide, kSide}, VoxelType::UInt8, std::move(data));
    }
};

// The same with its path-traced truth.
struct DenseBlock : DenseBlockScene {
    VolumePathTracerResult truth = cpuPathTraced(volume, tf, camera, VolumeScatteringMode::MultipleScattering, 1024);
    VolumePathTracerResult single = cpuPathTraced(volume, tf, camera, VolumeScatteringMode::SingleScattering, 1024);
    // The multiple-scattering part of `image` (options o's) against the truth's.
    double multiplePart(const Image& image, VolumeRenderOptions o) const {
        o.multipleScatteringCache = false;
        Scene singleScene(o, volume, tf);
        const Image singleImage = singleScene.frame(camera);
        return (meanRatio(image, single.image) - meanRatio(singleImage, single.image)) /
               (meanRatio(truth.image, single.image) - 1.0);
    }
};

TEST_CASE("the cache's once-scattered light follows the direct light within its cells",
          "[gl][volume][scattering-cache]") {
    test::GlTestScope gl;
    const DenseBlock block;
    const VolumeRenderOptions o = cached(1 << 20, DenseBlock::kSide / 4);  // four voxels per cell
    Scene scene(o, block.volume, block.tf);
    const Image image = scene.refined(block.camera);
    const double multiplePart = block.multiplePart(image, o);
    const double error = computeErrorMetrics(image, block.truth.image).relRmse;
    INFO("multiple-scattering part against the truth's " << multiplePart << ", relRMSE " << error << " (truth's noise "
                                                         << block.truth.relativeRmseEstimate << ")");
    // Measured on llvmpipe: 0.887, relRMSE 12.9 %. With the light volume's second sweep blended
    // in (under this light until 2026-12-01; the direct light inside the cells differs, what the
    // eye sees of it does not): 1.009, 17.0 %. The cell's mean alone: 0.546 (29.4 %); the direct
    // light extrapolated without the cap at twice the cell's largest: 1.288 (32.1 %); capped at
    // the cell's largest: 0.733 (19.8 %).
    CHECK(multiplePart > 0.8);
    CHECK(multiplePart < 1.2);
    CHECK(error < 0.15);
    gl.requireNoErrors();
}

TEST_CASE("a first frame's filtered fluence and direct-light slope keep a lit face's light on one line",
          "[gl][volume][scattering-cache]") {
    // 2^17 photons of 2^20: the finest cells (four voxels deep) are filtered over about one cell
    // (fluence_denoise.comp). The slope pooled with the same weights and the cell's mean carried
    // along it belong to one line; a coarser level's slope beside the finest cells' mean counts
    // the lit faces' once-scattered light twice.
    test::GlTestScope gl;
    const DenseBlock block;
    VolumeRenderOptions o = cached(1 << 20, DenseBlock::kSide / 4);
    o.cachePhotonsPerFrame = 1 << 17;
    Scene scene(o, block.volume, block.tf);
    const Image first = scene.frame(block.camera);
    const double multiplePart = block.multiplePart(first, o);
    const double error = computeErrorMetrics(first, block.truth.image).relRmse;
    INFO("first frame: multiple-scattering part against the truth's " << multiplePart << ", relRMSE " << error);
    // Measured on llvmpipe: 1.020, relRMSE 17.2 %. Reading level 1 for all of it (before the
    // filter): 0.747, 18.8 %; the filtered mean with level 1's slope: 1.446, 44.0 %; with no slope
    // at all: 0.554, 29.8 %.
    CHECK(multiplePart == Approx(1.0).margin(0.12));
    CHECK(error < 0.2);
    gl.requireNoErrors();
}

namespace {
// The bright cube's first frame of a 2^20-photon cache at 16 cells with `photonsPerFrame`: its
// relRMSE and mean ratio against the truth.
struct FirstFrameError {
    double relRmse;
    double meanRatio;
};
FirstFrameError brightCubeFirstFrame(int photonsPerFrame) {
    const auto& [camera, truth] = brightCubeView();
    VolumeRenderOptions o = cached(1 << 20, 16);
    o.cachePhotonsPerFrame = photonsPerFrame;
    Scene scene(o, test::brightCube(), test::brightCubeTransferFunction());
    const Image first = scene.frame(camera);
    return {computeErrorMetrics(first, truth.image).relRmse, meanRatio(first, truth.image)};
}
}  // namespace

TEST_CASE("the cache's first frames filter their finest cells and keep their brightness",
          "[gl][volume][scattering-cache]") {
    // 2^14 photons of 2^20: the angular shape is read at level log8(64) = 2, and the finest
    // cells' fluence is filtered over about 3 cells, pooling level 1's. Each cell's own flux length, lengthened
    // by noise, had made the lobes near deltas (first frame too dark), and the finest level's
    // noise was most of the error.
    test::GlTestScope gl;
    const auto [error, ratio] = brightCubeFirstFrame(1 << 14);
    INFO("first frame: relRMSE " << error << ", mean ratio " << ratio << " (truth's noise "
                                 << brightCubeView().truth.relativeRmseEstimate << ")");
    // Measured on llvmpipe: 9.0 %, mean ratio 1.032; pooling the finest cells instead, 9.2 %
    // (1.032) with the spatial sigma capped at the window's 2.2 cells and the range terms widened
    // beyond it, 8.9 % (1.028) with the sigma at 3 cells.
    // Reading level 2 for all of it (before the filter): 11.2 % (1.035); at the finest level
    // 18.5 % (1.031), and with the cells' own flux lengths as well 18.4 % (0.958).
    CHECK(error < 0.1);
    CHECK(ratio == Approx(1.0).margin(0.06));
    gl.requireNoErrors();
}

TEST_CASE("a first frame with far fewer photons than cells pools coarser cells like each finest cell",
          "[gl][volume][scattering-cache]") {
    // 2^11 photons of 2^20 over 16^3 cells, one per two cells: the filter is asked to reach
    // about 2^3 cells (log8(2^20 / 2^11) = 3 levels), beyond its 5^3 window, as a 128-cell cache's
    // first frame over 256^3 data is. It pools level 2's cells, each weighed by its likeness to
    // the finest cell, instead of the finest cells with wider range terms.
    test::GlTestScope gl;
    const auto [error, ratio] = brightCubeFirstFrame(1 << 11);
    INFO("first frame at 1 photon per 2 cells: relRMSE " << error << ", mean ratio " << ratio << " (truth's noise "
                                                        << brightCubeView().truth.relativeRmseEstimate << ")");
    // Measured on llvmpipe: 14.1 %, mean ratio 1.094; the finest cells pooled by a 5^3 window
    // whose range terms widen beyond it: 15.9 % (1.049).
    CHECK(error < 0.15);
    CHECK(ratio == Approx(1.0).margin(0.12));
    gl.requireNoErrors();
}

TEST_CASE("a refined cache with few photons per cell pools its cells as a first frame does",
          "[gl][volume][scattering-cache]") {
    // 2^13 photons in all over 16^3 cells, two per cell: refined at its first frame, and as noisy
    // as a cell of 128^3 over a 256^3 data set at the default 2^21 photons. The fluence is
    // filtered over about half a cell and the angular shape read at level log8(64 / 2).
    test::GlTestScope gl;
    const auto& [camera, truth] = brightCubeView();
    Scene scene(cached(1 << 13, 16), test::brightCube(), test::brightCubeTransferFunction());
    const Image refined = scene.frame(camera);
    REQUIRE(scene.renderer.cachedPhotons() == (1u << 13));
    const double error = computeErrorMetrics(refined, truth.image).relRmse;
    const double ratio = meanRatio(refined, truth.image);
    INFO("refined at 2 photons per cell: relRMSE " << error << ", mean ratio " << ratio << " (truth's noise "
                                                    << truth.relativeRmseEstimate << ")");
    // Measured on llvmpipe: 13.0 %, mean ratio 1.011; each cell's own values, as before the
    // pooling followed the photons per cell: 24.9 % (1.020).
    CHECK(error < 0.17);
    CHECK(ratio == Approx(1.0).margin(0.06));
    gl.requireNoErrors();
}

TEST_CASE("an albedo-1 cube lit by the cache sends out all the power it takes from the beam",
          "[gl][volume][scattering-cache]") {
    // A unit cube, sigma_t = 2, albedo 1, g = 0.5, lit along -z with E = 1: it takes 1 - exp(-2)
    // of the beam's power, and all of it must leave. What leaves is the intensity I(w) (an
    // orthographic image's radiance times pixel area) integrated over the sphere: 64 strata of
    // equal area, one jittered direction each. Only the camera moves: the cache is built once.
    test::GlTestScope gl;
    const int n = 8;
    const double voxel = 1.0 / n;
    const float opacity = static_cast<float>(-std::expm1(-2.0 * voxel));
    const double sigma = -std::log1p(-static_cast<double>(opacity)) / voxel;
    const Volume cube = Volume::fromData({n, n, n}, VoxelType::UInt8, std::vector<uint8_t>(n * n * n, 255));
    const TransferFunction tf({{0.0f, glm::vec3(1.0f), opacity}, {1.0f, glm::vec3(1.0f), opacity}});
    const std::vector<Light> beam{DirectionalLight{.direction = {0.0f, 0.0f, -1.0f}, .intensity = 1.0f}};

    constexpr int kPixels = 64;
    constexpr float kViewSize = 1.8f;  // > sqrt(3): the cube fits from any side
    const double pixelArea = double(kViewSize) / kPixels * double(kViewSize) / kPixels;
    const glm::vec3 centre = cube.worldBounds().center();
    auto leavingPower = [&](const VolumeRenderOptions& options, std::uint64_t* cacheRuns) {
        VolumeScatteringRenderer renderer(options);
        renderer.setVolume(cube);
        renderer.setTransferFunction(tf);
        renderer.setLights(beam);
        RenderTarget target(kPixels, kPixels);
        std::uint64_t state = 0x2545f491ull;
        auto uniform = [&] {
            state = state * 6364136223846793005ull + 1442695040888963407ull;
            return double(state >> 11) * 0x1.0p-53;
        };
        constexpr int kStrata = 8;
        double sum = 0.0;
        for (int i = 0; i < kStrata; ++i)
            for (int j = 0; j < kStrata; ++j) {
                const double z = -1.0 + (i + uniform()) * 2.0 / kStrata, yaw = (j + uniform()) * 360.0 / kStrata;
                Camera camera;
                camera.setProjectionType(Projection::Orthographic);
                camera.setOrthoHeight(kViewSize);
                camera.setTarget(centre);
                camera.setDistance(3.0f);
                camera.setYaw(static_cast<float>(yaw - 180.0));
                camera.setPitch(static_cast<float>(std::asin(z) * 180.0 / std::numbers::pi));
                target.clear(glm::vec4(0.0f));
                renderer.render(camera, target);
                while (renderer.cachedPhotons() < static_cast<std::uint64_t>(options.cachePhotons) &&
                       options.multipleScatteringCache) {
                    target.clear(glm::vec4(0.0f));
                    renderer.render(camera, target);
                }
                if (i == 0 && j == 0 && cacheRuns) *cacheRuns = renderer.stats().runs("scattering-cache");
                const Image image = target.readColor();
                for (int y = 0; y < kPixels; ++y)
                    for (int x = 0; x < kPixels; ++x) sum += image.at(x, y).r * pixelArea;
            }
        if (cacheRuns) *cacheRuns = renderer.stats().runs("scattering-cache") - *cacheRuns;
        return 4.0 * std::numbers::pi / (kStrata * kStrata) * sum;
    };
    const double expected = -std::expm1(-sigma);
    VolumeRenderOptions o = cached(1 << 20, 8);
    std::uint64_t cacheRunsAfterFirstView = 0;
    const double withCache = leavingPower(o, &cacheRunsAfterFirstView);
    o.multipleScatteringCache = false;
    const double singleOnly = leavingPower(o, nullptr);
    INFO("scattered out: with the cache " << withCache << ", single scattering only " << singleOnly
                                          << "; taken from the beam " << expected);
    // Measured 0.871 against 0.865 (+0.7 %), single scattering alone 0.374.
    CHECK(withCache == Approx(expected).epsilon(0.03));
    CHECK(singleOnly < 0.75 * expected);  // the test sees missing orders
    CHECK(cacheRunsAfterFirstView == 0);  // 63 camera moves traced no photons
    gl.requireNoErrors();
}

TEST_CASE("the multiple-scattering cache adds nothing for a black medium or a single bounce",
          "[gl][volume][scattering-cache]") {
    test::GlTestScope gl;
    const Camera camera = blobsCamera();
    for (int variant = 0; variant < 2; ++variant) {
        const bool black = variant == 0;
        const TransferFunction tf = black ? blobsTf(glm::vec3(0.0f)) : blobsTf();
        VolumeRenderOptions o = cached(1 << 16, 24);
        if (!black) o.maxBounces = 1;
        Scene scene(o, blobs(), tf);
        const Image image = scene.frame(camera);
        REQUIRE(scene.renderer.cachedPhotons() == (1u << 16));
        o.multipleScatteringCache = false;
        Scene without(o, blobs(), tf);
        const Image reference = without.frame(camera);
        INFO((black ? "albedo 0" : "maxBounces 1"));
        // Exactly single scattering: the same image, bit for bit.
        CHECK(computeErrorMetrics(image, reference).maxAbsError == 0.0);
    }
    gl.requireNoErrors();
}

TEST_CASE("the multiple-scattering cache is kept for camera moves and restarted by light changes",
          "[gl][volume][scattering-cache]") {
    test::GlTestScope gl;
    VolumeRenderOptions o = cached(1 << 17, 16);
    o.cachePhotonsPerFrame = 1 << 16;
    o.cacheViewEvaluation = CacheViewEvaluation::PerCell;  // counted below
    Scene scene(o, blobs(), blobsTf());
    scene.frame(blobsCamera(30.0f));
    scene.frame(blobsCamera(30.0f));
    REQUIRE(scene.renderer.cachedPhotons() == (1u << 17));
    const std::uint64_t runs = scene.renderer.stats().runs("scattering-cache");
    const std::uint64_t lightVolumeRuns = scene.renderer.stats().runs("light-volume");
    const std::uint64_t viewRuns = scene.renderer.stats().runs("scattering-cache-view");
    for (float yaw : {60.0f, 120.0f, -90.0f}) scene.frame(blobsCamera(yaw));
    CHECK(scene.renderer.stats().runs("scattering-cache") == runs);
    CHECK(scene.renderer.stats().runs("light-volume") == lightVolumeRuns);
    CHECK(scene.renderer.cachedPhotons() == (1u << 17));
    // Each camera move evaluates the cache towards the new viewer once; a frame that moves
    // nothing evaluates nothing.
    CHECK(scene.renderer.stats().runs("scattering-cache-view") == viewRuns + 3);
    scene.frame(blobsCamera(-90.0f));
    CHECK(scene.renderer.stats().runs("scattering-cache-view") == viewRuns + 3);
    scene.renderer.setLights({DirectionalLight{.direction = {1.0f, -0.7f, -0.4f}, .intensity = 10.0f}});
    scene.frame(blobsCamera());
    CHECK(scene.renderer.cachedPhotons() == (1u << 16));  // restarted with the first frame's photons
    CHECK(scene.renderer.stats().runs("scattering-cache") == runs + 1);
    CHECK(scene.renderer.stats().runs("scattering-cache-view") == viewRuns + 4);  // the cache changed
    // Leaving the mode drops the cache.
    o.multipleScatteringCache = false;
    scene.renderer.setOptions(o);
    scene.frame(blobsCamera());
    CHECK(scene.renderer.cachedPhotons() == 0);
    gl.requireNoErrors();
}

namespace {
// The image with each pixel's colour (not its coverage) multiplied by `scale`.
Image scaledColour(Image image, glm::vec3 scale) {
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            glm::vec4& p = image.at(x, y);
            p = glm::vec4(glm::vec3(p) * scale, p.a);
        }
    return image;
}
std::vector<Light> blobsLight(float intensity, glm::vec3 color) {
    return {DirectionalLight{.direction = {-1.0f, -0.7f, -0.4f}, .color = color, .intensity = intensity}};  // kLights
}
}  // namespace

TEST_CASE("a change of the lights' radiance alone keeps the cache and the light volumes",
          "[gl][volume][scattering-cache]") {
    // The photons' paths, the light volumes and the direct light the cache regresses on do not
    // depend on how bright the lights are, only on where their light goes: the ray caster scales
    // what the cache holds by the lights' radiance now over that of its photons.
    test::GlTestScope gl;
    VolumeRenderOptions o = cached(1 << 17, 16);
    o.cachePhotonsPerFrame = 1 << 16;
    const Camera camera = blobsCamera();
    Scene scene(o, blobs(), blobsTf());
    const Image white = scene.refined(camera);
    const RenderStats& stats = scene.renderer.stats();
    const std::uint64_t runs = stats.runs("scattering-cache"), lightVolumeRuns = stats.runs("light-volume");
    const auto freshly = [&](const std::vector<Light>& lights) {
        Scene fresh(o, blobs(), blobsTf());
        fresh.renderer.setLights(lights);
        return fresh.refined(camera);
    };

    // Three times the intensity: three times the picture, nothing traced or swept again, and what
    // a cache traced for that light from the start shows (the same photons).
    scene.renderer.setLights(blobsLight(30.0f, glm::vec3(1.0f)));
    const Image brighter = scene.frame(camera);
    CHECK(stats.runs("scattering-cache") == runs);
    CHECK(stats.runs("light-volume") == lightVolumeRuns);
    CHECK(scene.renderer.cachedPhotons() == (1u << 17));
    CHECK(computeErrorMetrics(brighter, scaledColour(white, glm::vec3(3.0f))).relRmse < 1e-5);
    const double againstFresh = computeErrorMetrics(brighter, freshly(blobsLight(30.0f, glm::vec3(1.0f)))).relRmse;
    INFO("three times the intensity, against a cache traced for it: relRMSE " << againstFresh);
    CHECK(againstFresh < 1e-4);  // measured on llvmpipe: 7e-8 (rounding)

    // A colour: each channel scaled. A cache traced for it makes other random decisions (its
    // photons' weights differ per channel), so the two agree within their noise.
    const glm::vec3 orange(1.0f, 0.5f, 0.25f);
    scene.renderer.setLights(blobsLight(10.0f, orange));
    const Image coloured = scene.frame(camera);
    CHECK(stats.runs("scattering-cache") == runs);
    CHECK(stats.runs("light-volume") == lightVolumeRuns);
    CHECK(computeErrorMetrics(coloured, scaledColour(white, orange)).relRmse < 1e-5);
    const Image freshColoured = freshly(blobsLight(10.0f, orange));
    const double colourError = computeErrorMetrics(coloured, freshColoured).relRmse;
    const glm::dvec3 ratio = channelSums(coloured) / channelSums(freshColoured);
    INFO("orange, against a cache traced for it: relRMSE " << colourError << ", channels " << ratio.x << " / "
                                                             << ratio.y << " / " << ratio.z);
    // Measured on llvmpipe: 0.51 %, channels 1.0048 / 1.0045 / 1.0040.
    CHECK(colourError < 0.02);
    CHECK(std::abs(ratio.x - 1.0) < 0.02);
    CHECK(std::abs(ratio.y - 1.0) < 0.02);
    CHECK(std::abs(ratio.z - 1.0) < 0.02);

    // Back to white from orange: the cache still holds the white light's photons.
    scene.renderer.setLights(blobsLight(10.0f, glm::vec3(1.0f)));
    CHECK(computeErrorMetrics(scene.frame(camera), white).relRmse < 1e-5);
    CHECK(stats.runs("scattering-cache") == runs);

    // What the cache cannot scale restarts it: a channel lit that was dark, one of two lights
    // brightened (their mix changes), a light turned.
    const auto restarts = [&](const std::vector<Light>& before, const std::vector<Light>& after) {
        Scene other(o, blobs(), blobsTf());
        other.renderer.setLights(before);
        other.refined(camera);
        const std::uint64_t was = other.renderer.stats().runs("scattering-cache");
        other.renderer.setLights(after);
        other.frame(camera);
        return other.renderer.stats().runs("scattering-cache") == was + 1 && other.renderer.cachedPhotons() == (1u << 16);
    };
    CHECK(restarts(blobsLight(10.0f, {1.0f, 1.0f, 0.0f}), blobsLight(10.0f, glm::vec3(1.0f))));
    const PointLight lamp{.position = {0.0f, 2.0f, 1.0f}, .intensity = 20.0f};
    PointLight brighterLamp = lamp;
    brighterLamp.intensity = 40.0f;
    CHECK(restarts({blobsLight(10.0f, glm::vec3(1.0f)).front(), lamp},
                   {blobsLight(10.0f, glm::vec3(1.0f)).front(), brighterLamp}));
    CHECK(!restarts({blobsLight(10.0f, glm::vec3(1.0f)).front(), lamp},
                    {blobsLight(20.0f, glm::vec3(1.0f)).front(), brighterLamp}));  // both doubled
    CHECK(restarts(blobsLight(10.0f, glm::vec3(1.0f)),
                   {DirectionalLight{.direction = {1.0f, -0.7f, -0.4f}, .intensity = 10.0f}}));
    gl.requireNoErrors();
}

TEST_CASE("the cache's light towards an orthographic camera is that towards a distant perspective one",
          "[gl][volume][scattering-cache]") {
    // The cache's lobes are evaluated towards the viewer, per cell (FluenceCache::evaluateView)
    // or per sample: the eye for a perspective camera, one direction for an orthographic one. A perspective
    // camera 100 times as far with a narrow field shows the same view (0.3 % apart); with the
    // orthographic viewer's direction turned the wrong way they were 84 % apart.
    test::GlTestScope gl;
    Camera orthographic = blobsCamera(40.0f);
    const float height = 2.0f * orthographic.distance() * std::tan(glm::radians(orthographic.fovY()) / 2.0f);
    Camera distant = orthographic;
    distant.setDistance(100.0f * orthographic.distance());
    distant.setFovY(glm::degrees(2.0f * std::atan(height / (2.0f * distant.distance()))));
    distant.setClipPlanes(0.5f * distant.distance(), 2.0f * distant.distance());
    orthographic.setProjectionType(Projection::Orthographic);
    orthographic.setOrthoHeight(height);
    VolumeRenderOptions withoutCache = cached(1);
    withoutCache.multipleScatteringCache = false;
    Scene singleScene(withoutCache, blobs(), blobsTf());
    const Image singleOrthographic = singleScene.frame(orthographic);
    for (CacheViewEvaluation evaluation : {CacheViewEvaluation::PerCell, CacheViewEvaluation::PerSample}) {
        VolumeRenderOptions o = cached(1 << 17, 24);
        o.cacheViewEvaluation = evaluation;
        Scene scene(o, blobs(), blobsTf());
        const Image fromOrthographic = scene.refined(orthographic);
        const Image fromDistant = scene.frame(distant);
        const double multipleShare = 1.0 - 1.0 / meanRatio(fromOrthographic, singleOrthographic);
        const double error = computeErrorMetrics(fromOrthographic, fromDistant).relRmse;
        INFO("evaluated " << enumName(evaluation) << ": multiple-scattering share " << multipleShare
                          << ", orthographic against distant perspective relRMSE " << error);
        REQUIRE(multipleShare > 0.5);
        CHECK(error < 0.02);
    }
    gl.requireNoErrors();
}

TEST_CASE("the cache's light evaluated per sample is the light evaluated per cell",
          "[gl][volume][scattering-cache]") {
    // Two ways to the same lobe (CacheViewEvaluation): once per cell and camera move, where
    // samples interpolate the cells' products, or per sample from the interpolated values. The
    // blobs refined and on their first frame (filtered, the angular shape from between levels 0
    // and 1), and the dense block (the direct-light slope and its cap at work).
    test::GlTestScope gl;
    const DenseBlockScene block;
    struct Case {
        const char* name;
        const Volume& volume;
        TransferFunction tf;
        Camera camera;
        VolumeRenderOptions options;
        bool refine;
        double bound;
    };
    VolumeRenderOptions firstFrame = cached(1 << 20, 24);
    firstFrame.cachePhotonsPerFrame = 1 << 18;
    // Measured on llvmpipe: relRMSE 0.20 % (blobs refined), 0.90 % (first frame), 0.62 % (dense
    // block); the bound is 2 %.
    const Case cases[] = {{"blobs, refined", blobs(), blobsTf(), blobsCamera(), cached(1 << 18, 24), true, 0.02},
                          {"blobs, first frame", blobs(), blobsTf(), blobsCamera(), firstFrame, false, 0.02},
                          {"dense block, refined", block.volume, block.tf, block.camera,
                           cached(1 << 20, DenseBlockScene::kSide / 4), true, 0.02}};
    for (const Case& c : cases) {
        std::vector<Image> images;  // per cell, per sample
        for (CacheViewEvaluation evaluation : {CacheViewEvaluation::PerCell, CacheViewEvaluation::PerSample}) {
            VolumeRenderOptions o = c.options;
            o.cacheViewEvaluation = evaluation;
            Scene scene(o, c.volume, c.tf);
            images.push_back(c.refine ? scene.refined(c.camera) : scene.frame(c.camera));
        }
        const double error = computeErrorMetrics(images[1], images[0]).relRmse;
        INFO(c.name << ": per sample against per cell, relRMSE " << error);
        CHECK(error < c.bound);
    }
    gl.requireNoErrors();
}

TEST_CASE("the cache is evaluated per sample where its cells outnumber the pixels on a software rasteriser",
          "[gl][volume][scattering-cache]") {
    // CacheViewEvaluation::Auto: per cell on hardware GPUs; on software rasterisers per sample
    // where the cache's cells are more than kCacheCellsPerPixel times the target's pixels. Per
    // sample, camera moves evaluate nothing towards the viewer.
    test::GlTestScope gl;
    const auto viewRunsOverMoves = [](CacheViewEvaluation evaluation, int width, int height) {
        VolumeRenderOptions o = cached(1 << 16, 24);  // 24^3 cells
        o.cacheViewEvaluation = evaluation;
        VolumeScatteringRenderer renderer(o);
        renderer.setVolume(blobs());
        renderer.setTransferFunction(blobsTf());
        renderer.setLights(kLights);
        RenderTarget target(width, height);
        for (float yaw : {30.0f, 60.0f, 90.0f}) renderer.render(blobsCamera(yaw), target);
        return renderer.stats().runs("scattering-cache-view");
    };
    const bool software = gl::currentDeviceIsSoftware();
    REQUIRE(24.0 * 24 * 24 > kCacheCellsPerPixel * 48 * 32);
    REQUIRE(24.0 * 24 * 24 < kCacheCellsPerPixel * 128 * 96);
    CHECK(viewRunsOverMoves(CacheViewEvaluation::Auto, 48, 32) == (software ? 0u : 3u));
    CHECK(viewRunsOverMoves(CacheViewEvaluation::Auto, 128, 96) == 3u);
    CHECK(viewRunsOverMoves(CacheViewEvaluation::PerSample, 128, 96) == 0u);
    CHECK(viewRunsOverMoves(CacheViewEvaluation::PerCell, 48, 32) == 3u);
    gl.requireNoErrors();
}

TEST_CASE("the multiple-scattering cache's sums do not depend on how photons are split into frames",
          "[gl][volume][scattering-cache]") {
    // Integer sums: the same photons give the same cache bit for bit, whatever the order in
    // which the GPU adds them.
    test::GlTestScope gl;
    VolumeRenderOptions twoFrames = cached(1 << 16, 16);
    twoFrames.cachePhotonsPerFrame = 1 << 15;
    VolumeRenderOptions oneFrame = cached(1 << 16, 16);
    Scene a(twoFrames, blobs(), blobsTf()), b(oneFrame, blobs(), blobsTf());
    a.frame(blobsCamera());
    const Image split = a.frame(blobsCamera());
    const Image whole = b.frame(blobsCamera());
    REQUIRE(a.renderer.cachedPhotons() == b.renderer.cachedPhotons());
    CHECK(computeErrorMetrics(split, whole).maxAbsError == 0.0);
    gl.requireNoErrors();
}

constexpr std::int64_t kSumsBytesPerCell = 23 * 8;  // volume/fluence_sums.glsl

TEST_CASE("the cache's sums split over several storage buffers give the same cache",
          "[gl][volume][scattering-cache]") {
    // Past GL_MAX_SHADER_STORAGE_BLOCK_SIZE one binding cannot reach all the sums (llvmpipe: 128
    // MiB, about 90^3 cells; its offsets wrap past 2 GiB, as a 256^3 cache's did), so they are
    // bound as up to four ranges of one buffer. 24^3 cells of 4096 per part: four parts.
    test::GlTestScope gl;
    const Image whole = Scene(cached(1 << 15, 24), blobs(), blobsTf()).frame(blobsCamera());
    gl::StorageBlockLimitForTesting limit(4096 * kSumsBytesPerCell);
    REQUIRE(detail::fluenceCacheCellsPerPart(gl::storageBlockLimit()) == 4096);
    Scene split(cached(1 << 15, 24), blobs(), blobsTf());
    const Image parts = split.frame(blobsCamera());
    CHECK(channelSums(whole).x > 0.0);
    CHECK(computeErrorMetrics(parts, whole).maxAbsError == 0.0);
    gl.requireNoErrors();
}

TEST_CASE("a cache whose sums exceed four storage buffers gets fewer cells and a warning",
          "[gl][volume][scattering-cache][errors]") {
    test::GlTestScope gl;
    gl::StorageBlockLimitForTesting limit(2048 * kSumsBytesPerCell);  // at most 4 x 2048 cells: 24^3 does not fit
    std::vector<std::string> warnings;
    setLogHandler([&](LogLevel level, std::string_view m) {
        if (level == LogLevel::Warning) warnings.emplace_back(m);
    });
    Scene reduced(cached(1 << 15, 24), blobs(), blobsTf());
    const Image first = reduced.frame(blobsCamera(30.0f));
    reduced.frame(blobsCamera(40.0f));
    setLogHandler({});
    REQUIRE(warnings.size() == 1);
    CHECK(warnings[0].find("cacheResolution 24") != std::string::npos);
    CHECK(warnings[0].find("24 x 24 x 24") != std::string::npos);
    CHECK(warnings[0].find("20 x 20 x 20") != std::string::npos);
    CHECK(warnings[0].find("GL_MAX_SHADER_STORAGE_BLOCK_SIZE") != std::string::npos);
    // The fewer cells still light the blobs as 20 cells asked for directly.
    gl::setStorageBlockLimitForTesting(0);
    const Image asked = Scene(cached(1 << 15, 20), blobs(), blobsTf()).frame(blobsCamera(30.0f));
    CHECK(computeErrorMetrics(first, asked).maxAbsError == 0.0);
    gl.requireNoErrors();
}

TEST_CASE("multiple-scattering cache options are validated", "[gl][volume][scattering-cache][errors]") {
    VolumeRenderOptions o = cached(1 << 16);
    o.model = VolumeModel::Paper;
    CHECK_THROWS_WITH(validate(o), Catch::Contains("multipleScatteringCache") && Catch::Contains("Physical"));
    o = cached(1 << 16);
    o.shading = VolumeShading::EmissionAbsorption;
    CHECK_THROWS_WITH(validate(o), Catch::Contains("multipleScatteringCache"));
    o = cached(1 << 16);
    o.multipleScattering = true;
    CHECK_THROWS_WITH(validate(o), Catch::Contains("multipleScatteringCache"));
    o = cached(1 << 16);
    o.cacheResolution = 0;
    CHECK_THROWS_WITH(validate(o), Catch::Contains("cacheResolution"));
    o = cached(1 << 16);
    o.cachePhotons = 0;
    CHECK_THROWS_WITH(validate(o), Catch::Contains("cachePhotons"));
    o = cached(1 << 16);
    o.shading = VolumeShading::ScatteringGradient;
    CHECK_NOTHROW(validate(o));
}

TEST_CASE("multiple-scattering cache: report against the CPU path tracer", "[.][scattering-cache-report]") {
    test::GlTestScope gl;
    const bool cube = std::getenv("SSS_CACHE_REPORT_CUBE") != nullptr;
    const Volume volume = cube ? Volume::fromData({16, 16, 16}, VoxelType::UInt8, std::vector<uint8_t>(16 * 16 * 16, 255))
                               : blobs();
    const TransferFunction tf = cube ? TransferFunction({{0.0f, glm::vec3(0.9f), 0.3f}, {1.0f, glm::vec3(0.9f), 0.3f}})
                                     : blobsTf();
    for (float g : {0.0f, 0.5f}) {
        const Camera camera = orbitCamera(volume.worldBounds(), 30.0f, 20.0f);
        const VolumePathTracerResult truth =
            cpuPathTraced(volume, tf, camera, VolumeScatteringMode::MultipleScattering, 2048, g);
        const VolumePathTracerResult single =
            cpuPathTraced(volume, tf, camera, VolumeScatteringMode::SingleScattering, 2048, g);
        std::vector<int> resolutions{4, 8, 16, 24};
        if (const char* only = std::getenv("SSS_CACHE_REPORT_RESOLUTION")) resolutions = {std::atoi(only)};
        for (int resolution : resolutions) {
            VolumeRenderOptions o = cached(1 << 21, resolution);
            o.anisotropy = g;
            Scene scene(o, volume, tf);
            const Image image = scene.refined(camera);
            VolumeRenderOptions s = o;
            s.multipleScatteringCache = false;
            Scene singleScene(s, volume, tf);
            const Image singleImage = singleScene.frame(camera);
            std::cout << "g " << g << " cells " << resolution << ": relRMSE "
                      << computeErrorMetrics(image, truth.image).relRmse << " mean ratio "
                      << meanRatio(image, truth.image) << "; single: GPU/CPU " << meanRatio(singleImage, single.image)
                      << ", multiple part GPU/CPU "
                      << (meanRatio(image, single.image) - meanRatio(singleImage, single.image)) /
                             (meanRatio(truth.image, single.image) - 1.0)
                      << " (truth " << truth.relativeRmseEstimate << ")\n";
        }
    }
    gl.requireNoErrors();
}

TEST_CASE("multiple-scattering cache: report on a data set", "[.][scattering-cache-data]") {
    // SSS_CACHE_DATA=path/to/volume.raw SSS_CACHE_TF=preset SSS_CACHE_RESOLUTIONS="64 128"
    // SSS_CACHE_PHOTONS=N: the bench's view and light (sss-bench --accuracy volume) at 128 x 72.
    test::GlTestScope gl;
    const char* path = std::getenv("SSS_CACHE_DATA");
    const char* preset = std::getenv("SSS_CACHE_TF");
    if (!path || !preset) return;
    const Volume volume = Volume::load(path);
    const TransferFunction tf = TransferFunction::preset(preset);
    const int width = 128, height = 72;
    Camera camera;
    camera.setYaw(30.0f);
    camera.setPitch(20.0f);
    camera.frameTight(volume.worldBounds(), float(width) / float(height));
    const std::vector<Light> light{DirectionalLight{.direction = glm::normalize(glm::vec3(-0.6f, -0.7f, -0.4f))}};
    VolumePathTracerOptions po;
    po.samplesPerPixel = 1024;
    const VolumePathTracerResult truth =
        renderVolumePathTraced(volume, tf, 256, glm::mat4(1.0f), light, camera, width, height, po);
    std::istringstream resolutions(std::getenv("SSS_CACHE_RESOLUTIONS") ? std::getenv("SSS_CACHE_RESOLUTIONS") : "64");
    const int photons = std::getenv("SSS_CACHE_PHOTONS") ? std::atoi(std::getenv("SSS_CACHE_PHOTONS")) : (1 << 21);
    for (int resolution; resolutions >> resolution;) {
        VolumeRenderOptions o = cached(photons, resolution);
        VolumeScatteringRenderer renderer(o);
        renderer.setVolume(volume);
        renderer.setTransferFunction(tf);
        renderer.setLights(light);
        RenderTarget target(width, height);
        do {
            target.clear(glm::vec4(0.0f));
            renderer.render(camera, target);
        } while (renderer.cachedPhotons() < static_cast<std::uint64_t>(photons));
        const Image image = target.readColor();
        const glm::dvec3 ratio(meanRatio(image, truth.image));
        std::cout << path << " cells " << resolution << " photons " << photons << ": relRMSE "
                  << computeErrorMetrics(image, truth.image).relRmse << " mean ratio " << ratio.x << " (truth noise "
                  << truth.relativeRmseEstimate << ")\n";
        if (const char* out = std::getenv("SSS_CACHE_OUT")) {
            image.saveExr(std::string(out) + "-" + std::to_string(resolution) + ".exr");
            truth.image.saveExr(std::string(out) + "-truth.exr");
        }
    }
}

TEST_CASE("the cache warns once where its angular model was measured far from the path tracer",
          "[gl][volume][scattering-cache]") {
    // Within 3-7 % for |g| up to 0.5, 10-80 % off at g 0.65-0.9 (docs/multiple-scattering.md).
    test::GlTestScope gl;
    std::vector<std::string> warnings;
    setLogHandler([&](LogLevel level, std::string_view m) {
        if (level == LogLevel::Warning) warnings.emplace_back(m);
    });
    VolumeRenderOptions o = cached(1 << 16);
    VolumeScatteringRenderer measured(o);
    o.anisotropy = -0.6f;
    measured.setOptions(o);
    const size_t quiet = warnings.size();
    o.anisotropy = 0.8f;
    measured.setOptions(o);
    measured.setOptions(o);
    o.multipleScatteringCache = false;
    VolumeScatteringRenderer withoutCache(o);  // the path tracer and the light volume: no limit
    o.anisotropy = -0.9f;
    o.multipleScatteringCache = true;
    VolumeScatteringRenderer backward(o);
    setLogHandler({});
    CHECK(quiet == 0);
    REQUIRE(warnings.size() == 2);
    CHECK(warnings[0].find("anisotropy 0.8") != std::string::npos);
    CHECK(warnings[0].find("multiple-scattering.md") != std::string::npos);
    CHECK(warnings[1].find("anisotropy -0.9") != std::string::npos);
    gl.requireNoErrors();
}
