// The multiple-scattering cache (VolumeRenderOptions::multipleScatteringCache): single scattering
// from the light volume plus the cached light scattered more than once converges towards the
// CPU path tracer's full transport; an albedo-1 cube sends out the power it takes from the beam;
// a black medium or one bounce adds nothing; camera moves rebuild nothing; the sums do not
// depend on how photons are split into frames. Small images and volumes: llvmpipe.
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
#include <cstdlib>
#include <iostream>
#include <map>
#include <numbers>
#include <vector>

using namespace sss;
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
    return TransferFunction({{0.0f, albedo, 0.0f}, {0.2f, albedo, 0.0f}, {0.5f, albedo, 0.25f}, {1.0f, albedo, 0.6f}});
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
