#include "support/gl_test.h"
#include "support/scenes.h"
#include "support/golden.h"

#include <catch2/catch.hpp>
#include <sss/error.h>
#include <sss/mesh_scattering_renderer.h>
#include <sss/procedural.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

using namespace sss;
using sss::test::orbitCamera;

namespace {

constexpr int kWidth = 256, kHeight = 144;  // small enough for llvmpipe on CI
const glm::vec4 kBackground{0.1f, 0.1f, 0.12f, 1.0f};

}  // namespace

TEST_CASE("Blinn-Phong sphere matches its golden image", "[gl][mesh][golden]") {
    test::GlTestScope gl;
    const Mesh sphere = makeUvSphere();
    MeshScatteringRenderer renderer;
    renderer.setMesh(sphere);
    renderer.setMaterial({.diffuse = {0.8f, 0.3f, 0.25f}, .specular = glm::vec3(0.5f), .shininess = 60.0f});
    renderer.setLights({DirectionalLight{.direction = {-1.0f, -0.8f, -1.0f}}});
    RenderTarget target(kWidth, kHeight);
    target.clear(kBackground);
    renderer.render(orbitCamera(sphere.bounds(), 20.0f, 15.0f), target);
    test::requireMatchesGolden(target.readColor(), "mesh_blinn_phong_sphere");
    CHECK(renderer.stats().runs("blinn-phong") == 1);
    gl.requireNoErrors();
}

TEST_CASE("Blinn-Phong torus with a directional and a point light matches its golden image",
          "[gl][mesh][golden]") {
    test::GlTestScope gl;
    const Mesh torus = makeTorus();
    MeshScatteringRenderer renderer;
    // Tilt the torus so both its hole and its inner surface are visible.
    renderer.setMesh(torus, glm::rotate(glm::mat4(1.0f), glm::radians(60.0f), glm::vec3(1, 0, 0)));
    renderer.setLights({DirectionalLight{.direction = {0.0f, -1.0f, -0.3f}, .color = {1.0f, 0.9f, 0.8f}},
                        PointLight{.position = {1.5f, 0.5f, 1.5f}, .color = {0.3f, 0.5f, 1.0f}, .intensity = 3.0f}});
    RenderTarget target(kWidth, kHeight);
    target.clear(kBackground);
    Camera camera = orbitCamera(torus.bounds(), -25.0f, 10.0f);
    camera.setProjectionType(Projection::Orthographic);
    camera.setOrthoHeight(2.2f);
    renderer.render(camera, target);
    test::requireMatchesGolden(target.readColor(), "mesh_blinn_phong_torus_two_lights");
    gl.requireNoErrors();
}

TEST_CASE("Lambert term of a sphere follows n.l analytically", "[gl][mesh][analytic]") {
    // Orthographic view along -z, light travelling along -z, no ambient or specular, linear output:
    // a pixel at distance r (in sphere radii) from the centre must read albedo * sqrt(1 - r^2).
    test::GlTestScope gl;
    const Mesh sphere = makeUvSphere(96, 64);  // fine tessellation so normals are near-exact
    MeshScatteringRenderer renderer;
    renderer.setMesh(sphere);
    const float albedo = 0.6f;
    renderer.setMaterial({.diffuse = glm::vec3(albedo), .specular = glm::vec3(0.0f), .ambient = glm::vec3(0.0f)});
    renderer.setLights({DirectionalLight{.direction = {0, 0, -1}}});
    const int size = 101;
    RenderTarget target(size, size);
    target.clear({0, 0, 0, 1});
    Camera camera;
    camera.setProjectionType(Projection::Orthographic);
    camera.setOrthoHeight(2.0f);  // the sphere exactly fills the image
    renderer.render(camera, target);
    const Image image = target.readColor();
    const float pixel = 2.0f / size;
    for (int x : {50, 60, 70, 80, 90}) {
        const float r = (static_cast<float>(x) + 0.5f) * pixel - 1.0f;
        const float expected = albedo * std::sqrt(std::max(0.0f, 1.0f - r * r));
        INFO("pixel " << x << ", r = " << r);
        // Flat-ish facets of the tessellation and interpolated normals: 2 % of the albedo.
        CHECK(image.at(x, 50).g == Approx(expected).margin(0.02f * albedo));
    }
    CHECK(image.at(0, 0).g == 0.0f);  // outside the sphere: background
    gl.requireNoErrors();
}

TEST_CASE("mesh renderer rejects bad parameters with clear errors", "[gl][mesh][errors]") {
    test::GlTestScope gl;
    CHECK_THROWS_WITH(MeshScatteringRenderer({.cameras = 0}), Catch::Contains("cameras"));
    MeshScatteringRenderer renderer;
    RenderTarget target(8, 8);
    CHECK_THROWS_WITH(renderer.render(Camera{}, target), Catch::Contains("no mesh"));
    CHECK_THROWS_WITH(renderer.setMaterial({.shininess = -1.0f}), Catch::Contains("shininess"));
    CHECK_THROWS_WITH(renderer.setLights({DirectionalLight{.direction = glm::vec3(0.0f)}}),
                      Catch::Contains("light 0"));
    CHECK_THROWS_WITH(renderer.setLights(std::vector<Light>(9, DirectionalLight{})), Catch::Contains("at most 8"));
    gl.requireNoErrors();
}
