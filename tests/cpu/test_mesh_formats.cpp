// Mesh::load for the formats read through Assimp (PLY, STL, glTF 2.0, OFF) and the choice of
// reader by extension and content. Every file is written here, into a temp directory.
#include "sss/log.h"
#include "sss/mesh.h"

#include "test_helpers.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

using Catch::Contains;
using sss::ErrorKind;
using sss::Mesh;

namespace {

// Tetrahedron (0,0,0) (1,0,0) (0,1,0) (0,0,1), faces counter-clockwise seen from outside.
const float kTetraVertices[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
const uint32_t kTetraFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

const char* kTetraPlyAscii =
    "ply\nformat ascii 1.0\ncomment a tetrahedron\n"
    "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 4\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
    "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

// Unit cube as 6 quads (counter-clockwise from outside), per-vertex normals pointing outwards
// along the diagonals.
const char* kCubePlyAscii =
    "ply\r\nformat ascii 1.0\r\n"
    "element vertex 8\r\nproperty float x\r\nproperty float y\r\nproperty float z\r\n"
    "property float nx\r\nproperty float ny\r\nproperty float nz\r\n"
    "element face 6\r\nproperty list uchar int vertex_indices\r\nend_header\r\n"
    "0 0 0 -1 -1 -1\r\n1 0 0 1 -1 -1\r\n1 1 0 1 1 -1\r\n0 1 0 -1 1 -1\r\n"
    "0 0 1 -1 -1 1\r\n1 0 1 1 -1 1\r\n1 1 1 1 1 1\r\n0 1 1 -1 1 1\r\n"
    "4 0 3 2 1\r\n4 4 5 6 7\r\n4 0 1 5 4\r\n4 3 7 6 2\r\n4 0 4 7 3\r\n4 1 2 6 5\r\n";

const char* kTetraOff = "OFF\n# a tetrahedron\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

struct Bytes {
    std::string data;
    void u8(uint8_t v) { data.push_back(static_cast<char>(v)); }
    void u16(uint16_t v) {
        for (int i = 0; i < 2; ++i) u8(static_cast<uint8_t>(v >> (8 * i)));
    }
    void u32(uint32_t v) {
        for (int i = 0; i < 4; ++i) u8(static_cast<uint8_t>(v >> (8 * i)));
    }
    void f32(float f) {
        uint32_t v = 0;
        std::memcpy(&v, &f, 4);
        u32(v);
    }
};

std::string tetraPlyBinary(float firstX = 0.0f) {
    Bytes b;
    b.data =
        "ply\nformat binary_little_endian 1.0\n"
        "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 4\nproperty list uchar int vertex_indices\nend_header\n";
    for (int v = 0; v < 4; ++v)
        for (int a = 0; a < 3; ++a) b.f32(v == 0 && a == 0 ? firstX : kTetraVertices[v][a]);
    for (const auto& f : kTetraFaces) {
        b.u8(3);
        for (uint32_t i : f) b.u32(i);
    }
    return b.data;
}

std::string tetraStlAscii() {
    std::string s = "solid tetra\n";
    for (const auto& f : kTetraFaces) {
        s += "  facet normal 0 0 0\n    outer loop\n";
        for (uint32_t i : f)
            s += "      vertex " + std::to_string(kTetraVertices[i][0]) + " " + std::to_string(kTetraVertices[i][1]) +
                 " " + std::to_string(kTetraVertices[i][2]) + "\n";
        s += "    endloop\n  endfacet\n";
    }
    return s + "endsolid tetra\n";
}

// The header starts with "solid", as many exporters write it: the size tells it is binary.
std::string tetraStlBinary(float poison = 0.0f) {
    Bytes b;
    b.data = std::string("solid binary header");
    b.data.resize(80, ' ');
    b.u32(4);
    for (const auto& f : kTetraFaces) {
        for (int a = 0; a < 3; ++a) b.f32(0.0f);  // facet normal: ignored
        for (uint32_t i : f)
            for (int a = 0; a < 3; ++a) b.f32(i == 3 && a == 2 ? kTetraVertices[i][a] + poison : kTetraVertices[i][a]);
        b.u16(0);
    }
    return b.data;
}

// The tetrahedron's glTF buffer: 4 float positions, then 12 uint16 indices.
std::string tetraGltfBuffer() {
    Bytes b;
    for (const auto& v : kTetraVertices)
        for (float c : v) b.f32(c);
    for (const auto& f : kTetraFaces)
        for (uint32_t i : f) b.u16(static_cast<uint16_t>(i));
    return b.data;  // 48 + 24 = 72 bytes
}

std::string base64(std::string_view in) {
    static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < in.size(); i += 3) {
        uint32_t n = static_cast<uint32_t>(static_cast<unsigned char>(in[i])) << 16;
        if (i + 1 < in.size()) n |= static_cast<uint32_t>(static_cast<unsigned char>(in[i + 1])) << 8;
        if (i + 2 < in.size()) n |= static_cast<unsigned char>(in[i + 2]);
        out += table[(n >> 18) & 63];
        out += table[(n >> 12) & 63];
        out += i + 1 < in.size() ? table[(n >> 6) & 63] : '=';
        out += i + 2 < in.size() ? table[n & 63] : '=';
    }
    return out;
}

// A glTF 2.0 document placing the tetrahedron at the given nodes. bufferUri empty: the GLB
// binary chunk. mode 4 = triangles, 1 = lines.
std::string tetraGltfJson(const std::string& nodes, const std::string& nodeList, const std::string& bufferUri,
                          int mode = 4) {
    const std::string uri = bufferUri.empty() ? "" : "\"uri\":\"" + bufferUri + "\",";
    return "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[" + nodeList + "]}],"
           "\"nodes\":[" + nodes + "],"
           "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"mode\":" +
           std::to_string(mode) + "}]}],"
           "\"buffers\":[{" + uri + "\"byteLength\":72}],"
           "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":48},"
           "{\"buffer\":0,\"byteOffset\":48,\"byteLength\":24}],"
           "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\","
           "\"min\":[0,0,0],\"max\":[1,1,1]},"
           "{\"bufferView\":1,\"componentType\":5123,\"count\":12,\"type\":\"SCALAR\"}]}";
}

std::string glb(std::string json, const std::string& bin) {
    while (json.size() % 4 != 0) json += ' ';
    std::string padded = bin;
    while (padded.size() % 4 != 0) padded += '\0';
    Bytes b;
    b.data = "glTF";
    b.u32(2);
    b.u32(static_cast<uint32_t>(12 + 8 + json.size() + 8 + padded.size()));
    b.u32(static_cast<uint32_t>(json.size()));
    b.data += "JSON" + json;
    b.u32(static_cast<uint32_t>(padded.size()));
    b.data += std::string("BIN\0", 4) + padded;
    return b.data;
}

bool near(glm::vec3 a, glm::vec3 b, float eps = 1e-5f) { return glm::length(a - b) < eps; }

// The common checks on a loaded tetrahedron offset by `offset`: smooth normals (one vertex
// per corner position), bounds, the normal at the right-angle corner, and the winding.
void checkTetra(const Mesh& m, glm::vec3 offset = glm::vec3(0.0f)) {
    REQUIRE(m.triangleCount() == 4);
    CHECK(m.vertexCount() == 4);
    CHECK(near(m.bounds().min, offset));
    CHECK(near(m.bounds().max, offset + glm::vec3(1.0f)));
    bool foundCorner = false;
    for (std::size_t i = 0; i < m.vertexCount(); ++i) {
        CHECK(std::abs(glm::length(m.normals()[i]) - 1.0f) < 1e-5f);
        if (near(m.positions()[i], offset)) {
            foundCorner = true;
            CHECK(near(m.normals()[i], -glm::normalize(glm::vec3(1.0f)), 1e-4f));
        }
    }
    CHECK(foundCorner);
    const glm::vec3 centre = offset + glm::vec3(0.25f);
    const auto& p = m.positions();
    const auto& idx = m.indices();
    for (std::size_t t = 0; t < m.triangleCount(); ++t) {
        const glm::vec3 a = p[idx[3 * t]], b = p[idx[3 * t + 1]], c = p[idx[3 * t + 2]];
        CHECK(glm::dot(glm::cross(b - a, c - a), (a + b + c) / 3.0f - centre) > 0.0f);  // faces outwards
    }
}

struct WarningLog {
    std::vector<std::string> warnings;
    WarningLog() {
        sss::setLogHandler([this](sss::LogLevel level, std::string_view m) {
            if (level == sss::LogLevel::Warning) warnings.emplace_back(m);
        });
    }
    ~WarningLog() { sss::setLogHandler({}); }
};

}  // namespace

TEST_CASE("Mesh::load reads ASCII and binary PLY", "[mesh-formats]") {
    sss::test::TempDir dir;
    SECTION("ASCII tetrahedron without normals") {
        const auto path = dir.write("tetra.ply", kTetraPlyAscii);
        const Mesh m = Mesh::load(path);
        CHECK(m.name() == path.string());
        checkTetra(m);
    }
    SECTION("binary little-endian tetrahedron, upper-case extension") {
        checkTetra(Mesh::load(dir.write("TETRA.PLY", tetraPlyBinary())));
    }
    SECTION("ASCII cube of quads with normals, CRLF lines") {
        const Mesh m = Mesh::load(dir.write("cube.ply", kCubePlyAscii));
        CHECK(m.triangleCount() == 12);
        CHECK(m.vertexCount() == 8);
        CHECK(m.bounds().min == glm::vec3(0.0f));
        CHECK(m.bounds().max == glm::vec3(1.0f));
        for (std::size_t i = 0; i < m.vertexCount(); ++i) {  // the file's normals, normalized
            const glm::vec3 p = m.positions()[i];
            CHECK(near(m.normals()[i], glm::normalize(p - glm::vec3(0.5f)), 1e-5f));
        }
    }
}

TEST_CASE("Mesh::load reads ASCII and binary STL, joining the facets' corners", "[mesh-formats]") {
    sss::test::TempDir dir;
    checkTetra(Mesh::load(dir.write("tetra.stl", tetraStlAscii())));
    checkTetra(Mesh::load(dir.write("tetra_bin.Stl", tetraStlBinary())));
}

TEST_CASE("Mesh::load reads OFF", "[mesh-formats]") {
    sss::test::TempDir dir;
    checkTetra(Mesh::load(dir.write("tetra.off", kTetraOff)));
}

TEST_CASE("Mesh::load reads glTF 2.0 and GLB, applying node transforms", "[mesh-formats]") {
    sss::test::TempDir dir;
    const std::string buffer = tetraGltfBuffer();
    REQUIRE(buffer.size() == 72);
    SECTION(".gltf with an embedded base64 buffer and a translated node") {
        const std::string json = tetraGltfJson("{\"mesh\":0,\"translation\":[10,0,0]}", "0",
                                               "data:application/octet-stream;base64," + base64(buffer));
        checkTetra(Mesh::load(dir.write("tetra.gltf", json)), glm::vec3(10.0f, 0.0f, 0.0f));
    }
    SECTION(".gltf with its buffer in a file beside it") {
        dir.write("tetra.bin", buffer);
        checkTetra(Mesh::load(dir.write("tetra.gltf", tetraGltfJson("{\"mesh\":0}", "0", "tetra.bin"))));
    }
    SECTION(".glb placing the mesh twice: once as is, once under a translated parent") {
        const std::string json = tetraGltfJson(
            "{\"mesh\":0},{\"translation\":[0,5,0],\"children\":[2]},{\"mesh\":0,\"translation\":[0,0,2]}", "0,1", "");
        const Mesh m = Mesh::load(dir.write("two.glb", glb(json, buffer)));
        CHECK(m.triangleCount() == 8);
        CHECK(m.vertexCount() == 8);
        CHECK(near(m.bounds().min, glm::vec3(0.0f)));
        CHECK(near(m.bounds().max, glm::vec3(1.0f, 6.0f, 3.0f)));
    }
    SECTION("a mirroring node keeps the triangles facing outwards") {
        const std::string json = tetraGltfJson("{\"mesh\":0,\"scale\":[-1,1,1]}", "0", "");
        const Mesh m = Mesh::load(dir.write("mirror.glb", glb(json, buffer)));
        REQUIRE(m.triangleCount() == 4);
        CHECK(near(m.bounds().min, glm::vec3(-1.0f, 0.0f, 0.0f)));
        const glm::vec3 centre(-0.25f, 0.25f, 0.25f);
        for (std::size_t t = 0; t < 4; ++t) {
            const glm::vec3 a = m.positions()[m.indices()[3 * t]], b = m.positions()[m.indices()[3 * t + 1]],
                            c = m.positions()[m.indices()[3 * t + 2]];
            CHECK(glm::dot(glm::cross(b - a, c - a), (a + b + c) / 3.0f - centre) > 0.0f);
        }
    }
}

TEST_CASE("Mesh::load picks the reader by content when the extension is missing, unknown or wrong",
          "[mesh-formats]") {
    sss::test::TempDir dir;
    checkTetra(Mesh::load(dir.write("tetra", kTetraOff)));
    checkTetra(Mesh::load(dir.write("tetra.mesh", tetraStlBinary())));
    checkTetra(Mesh::load(dir.write("tetra.txt", tetraStlAscii())));
    checkTetra(Mesh::load(dir.write("tetra.dat", tetraPlyBinary())));
    checkTetra(Mesh::load(dir.write("tetra.json", tetraGltfJson("{\"mesh\":0}", "0",
                                                               "data:application/octet-stream;base64," +
                                                                   base64(tetraGltfBuffer())))));
    checkTetra(Mesh::load(dir.write("tetra.bin", glb(tetraGltfJson("{\"mesh\":0}", "0", ""), tetraGltfBuffer()))));
    // An OBJ under an unknown extension stays an OBJ.
    CHECK(Mesh::load(dir.write("tri.txt", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")).triangleCount() == 1);

    WarningLog log;
    checkTetra(Mesh::load(dir.write("really_ply.obj", kTetraPlyAscii)));
    checkTetra(Mesh::load(dir.write("really_off.stl", kTetraOff)));
    REQUIRE(log.warnings.size() == 2);
    CHECK_THAT(log.warnings[0], Contains("really_ply.obj") && Contains("content is PLY"));
    CHECK_THAT(log.warnings[1], Contains("really_off.stl") && Contains("content is OFF"));
}

TEST_CASE("Mesh::load rejects corrupted PLY, STL, glTF and OFF files naming the file", "[mesh-formats]") {
    sss::test::TempDir dir;
    auto rejects = [&](const std::string& name, const std::string& contents, const std::string& problem) {
        const auto path = dir.write(name, contents);
        INFO(name);
        REQUIRE_SSS_ERROR(Mesh::load(path), ErrorKind::Parse, Contains(path.string()) && Contains(problem));
    };

    const std::string ply = tetraPlyBinary();
    rejects("truncated.ply", ply.substr(0, ply.size() - 10), "truncated: it ends in face 3 of the 4");
    rejects("truncated_header.ply", ply.substr(0, 40), "no end_header line");
    rejects("truncated.stl", tetraStlBinary().substr(0, 84 + 50 * 3 + 20), "truncated or has extra bytes");
    rejects("short.stl", std::string(40, '\0'), "too short for a binary STL");
    rejects("nan.ply", tetraPlyBinary(std::numeric_limits<float>::quiet_NaN()), "vertex 0 has a non-finite coordinate");
    rejects("inf.stl", tetraStlBinary(std::numeric_limits<float>::infinity()), "has a non-finite coordinate");
    rejects("huge.ply", tetraPlyBinary(3e30f), "vertex 0 has a coordinate (3e+30, 0, 0) outside the supported range");
    std::string badIndex = kTetraPlyAscii;
    badIndex.replace(badIndex.rfind("3 1 2 3"), 7, "3 1 2 7");
    rejects("bad_index.ply", badIndex, "face 3 references vertex 7, but the mesh has 4 vertices");
    std::string noFaces = kTetraPlyAscii;
    noFaces.replace(noFaces.find("element face 4"), 14, "element face 0");
    noFaces.resize(noFaces.find("3 0 2 1"));
    rejects("no_faces.ply", noFaces, "has no triangles");
    rejects("ascii_truncated.ply", std::string(kTetraPlyAscii).substr(0, std::string(kTetraPlyAscii).size() - 8),
            "truncated: it ends in face 3");
    rejects("empty.ply", "", "has no triangles (the file is empty)");
    rejects("empty.stl", "", "has no triangles");
    rejects("empty.glb", "", "has no triangles");
    rejects("blank.off", "\n\n", "has no triangles");
    rejects("bad_count.off", "OFF\n4 4 6\n0 0 0\n1 0 0\n", "truncated: it has 2 of the 4 vertex lines");
    rejects("bad_index.off", "OFF\n3 1 3\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n", "face 0 references vertex 5");
    rejects("zero_face.off", "OFF\n3 1 3\n0 0 0\n1 0 0\n0 1 0\n0 0 0\n", "face 0 has 0 vertices");
    rejects("ten_gon.off", "OFF\n3 1 3\n0 0 0\n1 0 0\n0 1 0\n10 0 1 2 0 1 2 0 1 2 0\n", "face 0 has 10 vertices");
    rejects("nan.off", "OFF\n3 1 3\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n", "vertex 1 has a non-finite coordinate");
    rejects("garbage.gltf", "{\"asset\":{\"version\":\"2.0\"}, \"meshes\": [", "cannot read glTF (Assimp)");
    rejects("lines.gltf",
            tetraGltfJson("{\"mesh\":0}", "0", "data:application/octet-stream;base64," + base64(tetraGltfBuffer()), 1),
            "has no triangles, only");
    rejects("garbage.glb", std::string("glTF\2\0\0\0\xff\xff\xff\x7f", 12) + "JSON{\"asset\":", "the GLB header declares 2147483647 bytes, but the file has 25");
    rejects("tiny.glb", "glTF\2", "is not a GLB file");
    std::string longGlb = glb(tetraGltfJson("{\"mesh\":0}", "0", ""), tetraGltfBuffer());
    longGlb.resize(longGlb.size() - 8);
    rejects("cut.glb", longGlb, "(truncated or corrupt)");
}
