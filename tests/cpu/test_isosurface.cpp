// Isosurfaces through VTK (sss/isosurface.h): a sphere of known radius in an anisotropic grid
// comes back at its physical size with outward normals; bad options name their field.
#include "cpu/test_helpers.h"

#include <catch2/catch.hpp>
#include <sss/isosurface.h>
#include <sss/scene.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstring>
#include <vector>

using namespace sss;
using Catch::Matchers::Contains;

namespace {

// Float32 voxels holding radius - (physical distance from the grid's centre): above the iso
// value 0 inside a sphere of `radius` (mm), below it outside.
Volume sphereVolume(glm::ivec3 dims, glm::vec3 spacing, float radius) {
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(dims.x) * dims.y * dims.z * 4);
    const glm::vec3 centre = 0.5f * glm::vec3(dims - 1) * spacing;
    std::size_t i = 0;
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x, i += 4) {
                const float value = radius - glm::length(glm::vec3(x, y, z) * spacing - centre);
                std::memcpy(&bytes[i], &value, 4);
            }
    return Volume::fromData(dims, VoxelType::Float32, std::move(bytes), spacing);
}

}  // namespace

TEST_CASE("isosurface: a sphere comes back at its physical size, centred, with outward normals",
          "[cpu][io][isosurface]") {
    const glm::vec3 spacing(1.0f, 1.0f, 2.0f);  // mm; the z slices twice as far apart
    const Volume volume = sphereVolume({40, 40, 20}, spacing, 15.0f);
    for (const int smoothing : {0, 15}) {
        IsosurfaceOptions o;
        o.value = 0.0;
        o.smoothingIterations = smoothing;
        const Mesh mesh = extractIsosurface(volume, o);
        INFO("smoothing " << smoothing << ": " << mesh.triangleCount() << " triangles");
        REQUIRE(mesh.triangleCount() > 500);
        double worstRadius = 0.0, worstNormal = 1.0;
        for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
            const glm::vec3 p = mesh.positions()[v];
            worstRadius = std::max(worstRadius, std::abs(static_cast<double>(glm::length(p)) - 15.0));
            worstNormal = std::min(worstNormal, static_cast<double>(glm::dot(mesh.normals()[v], glm::normalize(p))));
        }
        // Linear interpolation along voxel edges of a field that is exactly linear along rays
        // but not along the grid's axes: within a quarter of the coarsest spacing.
        CHECK(worstRadius < 0.5);
        CHECK(worstNormal > 0.9);
    }
}

TEST_CASE("isosurface: decimation keeps the shape within the triangle budget", "[cpu][io][isosurface]") {
    const Volume volume = sphereVolume({40, 40, 40}, glm::vec3(1.0f), 15.0f);
    IsosurfaceOptions o;
    o.maxTriangles = 800;
    const Mesh mesh = extractIsosurface(volume, o);
    CHECK(mesh.triangleCount() <= 880);
    CHECK(mesh.triangleCount() >= 600);
    for (const glm::vec3& p : mesh.positions()) REQUIRE(std::abs(glm::length(p) - 15.0f) < 1.0f);
}

TEST_CASE("isosurface: options out of range name their field", "[cpu][io][isosurface]") {
    const Volume volume = sphereVolume({8, 8, 8}, glm::vec3(1.0f), 3.0f);
    IsosurfaceOptions o;
    o.value = 100.0;  // above every voxel
    REQUIRE_SSS_ERROR(extractIsosurface(volume, o), ErrorKind::InvalidArgument, Contains("IsosurfaceOptions::value must lie strictly between"));
    o.value = 0.0;
    o.smoothingIterations = -1;
    REQUIRE_SSS_ERROR(extractIsosurface(volume, o), ErrorKind::InvalidArgument, Contains("IsosurfaceOptions::smoothingIterations must be >= 0"));
    o.smoothingIterations = 0;
    o.maxTriangles = -5;
    REQUIRE_SSS_ERROR(extractIsosurface(volume, o), ErrorKind::InvalidArgument, Contains("IsosurfaceOptions::maxTriangles must be >= 0"));
}

TEST_CASE("isosurface: a scene mesh made from a scene volume lies in its box at its physical scale",
          "[cpu][io][isosurface][scene]") {
    const std::string text = R"({"volumes": [{"source": "procedural:blobs", "visible": false}],
        "meshes": [{"isosurface": {"volume": 0, "value": 100, "maxTriangles": 3000, "millimetresPerVolumeUnit": 0.5},
                    "material": "marble"}]})";
    const SceneDescription scene = parseScene(text, "iso.json");
    REQUIRE(scene.meshes.size() == 1);
    REQUIRE(scene.meshes[0].isosurface);
    CHECK(scene.meshes[0].isosurface->options.value == 100.0);
    CHECK_FALSE(scene.volumes[0].visible);
    // Written and read back field for field.
    const SceneDescription again = parseScene(sceneToJson(scene), "again.json");
    REQUIRE(again.meshes[0].isosurface);
    CHECK(again.meshes[0].isosurface->options.maxTriangles == 3000);
    CHECK(again.meshes[0].isosurface->millimetresPerVolumeUnit == 0.5);
    CHECK(again.meshes[0].source.empty());
    CHECK_FALSE(again.volumes[0].visible);

    const SceneAssets assets = loadSceneAssets(scene);
    const Mesh& mesh = assets.meshes.at(0);
    CHECK(mesh.triangleCount() > 100);
    CHECK(mesh.triangleCount() <= 3300);
    // The blobs lie inside the volume's box (half a unit on its longest side), not at the
    // extraction's physical scale (64 voxels).
    const Bounds box = assets.volumes.at(0).worldBounds();
    const Bounds bounds = mesh.bounds();
    INFO("mesh " << bounds.min.x << ".." << bounds.max.x << ", box " << box.min.x << ".." << box.max.x);
    CHECK(glm::all(glm::greaterThanEqual(bounds.min, box.min - 1e-4f)));
    CHECK(glm::all(glm::lessThanEqual(bounds.max, box.max + 1e-4f)));
    CHECK(glm::length(bounds.size()) > 0.2f);
}

TEST_CASE("isosurface: scene errors name the isosurface field", "[cpu][io][isosurface][scene]") {
    const auto requireError = [](const std::string& text, const std::string& message) {
        REQUIRE_SSS_ERROR(parseScene(text, "iso.json"), ErrorKind::InvalidArgument, Contains(message));
    };
    requireError(R"({"volumes": [{"source": "procedural:blobs"}], "meshes": [{"isosurface": {"volume": 1, "value": 9}}]})",
                 "iso.json: meshes[0].isosurface.volume: no volume 1 (the scene has 1)");
    requireError(R"({"volumes": [{"source": "procedural:blobs"}],
                     "meshes": [{"source": "procedural:sphere", "isosurface": {"value": 9}}]})",
                 "iso.json: meshes[0].isosurface: a mesh has either a source or an isosurface");
    requireError(R"({"volumes": [{"source": "procedural:blobs"}], "meshes": [{"isosurface": {"value": 9}, "size": 2}]})",
                 "iso.json: meshes[0].size: an isosurface keeps its volume's size");
    requireError(R"({"volumes": [{"source": "procedural:blobs"}], "meshes": [{"isosurface": {"volume": 0}}]})",
                 "iso.json: meshes[0].isosurface.value: an isosurface needs a value");
    requireError(R"({"volumes": [{"source": "procedural:blobs"}], "meshes": [{"isosurface": {"value": 9, "maxTriangles": -1}}]})",
                 "iso.json: meshes[0].isosurface.maxTriangles: must be >= 0");
    // An iso value no voxel pair crosses is found when the assets load, and named there.
    const SceneDescription scene =
        parseScene(R"({"volumes": [{"source": "procedural:blobs"}], "meshes": [{"isosurface": {"value": 1000}}]})", "iso.json");
    REQUIRE_SSS_ERROR(loadSceneAssets(scene), ErrorKind::InvalidArgument, Contains("meshes[0]"));
}
