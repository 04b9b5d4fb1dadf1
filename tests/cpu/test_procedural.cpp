#include "sss/procedural.h"

#include "test_helpers.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <map>
#include <tuple>

using Catch::Contains;
using sss::ErrorKind;
using sss::Mesh;

namespace {

bool isDegenerate(const Mesh& m, std::size_t t) {
    const auto& i = m.indices();
    const auto& p = m.positions();
    const glm::vec3 n = glm::cross(p[i[3 * t + 1]] - p[i[3 * t]], p[i[3 * t + 2]] - p[i[3 * t]]);
    return glm::length(n) < 1e-9f;
}

using Key = std::tuple<long, long, long>;
Key key(glm::vec3 p) {  // positions quantized so that duplicated vertices compare equal
    return {std::lround(p.x * 1e4f), std::lround(p.y * 1e4f), std::lround(p.z * 1e4f)};
}

// Closed and consistently oriented: ignoring degenerate triangles, every directed edge (by
// position) appears exactly once and its reverse exactly once.
void requireClosedAndOriented(const Mesh& m) {
    std::map<std::pair<Key, Key>, int> edges;
    for (std::size_t t = 0; t < m.triangleCount(); ++t) {
        if (isDegenerate(m, t)) continue;
        for (int k = 0; k < 3; ++k) {
            const glm::vec3 a = m.positions()[m.indices()[3 * t + std::size_t(k)]];
            const glm::vec3 b = m.positions()[m.indices()[3 * t + std::size_t((k + 1) % 3)]];
            ++edges[{key(a), key(b)}];
        }
    }
    REQUIRE_FALSE(edges.empty());
    for (const auto& [e, count] : edges) {
        REQUIRE(count == 1);
        const auto reverse = edges.find({e.second, e.first});
        REQUIRE(reverse != edges.end());
        REQUIRE(reverse->second == 1);
    }
}

// Unit normals; each non-degenerate face normal agrees with its vertex normals.
void requireConsistentNormals(const Mesh& m) {
    for (const glm::vec3& n : m.normals()) REQUIRE(std::abs(glm::length(n) - 1.0f) < 1e-5f);
    for (std::size_t t = 0; t < m.triangleCount(); ++t) {
        if (isDegenerate(m, t)) continue;
        const auto& i = m.indices();
        const auto& p = m.positions();
        const glm::vec3 f = glm::cross(p[i[3 * t + 1]] - p[i[3 * t]], p[i[3 * t + 2]] - p[i[3 * t]]);
        for (int k = 0; k < 3; ++k) REQUIRE(glm::dot(f, m.normals()[i[3 * t + std::size_t(k)]]) > 0.0f);
    }
}

}  // namespace

TEST_CASE("makeUvSphere 20x20 matches the reference sphere", "[cpu]") {
    const Mesh s = sss::makeUvSphere();
    CHECK(s.vertexCount() == 382);
    CHECK(s.triangleCount() == 800);
    std::size_t degenerate = 0;
    for (std::size_t t = 0; t < s.triangleCount(); ++t) degenerate += isDegenerate(s, t) ? 1u : 0u;
    CHECK(degenerate == 40);  // one per pole quad
    for (std::size_t i = 0; i < s.vertexCount(); ++i) {
        const glm::vec3 p = s.positions()[i], n = s.normals()[i];
        REQUIRE(glm::length(p) == Approx(1.0f));
        REQUIRE(glm::dot(n, p) == Approx(1.0f));  // exact normal: n == p / radius
    }
    requireConsistentNormals(s);
    requireClosedAndOriented(s);
    CHECK(s.bounds().min.y == -1.0f);
    CHECK(s.bounds().max.y == 1.0f);
}

TEST_CASE("makeUvSphere with other parameters", "[cpu]") {
    const Mesh s = sss::makeUvSphere(7, 5, 2.5f);
    CHECK(s.vertexCount() == 2 + 4 * 7);
    CHECK(s.triangleCount() == 7 * 5 * 2);
    for (std::size_t i = 0; i < s.vertexCount(); ++i) {
        REQUIRE(glm::length(s.positions()[i]) == Approx(2.5f));
        REQUIRE(glm::dot(s.normals()[i], s.positions()[i]) > 0.0f);
    }
    requireClosedAndOriented(s);
    REQUIRE_SSS_ERROR(sss::makeUvSphere(2, 5), ErrorKind::InvalidArgument, Contains("segments") && Contains("got 2"));
    REQUIRE_SSS_ERROR(sss::makeUvSphere(8, 1), ErrorKind::InvalidArgument, Contains("rings"));
    REQUIRE_SSS_ERROR(sss::makeUvSphere(8, 8, 0.0f), ErrorKind::InvalidArgument, Contains("radius"));
}

TEST_CASE("makeTorus counts and outward normals", "[cpu]") {
    const Mesh t = sss::makeTorus();
    CHECK(t.vertexCount() == 48 * 24);
    CHECK(t.triangleCount() == 2 * 48 * 24);
    for (std::size_t i = 0; i < t.vertexCount(); ++i) {
        const glm::vec3 p = t.positions()[i];
        const glm::vec3 tubeCentre = 0.7f * glm::normalize(glm::vec3(p.x, 0.0f, p.z));
        REQUIRE(glm::length(p - tubeCentre) == Approx(0.3f));
        REQUIRE(glm::dot(t.normals()[i], p - tubeCentre) == Approx(0.3f));
    }
    requireConsistentNormals(t);
    requireClosedAndOriented(t);
    CHECK(t.bounds().max.x == Approx(1.0f));
    CHECK(t.bounds().max.y == Approx(0.3f));
    REQUIRE_SSS_ERROR(sss::makeTorus(0.3f, 0.3f), ErrorKind::InvalidArgument,
                      Contains("minorRadius must be < majorRadius"));
    REQUIRE_SSS_ERROR(sss::makeTorus(0.7f, 0.3f, 2), ErrorKind::InvalidArgument, Contains("majorSegments"));
}

TEST_CASE("makeFolds is a closed sphere carved by grooves and folds", "[cpu]") {
    const Mesh f = sss::makeFolds();
    CHECK(f.vertexCount() == 2 + 127 * 160);
    CHECK(f.triangleCount() == 2 * 128 * 160);
    double innermost = 1.0;
    for (const glm::vec3& p : f.positions()) {
        const double r = glm::length(p);
        REQUIRE(r <= 1.0 + 1e-6);
        innermost = std::min(innermost, r);
    }
    CHECK(innermost == Approx(0.5).margin(0.01));  // a groove crossing a fold at the equator
    CHECK(glm::length(f.positions().front()) == Approx(1.0f));  // no dimple at the poles
    CHECK(f.bounds().max.y == Approx(1.0f));
    requireConsistentNormals(f);
    requireClosedAndOriented(f);
    REQUIRE_SSS_ERROR(sss::makeFolds(2, 8), ErrorKind::InvalidArgument, Contains("makeFolds") && Contains("segments"));
    REQUIRE_SSS_ERROR(sss::makeFolds(8, 1), ErrorKind::InvalidArgument, Contains("rings"));
}

TEST_CASE("makeSlab is a closed box with flat normals", "[cpu]") {
    const Mesh s = sss::makeSlab();
    CHECK(s.vertexCount() == 24);
    CHECK(s.triangleCount() == 12);
    CHECK(s.bounds().min == glm::vec3(-0.8f, -0.5f, -0.1f));
    CHECK(s.bounds().max == glm::vec3(0.8f, 0.5f, 0.1f));
    for (std::size_t i = 0; i < s.vertexCount(); ++i) {
        const glm::vec3 n = s.normals()[i];
        CHECK(std::abs(n.x) + std::abs(n.y) + std::abs(n.z) == 1.0f);  // axis aligned
        CHECK(glm::dot(n, s.positions()[i]) > 0.0f);                   // outward
    }
    requireConsistentNormals(s);
    requireClosedAndOriented(s);
    REQUIRE_SSS_ERROR(sss::makeSlab({1, 0, 1}), ErrorKind::InvalidArgument, Contains("makeSlab") && Contains("size.y"));
}

TEST_CASE("Procedural volumes are deterministic and non-trivial", "[cpu]") {
    const sss::Volume a = sss::makeBlobsVolume(), b = sss::makeBlobsVolume();
    CHECK(a.dims() == glm::ivec3(64));
    CHECK(a.type() == sss::VoxelType::UInt8);
    CHECK(a.bytes() == b.bytes());
    CHECK(a.valueRange().second > a.valueRange().first);
    CHECK(a.valueRange().second >= 200);
    CHECK(a.valueAt(0, 0, 0) < 10);  // blobs fade out towards the corners

    const sss::Volume tiny = sss::makeBlobsVolume(2);
    CHECK(tiny.voxelCount() == 8);
    REQUIRE_SSS_ERROR(sss::makeBlobsVolume(1), ErrorKind::InvalidArgument,
                      Contains("makeBlobsVolume") && Contains("n must be in [2, 1024]"));
    REQUIRE_SSS_ERROR(sss::makeBlobsVolume(1025), ErrorKind::InvalidArgument, Contains("got 1025"));
}

TEST_CASE("makeShellVolume is hollow", "[cpu]") {
    const int n = 64;
    const sss::Volume v = sss::makeShellVolume(n);
    CHECK(v.bytes() == sss::makeShellVolume(n).bytes());
    CHECK(v.valueAt(n / 2, n / 2, n / 2) == 0);  // hollow centre
    CHECK(v.valueAt(0, 0, 0) == 0);              // empty corner
    // Mid-shell radius 0.38 of the side, along +x from the centre.
    const int x = static_cast<int>(0.5f * n + 0.38f * n);
    CHECK(v.valueAt(x, n / 2, n / 2) > 200);
    CHECK(v.valueAt(n - 1 - x, n / 2, n / 2) > 200);
    CHECK(v.valueAt(n / 2, x, n / 2) > 200);
    CHECK(v.valueRange() == std::pair<double, double>(0, 255));
    REQUIRE_SSS_ERROR(sss::makeShellVolume(n, 0.6f), ErrorKind::InvalidArgument, Contains("outerRadius"));
    REQUIRE_SSS_ERROR(sss::makeShellVolume(n, 0.3f, 0.4f), ErrorKind::InvalidArgument, Contains("thickness"));
}

TEST_CASE("makeBuckyLikeVolume is a symmetric cage of blobs", "[cpu]") {
    const int n = 32;
    const sss::Volume v = sss::makeBuckyLikeVolume();
    CHECK(v.dims() == glm::ivec3(n));
    CHECK(v.bytes() == sss::makeBuckyLikeVolume().bytes());
    CHECK(v.valueRange().second > 150);
    CHECK(v.valueAt(n / 2, n / 2, n / 2) == 0);  // the cage is hollow
    // The truncated icosahedron is symmetric under each axis mirror and cyclic axis rotation.
    int worst = 0;
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const int value = static_cast<int>(v.valueAt(x, y, z));
                worst = std::max(worst, std::abs(value - int(v.valueAt(n - 1 - x, y, z))));
                worst = std::max(worst, std::abs(value - int(v.valueAt(x, n - 1 - y, z))));
                worst = std::max(worst, std::abs(value - int(v.valueAt(y, z, x))));
            }
    CHECK(worst <= 1);
    // ...but not under swapping two axes (that is not a symmetry of C60 in this frame).
    int swapDiff = 0;
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) swapDiff = std::max(swapDiff, std::abs(int(v.valueAt(x, y, z)) - int(v.valueAt(y, x, z))));
    CHECK(swapDiff > 20);
}
