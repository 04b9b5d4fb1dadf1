// The GPU volume path tracer (VolumeRenderOptions::multipleScattering): it converges to the CPU
// path tracer's multiple-scattering image (sss/volume_path_tracer.h), its error falls
// monotonically as samples accumulate, one bounce is the CPU's single scattering, and the
// running mean restarts when the scene or the camera changes. Small images: llvmpipe.
#include "support/gl_test.h"
#include "support/scenes.h"

#include <catch2/catch.hpp>
#include <sss/error.h>
#include <sss/image_compare.h>
#include <sss/procedural.h>
#include <sss/volume_path_tracer.h>
#include <sss/volume_scattering_renderer.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <map>
#include <vector>

using namespace sss;
using sss::test::orbitCamera;

namespace {

constexpr int kWidth = 48, kHeight = 32;
constexpr float kAnisotropy = 0.5f;

// 24^3 blobs with a bright, high-albedo TF: multiple scattering carries about as much light as
// single scattering here, so a renderer that missed it could not pass.
const Volume& testVolume() {
    static const Volume volume = makeBlobsVolume(24);
    return volume;
}
TransferFunction testTf(glm::vec3 albedo = {0.95f, 0.85f, 0.7f}) {
    return TransferFunction({{0.0f, albedo, 0.0f}, {0.2f, albedo, 0.0f}, {0.5f, albedo, 0.25f}, {1.0f, albedo, 0.6f}});
}
const std::vector<Light> kLights{DirectionalLight{.direction = {-1.0f, -0.7f, -0.4f}, .intensity = 10.0f}};
Camera testCamera() { return orbitCamera(testVolume().worldBounds(), 30.0f, 20.0f); }

VolumeRenderOptions pathTraced(int samplesPerFrame, int maxBounces = VolumeRenderOptions{}.maxBounces) {
    VolumeRenderOptions o;
    o.shading = VolumeShading::Scattering;
    o.model = VolumeModel::Physical;
    o.multipleScattering = true;
    o.anisotropy = kAnisotropy;
    o.samplesPerFrame = samplesPerFrame;
    o.maxBounces = maxBounces;
    return o;
}

// The CPU truth, computed once per mode and process: 8192 paths per pixel (its own error
// estimate, relativeRmseEstimate: 2.1 % for multiple scattering). About 12 s for both modes.
const VolumePathTracerResult& cpuTruth(VolumeScatteringMode mode) {
    static std::map<VolumeScatteringMode, VolumePathTracerResult> cache;
    auto it = cache.find(mode);
    if (it == cache.end()) {
        VolumePathTracerOptions o;
        o.samplesPerPixel = 8192;
        o.mode = mode;
        o.g = kAnisotropy;
        it = cache.emplace(mode, renderVolumePathTraced(testVolume(), testTf(), 256, glm::mat4(1.0f), kLights,
                                                        testCamera(), kWidth, kHeight, o))
                 .first;
    }
    return it->second;
}

struct Scene {
    VolumeScatteringRenderer renderer;
    RenderTarget target{kWidth, kHeight};
    explicit Scene(const VolumeRenderOptions& options) : renderer(options) {
        renderer.setVolume(testVolume());
        renderer.setTransferFunction(testTf());
        renderer.setLights(kLights);
    }
    Image frame(const Camera& camera) {
        target.clear(glm::vec4(0.0f));
        renderer.render(camera, target);
        return target.readColor();
    }
};

double relRmse(const Image& test, const VolumePathTracerResult& truth) {
    return computeErrorMetrics(test, truth.image).relRmse;
}

double meanRatio(const Image& test, const Image& reference) {
    double a = 0.0, b = 0.0;
    for (int y = 0; y < test.height(); ++y)
        for (int x = 0; x < test.width(); ++x)
            for (int c = 0; c < 3; ++c) {
                a += test.at(x, y)[c];
                b += reference.at(x, y)[c];
            }
    return a / b;
}

}  // namespace

TEST_CASE("the GPU path tracer converges to the CPU path tracer's multiple scattering",
          "[gl][volume][path-trace]") {
    test::GlTestScope gl;
    const VolumePathTracerResult& truth = cpuTruth(VolumeScatteringMode::MultipleScattering);
    const VolumePathTracerResult& single = cpuTruth(VolumeScatteringMode::SingleScattering);
    REQUIRE(truth.majorantViolations == 0);
    // Multiple scattering matters in this scene (measured: it carries 2.6x the single light).
    REQUIRE(meanRatio(truth.image, single.image) > 1.5);

    Scene scene(pathTraced(512));
    Image image(1, 1);
    for (int i = 0; i < 8; ++i) image = scene.frame(testCamera());
    REQUIRE(scene.renderer.accumulatedSamples() == 4096);
    // Measured on llvmpipe, 4096 GPU paths against 8192 CPU paths: relRMSE 3.9 %, which is the two
    // images' noise (sqrt(2.1^2 + 2.9^2) = 3.6 %, the GPU's estimator being the CPU's), mean
    // brightness 0.7 % off, coverage 0.3 % off. A bias of 4 % would take the error past the bound;
    // a missing order of scattering is far beyond it (single scattering is 69 % off).
    // With 512 paths per frame this also checks that many paths per frame lose none (they did
    // when one shader invocation ran them all: llvmpipe's loop limiter cut them, -28 %).
    const double error = relRmse(image, truth);
    INFO("relRMSE against the CPU truth " << error << ", its own estimate " << truth.relativeRmseEstimate);
    CHECK(error < 0.05);
    CHECK(std::abs(meanRatio(image, truth.image) - 1.0) < 0.02);
    // Coverage: the fraction of paths with a real collision, as the CPU's alpha.
    double alphaGpu = 0.0, alphaCpu = 0.0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            alphaGpu += image.at(x, y).a;
            alphaCpu += truth.image.at(x, y).a;
        }
    CHECK(alphaGpu == Approx(alphaCpu).epsilon(0.01));
    gl.requireNoErrors();
}

TEST_CASE("the GPU path tracer's error falls monotonically as samples accumulate", "[gl][volume][path-trace]") {
    test::GlTestScope gl;
    const VolumePathTracerResult& truth = cpuTruth(VolumeScatteringMode::MultipleScattering);
    Scene scene(pathTraced(4));
    std::vector<double> errors;
    // Frames of 4 paths each; measured after 4, 16, 64 and 256 paths per pixel.
    for (int frame = 1; frame <= 64; ++frame) {
        const Image image = scene.frame(testCamera());
        if (frame == 1 || frame == 4 || frame == 16 || frame == 64) errors.push_back(relRmse(image, truth));
    }
    REQUIRE(scene.renderer.accumulatedSamples() == 256);
    // Measured: 77.7 %, 39.7 %, 21.4 %, 11.7 % (1 / sqrt(N): high-albedo paths are long and
    // their values spread widely; the truth's own 2.1 % hardly shows yet).
    INFO("relRMSE at 4, 16, 64, 256 paths: " << errors[0] << ", " << errors[1] << ", " << errors[2] << ", "
                                             << errors[3]);
    for (size_t i = 1; i < errors.size(); ++i) CHECK(errors[i] < errors[i - 1]);
    // Each fourfold increase should about halve the error: demand at least a factor 1.5.
    for (size_t i = 1; i < errors.size(); ++i) CHECK(errors[i] * 1.5 < errors[i - 1]);
    gl.requireNoErrors();
}

TEST_CASE("one bounce of the GPU path tracer is the CPU's single scattering", "[gl][volume][path-trace]") {
    test::GlTestScope gl;
    const VolumePathTracerResult& single = cpuTruth(VolumeScatteringMode::SingleScattering);
    const VolumePathTracerResult& multiple = cpuTruth(VolumeScatteringMode::MultipleScattering);
    Scene scene(pathTraced(512, 1));
    Image image(1, 1);
    for (int i = 0; i < 8; ++i) image = scene.frame(testCamera());
    // Measured (4096 GPU paths, 8192 CPU paths): 2.1 % against single scattering, which is the
    // noise of both; 69 % against multiple.
    const double error = relRmse(image, single);
    INFO("relRMSE against CPU single scattering " << error);
    CHECK(error < 0.03);
    CHECK(relRmse(image, multiple) > 0.3);
    gl.requireNoErrors();
}

TEST_CASE("the GPU path tracer: a black medium scatters nothing, a transparent one is not there",
          "[gl][volume][path-trace]") {
    test::GlTestScope gl;
    Scene scene(pathTraced(16));
    scene.renderer.setTransferFunction(testTf(glm::vec3(0.0f)));
    const Image black = scene.frame(testCamera());
    double rgb = 0.0, alpha = 0.0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            rgb += black.at(x, y).r + black.at(x, y).g + black.at(x, y).b;
            alpha += black.at(x, y).a;
        }
    CHECK(rgb == 0.0);   // albedo 0: every next-event term is 0
    CHECK(alpha > 10.0); // but the medium is there and hides what is behind it
    scene.renderer.setTransferFunction(TransferFunction({{0.0f, glm::vec3(1.0f), 0.0f}, {1.0f, glm::vec3(1.0f), 0.0f}}));
    const Image empty = scene.frame(testCamera());
    double sum = 0.0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) sum += empty.at(x, y).r + empty.at(x, y).a;
    CHECK(sum == 0.0);
    gl.requireNoErrors();
}

TEST_CASE("the GPU path tracer's running mean restarts when the camera or the scene changes",
          "[gl][volume][path-trace]") {
    test::GlTestScope gl;
    Scene scene(pathTraced(2));
    const Camera camera = testCamera();
    for (int i = 0; i < 4; ++i) scene.frame(camera);
    REQUIRE(scene.renderer.accumulatedSamples() == 8);

    // A moved camera: the mean restarts, and equals a fresh renderer's first frame exactly (the
    // random streams are keyed by pixel and sample index only).
    Camera moved = camera;
    moved.setYaw(camera.yaw() + 10.0f);
    const Image afterMove = scene.frame(moved);
    CHECK(scene.renderer.accumulatedSamples() == 2);
    Scene fresh(pathTraced(2));
    const Image freshFrame = fresh.frame(moved);
    CHECK(computeErrorMetrics(afterMove, freshFrame).maxAbsError == 0.0);
    scene.frame(moved);
    CHECK(scene.renderer.accumulatedSamples() == 4);

    // Lights, transfer function, model transform and options each restart it; samplesPerFrame,
    // which does not change the mean, does not.
    scene.renderer.setLights({DirectionalLight{.direction = {1.0f, -0.7f, -0.4f}, .intensity = 10.0f}});
    scene.frame(moved);
    CHECK(scene.renderer.accumulatedSamples() == 2);
    scene.renderer.setTransferFunction(testTf({0.5f, 0.5f, 0.5f}));
    scene.frame(moved);
    CHECK(scene.renderer.accumulatedSamples() == 2);
    scene.renderer.setModelTransform(glm::scale(glm::mat4(1.0f), glm::vec3(1.2f)));
    scene.frame(moved);
    CHECK(scene.renderer.accumulatedSamples() == 2);
    VolumeRenderOptions options = pathTraced(3);
    scene.renderer.setOptions(options);
    scene.frame(moved);
    CHECK(scene.renderer.accumulatedSamples() == 5);
    options.anisotropy = 0.2f;
    scene.renderer.setOptions(options);
    scene.frame(moved);
    CHECK(scene.renderer.accumulatedSamples() == 3);
    // Leaving the mode drops the mean.
    options.multipleScattering = false;
    scene.renderer.setOptions(options);
    scene.frame(moved);
    CHECK(scene.renderer.accumulatedSamples() == 0);
    gl.requireNoErrors();
}

TEST_CASE("multiple-scattering options are validated", "[gl][volume][path-trace][errors]") {
    VolumeRenderOptions o = pathTraced(1);
    o.model = VolumeModel::Paper;
    REQUIRE_THROWS_WITH(validate(o), Catch::Contains("multipleScattering"));
    o = pathTraced(1);
    o.shading = VolumeShading::EmissionAbsorption;
    REQUIRE_THROWS_WITH(validate(o), Catch::Contains("multipleScattering"));
    o = pathTraced(0);
    REQUIRE_THROWS_WITH(validate(o), Catch::Contains("samplesPerFrame"));
    o = pathTraced(1, 0);
    REQUIRE_THROWS_WITH(validate(o), Catch::Contains("maxBounces"));
    REQUIRE_NOTHROW(validate(pathTraced(4096, 1)));
}
