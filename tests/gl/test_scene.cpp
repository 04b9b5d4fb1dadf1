// Scene files rendered: a scene saved and loaded again renders the same pixels.
#include "support/gl_test.h"
#include "support/temp_dir.h"

#include <catch2/catch.hpp>
#include <sss/materials.h>
#include <sss/render_target.h>
#include <sss/scene.h>

using namespace sss;

namespace {

Image renderDescription(const SceneDescription& scene) {
    const SceneAssets assets = loadSceneAssets(scene);
    HybridCompositor compositor;
    populateCompositor(compositor, scene, assets);
    const Camera camera =
        sceneCamera(scene, assets, compositor.bounds(), float(scene.output.width) / float(scene.output.height));
    RenderTarget target(scene.output.width, scene.output.height);
    for (int frame = 0; frame < 3; ++frame) compositor.render(camera, target);
    return target.readColor();
}

}  // namespace

TEST_CASE("a scene saved and loaded again renders pixel-identically", "[gl][scene]") {
    test::GlTestScope gl;
    SceneDescription scene;
    SceneMesh torus;
    torus.source = "procedural:torus";
    torus.size = 0.6f;
    torus.transform = {{-0.5f, -0.2f, 0.1f}, {30.0f, 10.0f, 0.0f}, glm::vec3(1.0f)};
    torus.options.shading = MeshShading::Scattering;
    torus.options.cameras = 3;
    torus.options.samples = 6;
    torus.options.mapResolution = torus.options.lightMapResolution = 96;
    torus.options.accumulationFrames = 2;
    torus.options.millimetresPerUnit = 30.0;
    torus.material = materialPreset("skin1");
    scene.meshes.push_back(torus);
    SceneMesh sphere;
    sphere.source = "procedural:sphere";
    sphere.transform = {{0.6f, -0.3f, 0.4f}, glm::vec3(0.0f), glm::vec3(0.25f)};
    scene.meshes.push_back(sphere);
    SceneVolume volume;
    volume.source = "procedural:blobs";
    volume.transferFunction.points = {{0.1f, {0.9f, 0.5f, 0.2f}, 0.0f}, {0.9f, {0.3f, 0.6f, 0.9f}, 0.8f}};
    volume.transform = {{0.3f, 0.3f, -0.2f}, {0.0f, 45.0f, 0.0f}, glm::vec3(0.8f)};
    volume.options.shading = VolumeShading::Scattering;
    volume.options.jitter = false;
    scene.volumes.push_back(volume);
    scene.lights = {DirectionalLight{{-1.0f, -1.0f, -0.5f}, glm::vec3(0.8f), 1.0f},
                    SpotLight{{0.0f, 2.0f, 1.5f}, {0.0f, -1.0f, -0.7f}, 30.0f, 0.3f, {1.0f, 0.9f, 0.7f}, 3.0f}};
    scene.camera.yaw = 20.0f;
    scene.options.cornellBox = true;
    scene.output.width = 96;
    scene.output.height = 64;

    test::TempDir dir;
    saveSceneFile(scene, dir.path() / "scene.json");
    const SceneDescription loaded = loadSceneFile(dir.path() / "scene.json");
    const Image before = renderDescription(scene), after = renderDescription(loaded);
    REQUIRE(before.data().size() == after.data().size());
    int differing = 0, lit = 0;
    for (std::size_t i = 0; i < before.data().size(); ++i) {
        differing += before.data()[i] != after.data()[i] ? 1 : 0;
        lit += before.data()[i] > 0.05f ? 1 : 0;
    }
    CHECK(differing == 0);
    CHECK(lit > 1000);  // the scene is in view, not an empty frame compared with another
    gl.requireNoErrors();
}
