// The compute ray caster against the fragment one: same rays, same shader code, so the same
// image (issue 30: within 1/255), in every shading mode, over meshes, inside the volume and with
// the volume partly off screen.
#include "support/gl_test.h"
#include "support/scenes.h"

#include "volume/ray_cast_pass.h"

#include <catch2/catch.hpp>
#include <sss/mesh_scattering_renderer.h>
#include <sss/option_names.h>
#include <sss/procedural.h>
#include <sss/volume_scattering_renderer.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

using namespace sss;

namespace {

constexpr int kWidth = 120, kHeight = 68;
const glm::vec4 kBackground{0.1f, 0.1f, 0.12f, 1.0f};

struct Scene {
    Camera camera;
    glm::mat4 volumeModel{1.0f};
    bool sphereInside = false;  // a Blinn-Phong sphere through the volume: rays stop at its depth
};

Image render(const Volume& volume, const Scene& scene, VolumeRenderOptions options, RayCaster caster) {
    options.rayCaster = caster;
    VolumeScatteringRenderer renderer(options);
    renderer.setVolume(volume, scene.volumeModel);
    renderer.setTransferFunction(test::blobsTransferFunction());
    renderer.setLights({DirectionalLight{.direction = {-1.0f, -1.0f, -0.6f}}});
    RenderTarget target(kWidth, kHeight);
    target.clear(kBackground);
    if (scene.sphereInside) {
        MeshScatteringRenderer sphere({.shading = MeshShading::BlinnPhong});
        sphere.setMesh(makeUvSphere(24, 16, 0.25f));
        sphere.setLights({DirectionalLight{}});
        sphere.render(scene.camera, target);
    }
    renderer.render(scene.camera, target);
    return target.readColor();
}

struct Difference {
    float largest = 0.0f;  // over every channel of every pixel
    int volumePixels = 0;  // pixels the volume changed (fragment image against the background)
};

Difference compare(const Image& fragment, const Image& compute) {
    Difference d;
    for (int y = 0; y < fragment.height(); ++y)
        for (int x = 0; x < fragment.width(); ++x) {
            const glm::vec4 a = fragment.at(x, y), b = compute.at(x, y);
            for (int c = 0; c < 4; ++c) d.largest = std::max(d.largest, std::abs(a[c] - b[c]));
            if (glm::any(glm::greaterThan(glm::abs(a - kBackground), glm::vec4(1e-3f)))) ++d.volumePixels;
        }
    return d;
}

void checkSameImage(const Volume& volume, const Scene& scene, const VolumeRenderOptions& options,
                    int minimumVolumePixels) {
    const Difference d = compare(render(volume, scene, options, RayCaster::Fragment),
                                 render(volume, scene, options, RayCaster::Compute));
    INFO("largest difference " << d.largest << ", pixels the volume drew " << d.volumePixels);
    CHECK(d.volumePixels >= minimumVolumePixels);  // the comparison covers a picture, not a blank
    CHECK(d.largest <= 1.0f / 255.0f);
}

}  // namespace

TEST_CASE("the compute ray caster draws every mode as the fragment one does", "[gl][volume][ray-caster]") {
    test::GlTestScope gl;
    const Volume volume = makeBlobsVolume(40);
    const Scene scene{.camera = test::orbitCamera(volume.worldBounds(), 35.0f, 15.0f)};
    for (VolumeShading shading : {VolumeShading::EmissionAbsorption, VolumeShading::Gradient,
                                  VolumeShading::Scattering, VolumeShading::ScatteringGradient})
        for (bool preintegration : {true, false}) {
            INFO("shading " << enumName(shading) << ", pre-integration " << preintegration);
            checkSameImage(volume, scene, {.shading = shading, .preintegration = preintegration}, 600);
        }
    INFO("the physical model with the eye pass off, and the paper's with it on");
    checkSameImage(volume, scene, {.shading = VolumeShading::Scattering, .model = VolumeModel::Physical}, 600);
    checkSameImage(volume, scene, {.shading = VolumeShading::Scattering, .eyePass = true}, 600);
    gl.requireNoErrors();
}

TEST_CASE("the compute ray caster stops rays at meshes, inside the volume and off screen", "[gl][volume][ray-caster]") {
    test::GlTestScope gl;
    const Volume volume = makeBlobsVolume(40);
    const Bounds box = volume.worldBounds();
    const VolumeRenderOptions gradient{.shading = VolumeShading::Gradient};

    SECTION("a mesh through the volume") {
        checkSameImage(volume, {.camera = test::orbitCamera(box, 20.0f, 10.0f), .sphereInside = true}, gradient, 600);
    }
    SECTION("the eye inside the volume: the whole viewport") {
        Camera inside = test::orbitCamera(box, 30.0f, 10.0f);
        inside.setDistance(0.2f * glm::length(box.size()));
        inside.setClipPlanes(0.01f, 10.0f);
        checkSameImage(volume, {.camera = inside}, gradient, kWidth * kHeight / 2);
    }
    SECTION("the volume half out of the viewport") {
        const Scene edge{.camera = test::orbitCamera(box, 0.0f, 0.0f),
                         .volumeModel = glm::translate(glm::mat4(1.0f), {0.55f * box.size().x, 0.2f * box.size().y, 0.0f})};
        checkSameImage(volume, edge, gradient, 300);
    }
    gl.requireNoErrors();
}

TEST_CASE("the ray caster's screen rectangle holds the box and no more", "[gl][volume][ray-caster]") {
    const Bounds box{{-1.0f, -1.0f, -1.0f}, {1.0f, 1.0f, 1.0f}};
    const glm::ivec2 viewport(200, 100);
    const glm::mat4 projection = glm::perspective(glm::radians(60.0f), 2.0f, 0.1f, 100.0f);
    SECTION("in front of the eye: the projected corners' bounds, a pixel wider") {
        const glm::mat4 view = glm::lookAt(glm::vec3(0, 0, 10), glm::vec3(0), glm::vec3(0, 1, 0));
        const detail::PixelRect rect = detail::screenRectangle(projection * view, box, viewport);
        // The nearest face (z = 1, 9 units away) spans tan(30 deg) * 9 = 5.196 units half-height.
        const float halfHeight = 1.0f / (std::tan(glm::radians(30.0f)) * 9.0f) * 50.0f;
        CHECK(rect.origin.y == static_cast<int>(std::floor(50.0f - halfHeight)) - 1);
        CHECK(rect.size.y == static_cast<int>(std::ceil(50.0f + halfHeight)) + 1 - rect.origin.y);
        CHECK(rect.size.x < viewport.x / 4);
    }
    SECTION("reaching behind the eye: the whole viewport") {
        const glm::mat4 view = glm::lookAt(glm::vec3(0, 0, 0.5f), glm::vec3(0, 0, -1), glm::vec3(0, 1, 0));
        const detail::PixelRect rect = detail::screenRectangle(projection * view, box, viewport);
        CHECK(rect.origin == glm::ivec2(0));
        CHECK(rect.size == viewport);
    }
    SECTION("off screen: empty") {
        const glm::mat4 view = glm::lookAt(glm::vec3(40, 0, 10), glm::vec3(40, 0, 0), glm::vec3(0, 1, 0));
        CHECK(detail::screenRectangle(projection * view, box, viewport).empty());
    }
}
