// libFuzzer target: sss::Mesh::load for the formats read through Assimp (PLY, STL, glTF 2.0,
// GLB, OFF) and the choice of reader by extension and content.
//
// Input: the first byte picks the file name's extension (byte % 7: .ply .stl .gltf .glb .off,
// none, .obj); the rest is the file. Oracle (see fuzz_support.h): load() returns or throws
// sss::Error, and a returned mesh keeps the invariants of include/sss/mesh.h: at least one
// triangle, indices in range, positions finite within Mesh::kMaxCoordinate, one unit normal per
// position, and finite bounds around every position.
//
// Assimp is linked as Debian builds it (not instrumented): coverage guidance stops at its
// boundary, and only what reaches libsss's code or crashes outright is seen.
#include "fuzz_support.h"

#include "sss/error.h"
#include "sss/mesh.h"

#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include <cmath>
#include <optional>

namespace {

bool finite3(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void checkMesh(const sss::Mesh& mesh) {
    const auto& positions = mesh.positions();
    const auto& normals = mesh.normals();
    const auto& indices = mesh.indices();
    SSS_FUZZ_CHECK(!positions.empty() && !indices.empty() && indices.size() % 3 == 0,
                   "%zu positions, %zu indices", positions.size(), indices.size());
    SSS_FUZZ_CHECK(normals.size() == positions.size(), "%zu normals for %zu positions", normals.size(),
                   positions.size());
    for (uint32_t index : indices)
        SSS_FUZZ_CHECK(index < positions.size(), "index %u, %zu vertices", index, positions.size());
    const sss::Bounds& b = mesh.bounds();
    SSS_FUZZ_CHECK(!b.empty() && finite3(b.min) && finite3(b.max) && std::isfinite(b.radius()), "bounds");
    for (std::size_t i = 0; i < positions.size(); ++i) {
        const glm::vec3 p = positions[i], n = normals[i];
        SSS_FUZZ_CHECK(finite3(p) && std::fabs(p.x) <= sss::Mesh::kMaxCoordinate &&
                           std::fabs(p.y) <= sss::Mesh::kMaxCoordinate && std::fabs(p.z) <= sss::Mesh::kMaxCoordinate,
                       "position %zu is (%g, %g, %g)", i, p.x, p.y, p.z);
        SSS_FUZZ_CHECK(finite3(n) && std::fabs(glm::length(n) - 1.0f) < 1e-3f, "normal %zu is (%g, %g, %g)", i, n.x,
                       n.y, n.z);
        SSS_FUZZ_CHECK(glm::all(glm::lessThanEqual(b.min, p)) && glm::all(glm::lessThanEqual(p, b.max)),
                       "position %zu outside the bounds", i);
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    static const char* const kNames[] = {"input.ply", "input.stl", "input.gltf", "input.glb",
                                         "input.off", "input",     "input.obj"};
    const std::filesystem::path path = sss::fuzz::writeScratchFile(kNames[data[0] % 7], data + 1, size - 1);
    std::optional<sss::Mesh> mesh;
    try {
        mesh = sss::Mesh::load(path);
    } catch (const sss::Error&) {
        return 0;  // any other exception escapes: a bug
    }
    checkMesh(*mesh);
    return 0;
}
