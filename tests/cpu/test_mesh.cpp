#include "sss/log.h"
#include "sss/mesh.h"

#include "test_helpers.h"

#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>

#include <cmath>
#include <limits>

using Catch::Contains;
using sss::ErrorKind;
using sss::Mesh;

namespace {

// Unit cube [0,1]^3 as 6 quads, counter-clockwise seen from outside.
const char* kCubeVertices =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
    "v 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n";

const char* kCubeQuads =
    "f 1 4 3 2\n"   // z = 0
    "f 5 6 7 8\n"   // z = 1
    "f 1 2 6 5\n"   // y = 0
    "f 4 8 7 3\n"   // y = 1
    "f 1 5 8 4\n"   // x = 0
    "f 2 3 7 6\n";  // x = 1

const char* kCubeQuadsWithNormals =
    "vn 0 0 -1\nvn 0 0 1\nvn 0 -1 0\nvn 0 1 0\nvn -1 0 0\nvn 1 0 0\n"
    "f 1//1 4//1 3//1 2//1\n"
    "f 5//2 6//2 7//2 8//2\n"
    "f 1//3 2//3 6//3 5//3\n"
    "f 4//4 8//4 7//4 3//4\n"
    "f 1//5 5//5 8//5 4//5\n"
    "f 2//6 3//6 7//6 6//6\n";

bool isUnit(glm::vec3 n) { return std::abs(glm::length(n) - 1.0f) < 1e-5f; }

glm::vec3 faceNormal(const Mesh& m, std::size_t t) {
    const auto& p = m.positions();
    const auto& i = m.indices();
    return glm::cross(p[i[3 * t + 1]] - p[i[3 * t]], p[i[3 * t + 2]] - p[i[3 * t]]);
}

}  // namespace

TEST_CASE("Mesh::load reads an OBJ with normals, triangulating quads", "[cpu]") {
    sss::test::TempDir dir;
    const auto path = dir.write("cube_n.obj", std::string(kCubeVertices) + kCubeQuadsWithNormals);
    const Mesh m = Mesh::load(path);
    CHECK(m.triangleCount() == 12);
    // 8 corners x 3 face normals each: one vertex per distinct (position, normal) pair.
    CHECK(m.vertexCount() == 24);
    CHECK(m.indices().size() == 36);
    CHECK(m.normals().size() == m.positions().size());
    CHECK(m.name() == path.string());
    CHECK(m.bounds().min == glm::vec3(0.0f));
    CHECK(m.bounds().max == glm::vec3(1.0f));
    // File normals are used as given: axis aligned and pointing away from the cube centre.
    for (std::size_t i = 0; i < m.vertexCount(); ++i) {
        const glm::vec3 n = m.normals()[i];
        CHECK(isUnit(n));
        CHECK(std::abs(n.x) + std::abs(n.y) + std::abs(n.z) == Approx(1.0f));
        CHECK(glm::dot(n, m.positions()[i] - glm::vec3(0.5f)) > 0.0f);
    }
    // Triangulation keeps the winding: every face normal agrees with its vertex normals.
    for (std::size_t t = 0; t < m.triangleCount(); ++t)
        CHECK(glm::dot(faceNormal(m, t), m.normals()[m.indices()[3 * t]]) > 0.0f);
}

TEST_CASE("Mesh::load computes smooth normals when the file has none", "[cpu]") {
    sss::test::TempDir dir;
    const Mesh m = Mesh::load(dir.write("cube.obj", std::string(kCubeVertices) + kCubeQuads));
    CHECK(m.triangleCount() == 12);
    CHECK(m.vertexCount() == 8);  // one vertex per position when smoothing
    for (std::size_t i = 0; i < m.vertexCount(); ++i) {
        const glm::vec3 n = m.normals()[i];
        REQUIRE(isUnit(n));
        // A cube corner's area-weighted normal mixes its three faces' normals with weights 1 or
        // 1/2 (depending on the quad split), so it is close to the outward diagonal.
        const glm::vec3 diagonal = glm::normalize(m.positions()[i] - glm::vec3(0.5f));
        CHECK(glm::dot(n, diagonal) > 0.93f);
        CHECK(n.x * diagonal.x > 0.0f);
        CHECK(n.y * diagonal.y > 0.0f);
        CHECK(n.z * diagonal.z > 0.0f);
    }
}

TEST_CASE("Mesh::load smooths when only some faces have normals", "[cpu]") {
    sss::test::TempDir dir;
    const std::string text = std::string(kCubeVertices) +
                             "vn 0 0 -1\n"
                             "f 1//1 4//1 3//1 2//1\n"
                             "f 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n";
    const Mesh m = Mesh::load(dir.write("mixed.obj", text));
    CHECK(m.vertexCount() == 8);
    CHECK(m.triangleCount() == 12);
    // The corner normal is the smooth diagonal, not the file's (0,0,-1).
    for (std::size_t i = 0; i < m.vertexCount(); ++i) CHECK(std::abs(m.normals()[i].z) < 0.9f);
}

TEST_CASE("Mesh::load merges shapes, fans polygons and resolves relative indices", "[cpu]") {
    sss::test::TempDir dir;
    const std::string text =
        "o first\n"
        "v 0 0 0\nv 1 0 0\nv 1.3 0.8 0\nv 0.5 1.3 0\nv -0.3 0.8 0\n"
        "f 1 2 3 4 5\n"  // pentagon -> 3 triangles
        "o second\n"
        "v 0 0 1\nv 1 0 1\nv 0 1 1\n"
        "f -3 -2 -1\n";  // relative: vertices 6, 7, 8
    const Mesh m = Mesh::load(dir.write("two.obj", text));
    CHECK(m.triangleCount() == 4);
    CHECK(m.vertexCount() == 8);
    CHECK(m.bounds().min == glm::vec3(-0.3f, 0.0f, 0.0f));
    CHECK(m.bounds().max == glm::vec3(1.3f, 1.3f, 1.0f));
    // Flat counter-clockwise polygons in z = const: all normals are +z.
    for (const glm::vec3& n : m.normals()) CHECK(n.z == Approx(1.0f));
}

TEST_CASE("Mesh::load reports bad files with the file name and the problem", "[cpu]") {
    sss::test::TempDir dir;
    const auto missing = dir.path() / "nope.obj";
    REQUIRE_SSS_ERROR(Mesh::load(missing), ErrorKind::Io, Contains(missing.string()) && Contains("does not exist"));

    const auto outOfRange = dir.write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 9\n");
    REQUIRE_SSS_ERROR(Mesh::load(outOfRange), ErrorKind::Parse,
                      Contains(outOfRange.string()) && Contains("face 2 references vertex 9") &&
                          Contains("4 vertices"));

    // tinyobjloader itself silently drops quads with bad indices; we must still report them.
    const auto quadOutOfRange = dir.write("quad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 7\n");
    REQUIRE_SSS_ERROR(Mesh::load(quadOutOfRange), ErrorKind::Parse,
                      Contains("quad.obj") && Contains("face 1 references vertex 7"));

    const auto relativeOut = dir.write("rel.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -5\n");
    REQUIRE_SSS_ERROR(Mesh::load(relativeOut), ErrorKind::Parse, Contains("rel.obj") && Contains("face 1 references vertex"));

    const auto badNormal = dir.write("badn.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//4\n");
    REQUIRE_SSS_ERROR(Mesh::load(badNormal), ErrorKind::Parse,
                      Contains("badn.obj") && Contains("references normal 4") && Contains("1 normals"));

    const auto noFaces = dir.write("nofaces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    REQUIRE_SSS_ERROR(Mesh::load(noFaces), ErrorKind::Parse, Contains("nofaces.obj") && Contains("no faces"));

    const auto empty = dir.write("empty.obj", "");
    REQUIRE_SSS_ERROR(Mesh::load(empty), ErrorKind::Parse, Contains("empty.obj") && Contains("no faces"));

    const auto inf = dir.write("inf.obj", "v 0 0 0\nv 1e999 0 0\nv 0 1 0\nf 1 2 3\n");
    REQUIRE_SSS_ERROR(Mesh::load(inf), ErrorKind::Parse,
                      Contains("inf.obj") && Contains("vertex 2") && Contains("non-finite"));

    // tinyobjloader alone would read these as 0: a silently wrong mesh.
    for (const char* token : {"nan", "-nan", "NaN", "abc"}) {
        const auto bad = dir.write("nan.obj", std::string("v 0 0 0\nv 1 0 0\nv 0 ") + token + " 0\nf 1 2 3\n");
        REQUIRE_SSS_ERROR(Mesh::load(bad), ErrorKind::Parse,
                          Contains("nan.obj") && Contains("vertex 3") && Contains(token));
    }

    // What tinyobjloader alone reads as 0 or wraps around (issue 9, D3/D4): leading blanks,
    // lines ending in a lone CR, hex floats, huge but finite coordinates, 64-bit face indices.
    const std::pair<std::string, std::string> misread[] = {
        {"  v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "vertex 1 has a non-finite or non-numeric coordinate \"nan\""},
        {"v 0 0 0\rv 1 0 0\rv 0 nan 0\rf 1 2 3\r", "vertex 3 has a non-finite or non-numeric coordinate \"nan\""},
        {"\tv 0 0 0\r\nv 0x1p3 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n", "vertex 2 has a non-finite or non-numeric coordinate \"0x1p3\""},
        {"v 0 0 0\nv 1e19 0 0\nv 0 1 0\nf 1 2 3\n", "vertex 2 has the coordinate 1e19, which is outside the supported range"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 -1e30\nf 1 2 3\n", "vertex 3 has the coordinate -1e30"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3000000000\n", "face 1 references vertex 3000000000, but the file has 3 vertices"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -9999999999\n", "face 1 references vertex -9999999999"},
        {"v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "vertex 1 has 2 coordinates"},
    };
    for (const auto& [text, message] : misread) {
        const auto bad = dir.write("misread.obj", text);
        INFO(text);
        REQUIRE_SSS_ERROR(Mesh::load(bad), ErrorKind::Parse, Contains("misread.obj") && Contains(message));
    }

    // A zero index is invalid OBJ; tinyobjloader's own message is passed on.
    const auto zero = dir.write("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
    REQUIRE_SSS_ERROR(Mesh::load(zero), ErrorKind::Parse,
                      Contains("zero.obj") && Contains("cannot parse OBJ") && Contains("line 4"));

    REQUIRE_SSS_ERROR(Mesh::load(dir.path()), ErrorKind::Io, Contains(dir.path().string()) && Contains("directory"));
}

TEST_CASE("Mesh::load accepts the whole supported coordinate range and every line ending", "[cpu]") {
    sss::test::TempDir dir;
    for (const char* eol : {"\n", "\r\n", "\r"}) {
        const std::string text = std::string("v -1e18 0 0") + eol + "  v 1e18 0 0" + eol + "\tv 0 1.5e17 0" + eol +
                                 "f 1 2 3" + eol;
        const Mesh mesh = Mesh::load(dir.write("big.obj", text));
        REQUIRE(mesh.triangleCount() == 1);
        REQUIRE(mesh.bounds().max.x == 1e18f);
        REQUIRE(std::isfinite(mesh.bounds().radius()));
    }
}

TEST_CASE("normals are unit length for tiny and huge geometry", "[cpu]") {
    // Found by tests/fuzz: a smoothed normal whose squared length was denormal came out with
    // length 0.98; squares of huge vectors overflow float instead.
    for (const float s : {1e-20f, 1e-12f, 1.0f, 1e12f, 1e18f}) {
        const Mesh mesh = Mesh::fromArrays({{0, 0, 0}, {s, 0, 0}, {0, s, 0}, {0, 0, s}}, {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3});
        for (const glm::vec3& n : mesh.normals()) {
            INFO("scale " << s << ": normal (" << n.x << ", " << n.y << ", " << n.z << ")");
            REQUIRE(std::abs(glm::length(n) - 1.0f) < 1e-6f);
        }
        const Mesh scaled = Mesh::fromArrays({{0, 0, 0}, {s, 0, 0}, {0, s, 0}}, {0, 1, 2}, {{0, 0, s}, {0, 0, s}, {0, 0, s}});
        REQUIRE(scaled.normals()[0] == glm::vec3(0, 0, 1));
    }
}

TEST_CASE("Mesh::load ignores vertex weights, even out-of-range ones", "[cpu]") {
    // tinyobjloader converts "vw" joint ids to int unchecked (undefined behaviour under UBSan,
    // found by tests/fuzz); libsss does not use them and blanks those lines before parsing.
    sss::test::TempDir dir;
    const auto file = dir.write("weights.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n  vw 0 63333333333333333333333333333333 0.5\n"
                                                "vw 1 0 1\nf 1 2 3\nf 1 2 9\n");
    REQUIRE_SSS_ERROR(Mesh::load(file), ErrorKind::Parse, Contains("weights.obj") && Contains("face 2 references vertex 9"));
    const auto ok = dir.write("weights_ok.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvw 0 1e31 0.5\nf 1 2 3\n");
    REQUIRE(Mesh::load(ok).triangleCount() == 1);
}

TEST_CASE("Mesh::load skips faces with fewer than 3 vertices, with a warning", "[cpu]") {
    sss::test::TempDir dir;
    std::vector<std::string> warnings;
    sss::setLogHandler([&](sss::LogLevel level, std::string_view m) {
        if (level == sss::LogLevel::Warning) warnings.emplace_back(m);
    });
    const auto file = dir.write("short.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\nf 1 2 3\nf 3\n");
    const Mesh mesh = Mesh::load(file);
    sss::setLogHandler({});
    REQUIRE(mesh.triangleCount() == 1);
    REQUIRE(warnings.size() == 1);
    REQUIRE_THAT(warnings[0], Contains("short.obj") && Contains("skipped 2 faces with fewer than 3 vertices") &&
                                  Contains("face 1"));
}

TEST_CASE("Mesh::fromArrays builds and validates meshes", "[cpu]") {
    const std::vector<glm::vec3> tri = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};

    SECTION("valid triangle gets +z normals") {
        const Mesh m = Mesh::fromArrays(tri, {0, 1, 2});
        CHECK(m.vertexCount() == 3);
        CHECK(m.triangleCount() == 1);
        CHECK(m.name() == "mesh");
        for (const glm::vec3& n : m.normals()) CHECK(n == glm::vec3(0, 0, 1));
        CHECK(m.bounds().size() == glm::vec3(1, 1, 0));
    }
    SECTION("given normals are normalized") {
        const Mesh m = Mesh::fromArrays(tri, {0, 1, 2}, {{0, 0, 2}, {0, 3, 0}, {4, 0, 0}});
        CHECK(m.normals()[0] == glm::vec3(0, 0, 1));
        CHECK(m.normals()[1] == glm::vec3(0, 1, 0));
        CHECK(m.normals()[2] == glm::vec3(1, 0, 0));
    }
    SECTION("errors name the mesh and the problem") {
        REQUIRE_SSS_ERROR(Mesh::fromArrays(tri, {}, {}, "thing"), ErrorKind::InvalidArgument,
                          Contains("thing") && Contains("no triangles"));
        REQUIRE_SSS_ERROR(Mesh::fromArrays({}, {}, {}, "thing"), ErrorKind::InvalidArgument,
                          Contains("thing") && Contains("no triangles"));
        REQUIRE_SSS_ERROR(Mesh::fromArrays(tri, {0, 1, 2, 0}, {}, "thing"), ErrorKind::InvalidArgument,
                          Contains("thing") && Contains("index count 4 is not a multiple of 3"));
        REQUIRE_SSS_ERROR(Mesh::fromArrays(tri, {0, 1, 2, 2, 1, 3}, {}, "thing"), ErrorKind::InvalidArgument,
                          Contains("thing") && Contains("triangle 1") && Contains("references vertex 3") &&
                              Contains("3 vertices"));
        const float nan = std::numeric_limits<float>::quiet_NaN();
        REQUIRE_SSS_ERROR(Mesh::fromArrays({{0, 0, 0}, {nan, 0, 0}, {0, 1, 0}}, {0, 1, 2}, {}, "thing"),
                          ErrorKind::InvalidArgument, Contains("thing") && Contains("vertex 1") && Contains("non-finite"));
        REQUIRE_SSS_ERROR(Mesh::fromArrays(tri, {0, 1, 2}, {{0, 0, 1}, {0, 0, 1}}, "thing"),
                          ErrorKind::InvalidArgument, Contains("thing") && Contains("2 normals given for 3 positions"));
        REQUIRE_SSS_ERROR(Mesh::fromArrays(tri, {0, 1, 2}, {{0, 0, 1}, {0, 0, 0}, {0, 0, 1}}, "thing"),
                          ErrorKind::InvalidArgument, Contains("thing") && Contains("normal 1") && Contains("zero"));
    }
}

TEST_CASE("Degenerate triangles never give NaN normals", "[cpu]") {
    // Vertex 3 is only used by a zero-area triangle; vertex 0 has one real and one degenerate.
    const Mesh m = Mesh::fromArrays({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 5, 5}}, {0, 1, 2, 0, 3, 3});
    for (const glm::vec3& n : m.normals()) {
        CHECK(std::isfinite(n.x));
        CHECK(std::isfinite(n.y));
        CHECK(std::isfinite(n.z));
        CHECK(isUnit(n));
    }
    CHECK(m.normals()[0] == glm::vec3(0, 0, 1));
    // Fallback: direction from the bounds centre (2.5, 2.5, 2.5).
    CHECK(glm::dot(m.normals()[3], glm::normalize(glm::vec3(1))) == Approx(1.0f));

    // All triangles degenerate at one point: the last fallback is +z.
    const Mesh p = Mesh::fromArrays({{1, 1, 1}}, {0, 0, 0});
    CHECK(p.normals()[0] == glm::vec3(0, 0, 1));
}

TEST_CASE("Mesh::transformed moves positions, normals and keeps winding", "[cpu]") {
    const Mesh m = Mesh::fromArrays({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2}, {{1, 0, 1}, {1, 0, 1}, {1, 0, 1}});

    const glm::mat4 t = glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(1, 2, 3)), glm::vec3(2, 1, 1));
    const Mesh a = m.transformed(t);
    CHECK(a.positions()[1] == glm::vec3(3, 2, 3));
    CHECK(a.bounds().min == glm::vec3(1, 2, 3));
    CHECK(a.bounds().max == glm::vec3(3, 3, 3));
    // Non-uniform scale: normals use the inverse transpose, (1,0,1) -> (0.5,0,1) normalized.
    CHECK(glm::dot(a.normals()[0], glm::normalize(glm::vec3(0.5f, 0, 1))) == Approx(1.0f));
    CHECK(a.indices() == m.indices());

    const Mesh mirrored = m.transformed(glm::scale(glm::mat4(1.0f), glm::vec3(1, 1, -1)));
    CHECK(glm::dot(mirrored.normals()[0], glm::normalize(glm::vec3(1, 0, -1))) == Approx(1.0f));
    // The mirror turned the triangle clockwise; transformed() must reverse it back so the face
    // normal still agrees with the vertex normals. (Flat triangle in z=0: face normal is +-z.)
    const Mesh flat = Mesh::fromArrays({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2});
    const Mesh flipped = flat.transformed(glm::scale(glm::mat4(1.0f), glm::vec3(1, 1, -1)));
    CHECK(flipped.normals()[0] == glm::vec3(0, 0, -1));
    CHECK(glm::dot(faceNormal(flipped, 0), flipped.normals()[0]) > 0.0f);
    CHECK(flipped.indices() != flat.indices());

    REQUIRE_SSS_ERROR(m.transformed(glm::scale(glm::mat4(1.0f), glm::vec3(1, 0, 1))), ErrorKind::InvalidArgument,
                      Contains("mesh") && Contains("singular"));
}
