// Clip planes and the crop box (sss/volume_clip.h) in the GPU renderer: what is cut is not seen,
// casts no shadows unless asked, and the plane and box agree with each other, with the data
// made transparent where it is cut, and with the CPU reference.
#include "support/gl_test.h"
#include "support/scenes.h"

#include <catch2/catch.hpp>
#include <sss/volume_reference.h>
#include <sss/volume_scattering_renderer.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>
#include <vector>

using namespace sss;

namespace {

const glm::vec4 kBackground{0.0f, 0.0f, 0.0f, 1.0f};
constexpr int kN = 32;

Volume makeVolume(const std::function<uint8_t(int, int, int)>& value) {
    std::vector<uint8_t> bytes(static_cast<size_t>(kN * kN * kN));
    for (int z = 0; z < kN; ++z)
        for (int y = 0; y < kN; ++y)
            for (int x = 0; x < kN; ++x) bytes[static_cast<size_t>((z * kN + y) * kN + x)] = value(x, y, z);
    return Volume::fromData({kN, kN, kN}, VoxelType::UInt8, std::move(bytes));
}

// A ball of dense matter in a faint haze.
Volume ballVolume() {
    return makeVolume([](int x, int y, int z) {
        const glm::vec3 d = glm::vec3(x, y, z) + 0.5f - glm::vec3(kN / 2.0f);
        return glm::length(d) < 11.0f ? uint8_t(220) : uint8_t(90);
    });
}

TransferFunction greyTf() {
    return TransferFunction({{0.0f, {0.9f, 0.9f, 0.9f}, 0.0f}, {0.3f, {0.9f, 0.9f, 0.9f}, 0.02f},
                             {0.8f, {0.9f, 0.9f, 0.9f}, 0.3f}, {1.0f, {0.9f, 0.9f, 0.9f}, 0.9f}});
}

struct Render {
    VolumeRenderOptions options{};
    VolumeClip clip{};
    glm::mat4 model{1.0f};
    std::vector<Light> lights{DirectionalLight{.direction = {-1.0f, -0.1f, -0.2f}}};
    int frames = 1;
};

Image render(const Volume& volume, const Render& r, const Camera& camera) {
    VolumeScatteringRenderer renderer(r.options);
    renderer.setVolume(volume, r.model);
    renderer.setTransferFunction(greyTf());
    renderer.setLights(r.lights);
    renderer.setClip(r.clip);
    RenderTarget target(64, 48);
    for (int i = 0; i < r.frames; ++i) {
        target.clear(kBackground);
        renderer.render(camera, target);
    }
    return target.readColor();
}

Camera frontCamera(const Volume& volume) { return test::orbitCamera(volume.worldBounds(), 0.0f, 0.0f); }

float largestDifference(const Image& a, const Image& b, int x0 = 0, int x1 = -1) {
    float largest = 0.0f;
    for (int y = 0; y < a.height(); ++y)
        for (int x = x0; x < (x1 < 0 ? a.width() : x1); ++x) {
            const glm::vec4 d = glm::abs(a.at(x, y) - b.at(x, y));
            largest = std::max({largest, d.r, d.g, d.b});
        }
    return largest;
}

float meanLuminance(const Image& image, int x0, int x1) {
    double sum = 0.0;
    for (int y = 0; y < image.height(); ++y)
        for (int x = x0; x < x1; ++x) sum += (image.at(x, y).r + image.at(x, y).g + image.at(x, y).b) / 3.0;
    return static_cast<float>(sum / (image.height() * (x1 - x0)));
}

}  // namespace

TEST_CASE("a crop box hides what it cuts and leaves the rest as it was", "[gl][volume][clip]") {
    test::GlTestScope gl;
    const Volume volume = ballVolume();
    for (const auto& [shading, caster] : {std::pair(VolumeShading::EmissionAbsorption, RayCaster::Fragment),
                                         std::pair(VolumeShading::Gradient, RayCaster::Fragment),
                                         std::pair(VolumeShading::EmissionAbsorption, RayCaster::Compute)}) {
        Render whole;
        whole.options.shading = shading;
        whole.options.rayCaster = caster;
        Render cropped = whole;
        cropped.clip.cropMin = {0.0f, 0.0f, 0.0f};
        cropped.clip.cropMax = {0.5f, 1.0f, 1.0f};  // keeps world x <= 0: the image's left half
        const Image a = render(volume, whole, frontCamera(volume));
        const Image b = render(volume, cropped, frontCamera(volume));
        const int w = a.width();
        // Rays through the image's left third never reach x > 0; those in its right third only
        // cross the cut part.
        INFO("shading " << static_cast<int>(shading) << ", ray caster " << static_cast<int>(caster));
        CHECK(largestDifference(a, b, 0, w / 3) == 0.0f);
        CHECK(largestDifference(b, Image(w, a.height(), kBackground), 2 * w / 3, w) == 0.0f);
        CHECK(meanLuminance(a, 2 * w / 3, w) > 0.05f);  // there was something to cut
    }
    gl.requireNoErrors();
}

TEST_CASE("a clip plane cuts what the crop box cuts, in world or data space, under any placement",
          "[gl][volume][clip]") {
    test::GlTestScope gl;
    const Volume volume = ballVolume();
    for (const float angle : {0.0f, 35.0f}) {
        Render cropped;
        cropped.model = glm::rotate(glm::mat4(1.0f), glm::radians(angle), glm::vec3(0.0f, 1.0f, 0.0f));
        cropped.clip.cropMax = {0.5f, 1.0f, 0.7f};
        Render planes = cropped;
        planes.clip = {};
        // The box's faces at data x = 0.5 and z = 0.7, as world planes keeping the inside.
        const glm::mat3 r(cropped.model);
        planes.clip.planes = {{.point = glm::vec3(0.0f), .normal = r * glm::vec3(-1.0f, 0.0f, 0.0f)},
                              {.point = r * glm::vec3(0.0f, 0.0f, 0.2f), .normal = r * glm::vec3(0.0f, 0.0f, -1.0f)}};
        const Camera camera = test::orbitCamera(volume.worldBounds(), 20.0f, 15.0f);
        const Image a = render(volume, cropped, camera);
        const Image b = render(volume, planes, camera);
        Render unclipped;
        unclipped.model = cropped.model;
        const Image whole = render(volume, unclipped, camera);
        INFO("rotated " << angle << " degrees: largest difference " << largestDifference(a, b));
        CHECK(largestDifference(a, b) <= 1.5f / 255.0f);
        CHECK(largestDifference(a, whole) > 0.1f);  // the cut is visible
        // The same faces as planes in normalised data coordinates: n . p + d >= 0 with n (-1, 0, 0),
        // d 0.5 and n (0, 0, -1), d 0.7 (sss-render --clip-plane=-1,0,0,0.5), whatever the placement.
        Render dataPlanes = planes;
        dataPlanes.clip.planeSpace = CropSpace::Data;
        dataPlanes.clip.planes = {{.point = {0.5f, 0.0f, 0.0f}, .normal = {-1.0f, 0.0f, 0.0f}},
                                  {.point = {0.0f, 0.0f, 0.7f}, .normal = {0.0f, 0.0f, -1.0f}}};
        const Image e = render(volume, dataPlanes, camera);
        INFO("data-space planes against the crop box: largest difference " << largestDifference(a, e));
        CHECK(largestDifference(a, e) <= 1.5f / 255.0f);
        // A world-space crop box that only cuts at world x = 0.1 is that world plane, whatever
        // the placement.
        Render worldBox = unclipped, worldPlane = unclipped;
        worldBox.clip.cropSpace = CropSpace::World;
        worldBox.clip.cropMin = glm::vec3(-10.0f);
        worldBox.clip.cropMax = {0.1f, 10.0f, 10.0f};
        worldPlane.clip.planes = {{.point = {0.1f, 0.0f, 0.0f}, .normal = {-1.0f, 0.0f, 0.0f}}};
        const Image c = render(volume, worldBox, camera), d = render(volume, worldPlane, camera);
        INFO("world crop against world plane: largest difference " << largestDifference(c, d));
        CHECK(largestDifference(c, d) <= 1.5f / 255.0f);
        CHECK(largestDifference(c, whole) > 0.1f);
    }
    gl.requireNoErrors();
}

TEST_CASE("cut matter casts no shadows unless asked, in the light volume and the path tracer", "[gl][volume][clip]") {
    test::GlTestScope gl;
    const Volume withWall = test::blockAndWallVolume(true), withoutWall = test::blockAndWallVolume(false);
    const Camera camera = test::orbitCamera(withWall.worldBounds(), 0.0f, 0.0f);
    VolumeClip cutWall;  // keeps data x <= 0.6 (voxel 19): the wall goes, the block stays
    cutWall.planes = {{.point = {0.1f, 0.0f, 0.0f}, .normal = {-1.0f, 0.0f, 0.0f}}};
    VolumeClip shadowingWall = cutWall;
    shadowingWall.clippedMatterCastsShadows = true;
    const int blockColumns = 64 / 2;  // the block is in the image's left half

    VolumeRenderOptions light;
    light.shading = VolumeShading::Scattering;
    VolumeRenderOptions traced = light;
    traced.model = VolumeModel::Physical;
    traced.multipleScattering = true;
    traced.samplesPerFrame = 64;
    for (const VolumeRenderOptions& options : {light, traced}) {
        const int frames = options.multipleScattering ? 4 : 1;
        // The physical model is about 4 pi dimmer than the paper's.
        const std::vector<Light> lights{DirectionalLight{.direction = {-1.0f, -0.1f, -0.2f},
                                                         .intensity = options.multipleScattering ? 12.0f : 1.0f}};
        const auto renderWith = [&](const Volume& volume, const VolumeClip& clip) {
            Render r;
            r.options = options;
            r.clip = clip;
            r.lights = lights;
            r.frames = frames;
            return render(volume, r, camera);
        };
        const Image clipped = renderWith(withWall, cutWall);
        const Image noWall = renderWith(withoutWall, {});
        const Image shadowed = renderWith(withWall, shadowingWall);
        const float lit = meanLuminance(clipped, 0, blockColumns), reference = meanLuminance(noWall, 0, blockColumns);
        const float dark = meanLuminance(shadowed, 0, blockColumns);
        INFO((options.multipleScattering ? "path tracer" : "light volume")
             << ": block luminance " << lit << " clipped, " << reference << " without the wall, " << dark
             << " with the cut wall's shadow; largest difference to no wall " << largestDifference(clipped, noWall));
        CHECK(reference > 0.05f);
        // The path tracer: 256 paths per pixel, about 1 % noise in the block's mean.
        CHECK(std::abs(lit - reference) <= (options.multipleScattering ? 0.03f : 0.01f) * reference);
        CHECK(dark < 0.5f * lit);
        if (!options.multipleScattering) CHECK(largestDifference(clipped, noWall) <= 1.0f / 255.0f);
    }
    gl.requireNoErrors();
}

TEST_CASE("the clipped GPU image agrees with the clipped CPU reference", "[gl][volume][clip]") {
    test::GlTestScope gl;
    const Volume volume = ballVolume();
    VolumeClip clip;
    clip.planes = {{.point = {0.1f, 0.0f, 0.0f}, .normal = {-1.0f, 0.3f, 0.0f}}};
    clip.cropMin = {0.0f, 0.2f, 0.0f};
    const Camera camera = test::orbitCamera(volume.worldBounds(), 25.0f, 10.0f);
    Render gpu;
    gpu.clip = clip;
    gpu.options.stepSize = 0.25f;
    gpu.options.jitter = false;
    const Image image = render(volume, gpu, camera);
    const Image reference = renderVolumeReference(volume, greyTf(), gpu.options.transferFunctionEntries, glm::mat4(1.0f),
                                                  gpu.lights, camera, 64, 48, {.background = glm::dvec4(kBackground), .clip = clip});
    const Image unclipped = renderVolumeReference(volume, greyTf(), gpu.options.transferFunctionEntries, glm::mat4(1.0f),
                                                  gpu.lights, camera, 64, 48, {.background = glm::dvec4(kBackground)});
    INFO("largest difference to the clipped reference " << largestDifference(image, reference) << ", to the unclipped "
                                                         << largestDifference(image, unclipped));
    CHECK(largestDifference(image, reference) <= 6.0f / 255.0f);
    CHECK(largestDifference(image, unclipped) > 0.1f);
    gl.requireNoErrors();
}

TEST_CASE("bad clips are refused with the field named", "[gl][volume][clip][errors]") {
    test::GlTestScope gl;
    VolumeScatteringRenderer renderer;
    VolumeClip tooMany;
    tooMany.planes.resize(7);
    REQUIRE_THROWS_WITH(renderer.setClip(tooMany), Catch::Contains("VolumeClip::planes holds at most 6 planes, got 7"));
    VolumeClip zero;
    zero.planes = {{.point = glm::vec3(0.0f), .normal = glm::vec3(0.0f)}};
    REQUIRE_THROWS_WITH(renderer.setClip(zero), Catch::Contains("VolumeClip::planes[0].normal must be non-zero"));
    VolumeClip inverted;
    inverted.cropMin = {0.6f, 0.0f, 0.0f};
    inverted.cropMax = {0.4f, 1.0f, 1.0f};
    REQUIRE_THROWS_WITH(renderer.setClip(inverted), Catch::Contains("VolumeClip::cropMin must be below cropMax on every axis"));
    CHECK(renderer.clip().clipsNothing());  // a refused clip leaves the renderer's as it was
}
