// Uses each component of an installed libsss once: scene (a scene file naming an OBJ), io (the
// OBJ and a PNG), reference (a few slab random-walk paths). Exit code 0 on success.
#include <sss/random_walk.h>
#include <sss/scene.h>
#include <sss/sss.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

int main() {
    try {
        const std::filesystem::path dir = std::filesystem::temp_directory_path() / "sss_components_consumer";
        std::filesystem::create_directories(dir);
        std::ofstream(dir / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
        std::ofstream(dir / "scene.json") << R"({"version": 1, "meshes": [{"source": "tri.obj"}]})";

        const sss::SceneDescription scene = sss::loadSceneFile(dir / "scene.json");
        const sss::SceneAssets assets = sss::loadSceneAssets(scene);
        const sss::Mesh mesh = sss::Mesh::load(dir / "tri.obj");

        sss::Image8 image(4, 4, {10, 20, 30, 255});
        image.savePng(dir / "out.png");
        const sss::Image8 back = sss::Image8::loadPng(dir / "out.png");

        sss::SlabRandomWalkOptions walk;
        walk.paths = 2000;
        const sss::SlabRandomWalkResult slab = sss::simulateSlab(sss::materialPreset("marble"), 0.0, walk);

        std::printf("scene meshes %zu, triangles %zu, png %d, slab reflectance %.3f\n", scene.meshes.size(),
                    mesh.indices().size() / 3, int(back.at(1, 1).g), slab.channels[0].diffuse.value);
        const bool ok = scene.meshes.size() == 1 && assets.meshes.size() == 1 && mesh.indices().size() == 3 &&
                        back.at(1, 1).g == 20 && slab.channels[0].diffuse.value > 0.1;
        return ok ? 0 : 1;
    } catch (const sss::Error& e) {
        std::fprintf(stderr, "consumer: %s\n", e.what());
        return 1;
    }
}
