// sss-bench --scene FILE.json: times a scene file's frames, "fixed" (nothing changes: what a
// still scene costs) and "change" (its lights turn by 3 degrees every frame, so every
// view-independent pass reruns).
#include "bench.h"

#include <sss/scene.h>

#include <glm/gtc/matrix_transform.hpp>

namespace {

/// `light` turned 3 degrees about +y (directions, and positions about the scene's centre).
sss::Light nudgedLight(const sss::Light& light, glm::vec3 centre) {
    const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), glm::radians(3.0f), glm::vec3(0, 1, 0));
    const auto direction = [&](glm::vec3 d) { return glm::vec3(turn * glm::vec4(d, 0.0f)); };
    const auto position = [&](glm::vec3 p) { return centre + glm::vec3(turn * glm::vec4(p - centre, 0.0f)); };
    sss::Light other = light;
    if (auto* d = std::get_if<sss::DirectionalLight>(&other)) d->direction = direction(d->direction);
    if (auto* p = std::get_if<sss::PointLight>(&other)) p->position = position(p->position);
    if (auto* s = std::get_if<sss::SpotLight>(&other)) s->position = position(s->position), s->direction = direction(s->direction);
    return other;
}

}  // namespace

void runSceneTable(BenchmarkContext& bench, const sss::SceneDescription& scene, const std::string& name) {
    const std::filesystem::path searchDirs[] = {bench.options().dataDir};
    const sss::SceneAssets assets = sss::loadSceneAssets(scene, searchDirs);
    sss::HybridCompositor compositor;
    sss::populateCompositor(compositor, scene, assets);
    const int width = bench.options().width, height = bench.options().height;
    const sss::Camera camera = sss::sceneCamera(scene, assets, compositor.bounds(), float(width) / float(height));
    const std::vector<sss::Light> lights = compositor.lights();
    std::vector<sss::Light> turned;
    for (const sss::Light& light : lights) turned.push_back(nudgedLight(light, compositor.bounds().center()));

    bool useTurned = false;
    const Measurement change = bench.measure(
        [&](sss::RenderTarget& t) {
            useTurned = !useTurned;
            compositor.setLights(useTurned ? turned : lights);
            compositor.render(camera, t);
        },
        "scene-" + name + "-change");
    compositor.setLights(lights);
    const Measurement fixed = bench.measure([&](sss::RenderTarget& t) { compositor.render(camera, t); },
                                            "scene-" + name + "-fixed");
    std::size_t triangles = 0;
    for (const sss::Mesh& m : assets.meshes) triangles += m.triangleCount();
    std::size_t voxels = 0;
    for (const sss::Volume& v : assets.volumes)
        voxels += std::size_t(v.dims().x) * std::size_t(v.dims().y) * std::size_t(v.dims().z);
    for (const auto& [mode, m] : {std::pair{"change", change}, std::pair{"fixed", fixed}}) {
        Record r;
        r.table = "scene";
        r.model = name;
        r.mode = mode;
        r.dataSize = std::to_string(scene.meshes.size()) + " mesh(es), " + std::to_string(triangles) + " tri; " +
                     std::to_string(scene.volumes.size()) + " volume(s), " + std::to_string(voxels) + " voxels";
        r.params = std::to_string(lights.size()) + " light(s)";
        r.width = width;
        r.height = height;
        r.measurement = m;
        r.details["meshes"] = scene.meshes.size();
        r.details["volumes"] = scene.volumes.size();
        r.details["lights"] = lights.size();
        bench.addRecord(std::move(r));
    }
}
