// Mesh::load for the formats read through Assimp (PLY, STL, glTF 2.0, OFF), the choice of
// reader by extension and content, and the texture coordinates and base-colour textures of every
// reader (OBJ + MTL included). Every file is written here, into a temp directory.
#include "sss/image.h"
#include "sss/log.h"
#include "sss/mesh.h"

#include "test_helpers.h"

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
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
    // Not JSON, so Assimp's glTF readers decline it; Assimp then tried its other readers, and the
    // PLY reader, finding "ply" in the first bytes, hung on it (the fuzzer's reproducer,
    // tests/fuzz/corpus/mesh_formats/repro_gltf_not_json_ply_reader_hang). Only the glTF readers
    // may read a glTF file.
    const char notJson[] = "plyly\nformat ascii 1.0\ne.\0\0\0%\xff 0 0\n1 0 0\n0 t1loa\nformat ascii 1.0\ne.\0\0\0"
                           "%\xff 0 0\n1 0 0\n0 t1loat  x\np0";
    rejects("ply_inside.gltf", std::string(notJson, sizeof notJson - 1), "cannot read glTF (Assimp)");
}

// ---- texture coordinates and base-colour textures -------------------------------------------

namespace {

// 4 x 2 texels, every one a different colour, so that a flipped or mirrored lookup reads a
// wrong one. Row 0 is the top row, as Image8 stores it.
sss::Image8 asymmetricTexture() {
    sss::Image8 image(4, 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x)
            image.at(x, y) = glm::u8vec4(10 + 60 * x, 20 + 150 * y, 230 - 40 * x - 70 * y, 255);
    return image;
}

// A texel's centre in Mesh's convention: (0, 0) the bottom-left corner of the image.
glm::vec2 meshUv(const sss::Image8& image, int x, int y) {
    return {(x + 0.5f) / static_cast<float>(image.width()), 1.0f - (y + 0.5f) / static_cast<float>(image.height())};
}

// The same texel in glTF's convention: (0, 0) the top-left corner.
glm::vec2 gltfUv(const sss::Image8& image, int x, int y) {
    return {(x + 0.5f) / static_cast<float>(image.width()), (y + 0.5f) / static_cast<float>(image.height())};
}

// What a renderer reads at uv through Mesh's convention: pixel (u W, (1 - v) H) of the image.
glm::u8vec4 texelAt(const sss::Image8& image, glm::vec2 uv) {
    const int x = std::clamp(static_cast<int>(std::floor(uv.x * static_cast<float>(image.width()))), 0, image.width() - 1);
    const int y = std::clamp(static_cast<int>(std::floor((1.0f - uv.y) * static_cast<float>(image.height()))), 0,
                             image.height() - 1);
    return image.at(x, y);
}

bool sameImage(const sss::Image8& a, const sss::Image8& b) {
    return a.width() == b.width() && a.height() == b.height() && a.data() == b.data();
}

std::string readFile(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::string objUv(glm::vec2 uv) { return "vt " + std::to_string(uv.x) + " " + std::to_string(uv.y) + "\n"; }

// A vertex of a loaded mesh: where it is and which texel its texture coordinate reads.
struct TexturedCorner {
    glm::vec3 position;
    glm::ivec2 texel;
};

// Every expected corner is a vertex of m, and every vertex one of them: positions and the texel
// its texture coordinate reads through Mesh's convention.
void checkCorners(const Mesh& m, const sss::Image8& image, const std::vector<TexturedCorner>& expected) {
    REQUIRE(m.texcoords().size() == m.vertexCount());
    REQUIRE(m.baseColour());
    CHECK(m.vertexCount() == expected.size());
    for (std::size_t i = 0; i < m.vertexCount(); ++i) {
        const glm::u8vec4 read = texelAt(*m.baseColour(), m.texcoords()[i]);
        const bool found = std::any_of(expected.begin(), expected.end(), [&](const TexturedCorner& c) {
            return near(m.positions()[i], c.position) && read == image.at(c.texel.x, c.texel.y);
        });
        INFO("vertex " << i << " at (" << m.positions()[i].x << ", " << m.positions()[i].y << ", "
                       << m.positions()[i].z << ") uv (" << m.texcoords()[i].x << ", " << m.texcoords()[i].y << ")");
        CHECK(found);
    }
}

// A folded quad: triangles (1 2 3) and (1 3 4), with position 1 on a UV seam (vt 1 in the first
// triangle, vt 4 in the second). Texels: vt 1 (0, 1), vt 2 (3, 1), vt 3 (3, 0), vt 4 (1, 0),
// vt 5 (2, 1).
std::string seamObj(const sss::Image8& image, bool normals) {
    std::string obj = "mtllib quad.mtl\nv 0 0 0\nv 1 0 1\nv 1 1 0\nv 0 1 0\n";
    for (glm::ivec2 t : {glm::ivec2(0, 1), glm::ivec2(3, 1), glm::ivec2(3, 0), glm::ivec2(1, 0), glm::ivec2(2, 1)})
        obj += objUv(meshUv(image, t.x, t.y));
    if (normals) return obj + "vn 0 0 1\nusemtl skin\nf 1/1/1 2/2/1 3/3/1\nf 1/4/1 3/3/1 4/5/1\n";
    return obj + "usemtl skin\nf 1/1 2/2 3/3\nf 1/4 3/3 4/5\n";
}

const std::vector<TexturedCorner> kSeamCorners = {
    {{0, 0, 0}, {0, 1}}, {{1, 0, 1}, {3, 1}}, {{1, 1, 0}, {3, 0}}, {{0, 0, 0}, {1, 0}}, {{0, 1, 0}, {2, 1}}};

}  // namespace

TEST_CASE("Mesh::load keeps OBJ texture coordinates and the map_Kd texture of the MTL", "[mesh-formats]") {
    sss::test::TempDir dir;
    const sss::Image8 image = asymmetricTexture();
    std::filesystem::create_directories(dir.path() / "maps");
    image.savePng(dir.path() / "maps" / "skin.png");
    // Texture options before the name (tinyobjloader parses them; only the name is used), the
    // path relative to the MTL's directory.
    dir.write("quad.mtl", "newmtl skin\nKd 1 1 1\nmap_Kd -s 1 1 1 -bm 0.5 maps/skin.png\n");

    SECTION("with normals: one vertex per (position, normal, texcoord); the seam splits position 1") {
        WarningLog log;
        const Mesh m = Mesh::load(dir.write("quad.obj", seamObj(image, true)));
        CHECK(m.triangleCount() == 2);
        checkCorners(m, image, kSeamCorners);
        CHECK(sameImage(*m.baseColour(), image));
        CHECK(log.warnings.empty());
    }
    SECTION("without normals: smooth normals shared across the seam") {
        const Mesh m = Mesh::load(dir.write("quad.obj", seamObj(image, false)));
        checkCorners(m, image, kSeamCorners);
        std::vector<glm::vec3> atOrigin;
        for (std::size_t i = 0; i < m.vertexCount(); ++i)
            if (near(m.positions()[i], glm::vec3(0.0f))) atOrigin.push_back(m.normals()[i]);
        REQUIRE(atOrigin.size() == 2);
        CHECK(near(atOrigin[0], atOrigin[1]));
        // The sum over both triangles, not either triangle's own normal.
        const glm::vec3 a = glm::cross(glm::vec3(1, 0, 1), glm::vec3(1, 1, 0));
        const glm::vec3 b = glm::cross(glm::vec3(1, 1, 0), glm::vec3(0, 1, 0));
        CHECK(near(atOrigin[0], glm::normalize(a + b), 1e-4f));
    }
    SECTION("a relative path from another working directory") {
        const std::filesystem::path previous = std::filesystem::current_path();
        dir.write("quad.obj", seamObj(image, true));
        std::filesystem::current_path(dir.path().parent_path());
        const std::filesystem::path relative = dir.path().filename() / "quad.obj";
        std::shared_ptr<const sss::Image8> texture;
        CHECK_NOTHROW(texture = Mesh::load(relative).baseColour());
        std::filesystem::current_path(previous);
        REQUIRE(texture);
        CHECK(sameImage(*texture, image));
    }
}

TEST_CASE("Mesh::load keeps an OBJ's geometry when its texture cannot be used, with a warning", "[mesh-formats]") {
    sss::test::TempDir dir;
    const sss::Image8 image = asymmetricTexture();
    WarningLog log;
    SECTION("map_Kd names a missing file") {
        dir.write("quad.mtl", "newmtl skin\nmap_Kd missing.png\n");
        const auto obj = dir.write("quad.obj", seamObj(image, true));
        const Mesh m = Mesh::load(obj);
        CHECK(m.vertexCount() == 5);
        CHECK(m.texcoords().size() == 5);
        CHECK_FALSE(m.baseColour());
        REQUIRE(log.warnings.size() == 1);
        CHECK_THAT(log.warnings[0], Contains(obj.string()) && Contains((dir.path() / "quad.mtl").string()) &&
                                        Contains((dir.path() / "missing.png").string()) &&
                                        Contains("does not exist") && Contains("without a texture"));
    }
    SECTION("map_Kd names a file that is not an image") {
        dir.write("skin.png", "not a PNG at all");
        dir.write("quad.mtl", "newmtl skin\nmap_Kd skin.png\n");
        const Mesh m = Mesh::load(dir.write("quad.obj", seamObj(image, true)));
        CHECK_FALSE(m.baseColour());
        REQUIRE(log.warnings.size() == 1);
        CHECK_THAT(log.warnings[0], Contains("skin.png") && Contains("cannot decode image"));
    }
    SECTION("the MTL file is missing") {
        const auto obj = dir.write("quad.obj", seamObj(image, true));
        const Mesh m = Mesh::load(obj);
        CHECK(m.texcoords().size() == 5);
        CHECK_FALSE(m.baseColour());
        REQUIRE(log.warnings.size() == 1);
        CHECK_THAT(log.warnings[0], Contains(obj.string()) && Contains("quad.mtl") && Contains("mtllib"));
    }
    SECTION("only some face corners have texture coordinates") {
        image.savePng(dir.path() / "skin.png");
        dir.write("quad.mtl", "newmtl skin\nmap_Kd skin.png\n");
        std::string obj = seamObj(image, true);
        obj.replace(obj.find("f 1/4/1"), 7, "f 1//1");
        const auto path = dir.write("partial.obj", obj);
        const Mesh m = Mesh::load(path);
        CHECK(m.texcoords().empty());
        CHECK_FALSE(m.baseColour());
        CHECK(m.vertexCount() == 4);  // no seam without texture coordinates
        REQUIRE(log.warnings.size() == 2);
        CHECK_THAT(log.warnings[0], Contains(path.string()) && Contains("5 of its 6 face corners"));
        CHECK_THAT(log.warnings[1], Contains("skin.png") && Contains("no texture coordinates"));
    }
}

TEST_CASE("Mesh::load takes the texture on the most OBJ faces when materials name several", "[mesh-formats]") {
    sss::test::TempDir dir;
    const sss::Image8 image = asymmetricTexture();
    image.savePng(dir.path() / "b.png");
    image.flippedVertically().savePng(dir.path() / "a.png");
    dir.write("two.mtl", "newmtl a\nmap_Kd a.png\nnewmtl b\nmap_Kd b.png\nnewmtl plain\nKd 1 0 0\n");
    const std::string obj = "mtllib two.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n"
                            "usemtl a\nf 1/1 2/2 3/3\nusemtl b\nf 1/1 3/3 4/2\nf 2/1 3/2 4/3\n"
                            "usemtl plain\nf 1/1 2/2 4/3\n";
    WarningLog log;
    const Mesh m = Mesh::load(dir.write("two.obj", obj));
    REQUIRE(m.baseColour());
    CHECK(sameImage(*m.baseColour(), image));
    REQUIRE(log.warnings.size() == 1);
    CHECK_THAT(log.warnings[0], Contains("2 textures") && Contains("b.png") && Contains("on 2 faces"));
}

TEST_CASE("Mesh::load rejects bad OBJ texture coordinates naming the file and line", "[mesh-formats]") {
    sss::test::TempDir dir;
    auto rejects = [&](const std::string& name, const std::string& contents, const std::string& problem) {
        const auto path = dir.write(name, contents);
        INFO(name);
        REQUIRE_SSS_ERROR(Mesh::load(path), ErrorKind::Parse, Contains(path.string()) && Contains(problem));
    };
    const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    rejects("nan.obj", tri + "vt 0 0\nvt nan 0.5\nf 1/1 2/2 3/1\n",
            "texture coordinate 2 (line 5) has a non-finite or non-numeric value \"nan\"");
    rejects("inf.obj", tri + "vt 0 inf\nf 1/1 2/1 3/1\n", "texture coordinate 1 (line 4)");
    rejects("huge.obj", tri + "vt 0 1e39\nf 1/1 2/1 3/1\n", "texture coordinate 1 (line 4) has the value 1e39");
    rejects("range.obj", tri + "vt 0 0\nf 1/1 2/3 3/1\n",
            "face 1 references texture coordinate 3, but the file has 1 texture coordinates");
    rejects("wrap.obj", tri + "vt 0 0\nf 1/1 2/4294967297 3/1\n", "face 1 references texture coordinate 4294967297");
}

namespace {

// A glTF quad with a UV seam at the origin: vertices 0 and 3 share a position but not a texel.
// Texels (image x, y from the top): 0 (0, 0), 1 (3, 0), 2 (3, 1), 3 (1, 1), 4 (2, 0).
const glm::vec3 kGltfQuad[5] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 0, 0}, {0, 1, 0}};
const glm::ivec2 kGltfTexels[5] = {{0, 0}, {3, 0}, {3, 1}, {1, 1}, {2, 0}};

// Positions (60 bytes), UVs in glTF's convention (40), indices 0 1 2, 3 2 4 (12).
std::string gltfQuadBuffer(const sss::Image8& image) {
    Bytes b;
    for (const glm::vec3& p : kGltfQuad)
        for (int a = 0; a < 3; ++a) b.f32(p[a]);
    for (const glm::ivec2& t : kGltfTexels) {
        const glm::vec2 uv = gltfUv(image, t.x, t.y);
        b.f32(uv.x);
        b.f32(uv.y);
    }
    for (uint16_t i : {0, 1, 2, 3, 2, 4}) b.u16(i);
    return b.data;
}

// The quad with a base-colour texture; `image` is the glTF image object, extraViews more buffer
// views (the image's, in a GLB), bufferLength the buffer's size.
std::string gltfQuadJson(const std::string& bufferUri, std::size_t bufferLength, const std::string& image,
                         const std::string& extraViews = "") {
    const std::string uri = bufferUri.empty() ? "" : "\"uri\":\"" + bufferUri + "\",";
    return "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
           "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"TEXCOORD_0\":1},\"indices\":2,"
           "\"material\":0}]}],"
           "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}],"
           "\"textures\":[{\"source\":0}],\"images\":[" + image + "],"
           "\"buffers\":[{" + uri + "\"byteLength\":" + std::to_string(bufferLength) + "}],"
           "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":60},"
           "{\"buffer\":0,\"byteOffset\":60,\"byteLength\":40},"
           "{\"buffer\":0,\"byteOffset\":100,\"byteLength\":12}" + extraViews + "],"
           "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":5,\"type\":\"VEC3\","
           "\"min\":[0,0,0],\"max\":[1,1,0]},"
           "{\"bufferView\":1,\"componentType\":5126,\"count\":5,\"type\":\"VEC2\"},"
           "{\"bufferView\":2,\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\"}]}";
}

std::vector<TexturedCorner> gltfQuadCorners() {
    std::vector<TexturedCorner> corners;
    for (int i = 0; i < 5; ++i) corners.push_back({kGltfQuad[i], kGltfTexels[i]});
    return corners;
}

// Both vertices at the origin (split by the seam) have the quad's normal.
void checkGltfQuad(const Mesh& m, const sss::Image8& image) {
    CHECK(m.triangleCount() == 2);
    checkCorners(m, image, gltfQuadCorners());
    CHECK(sameImage(*m.baseColour(), image));
    for (const glm::vec3& n : m.normals()) CHECK(near(n, glm::vec3(0, 0, 1)));
}

}  // namespace

TEST_CASE("Mesh::load reads glTF texture coordinates (top-left origin) into Mesh's convention", "[mesh-formats]") {
    sss::test::TempDir dir;
    const sss::Image8 image = asymmetricTexture();
    image.savePng(dir.path() / "skin.png");
    const std::string png = readFile(dir.path() / "skin.png");
    const std::string buffer = gltfQuadBuffer(image);
    REQUIRE(buffer.size() == 112);
    const std::string base64Buffer = "data:application/octet-stream;base64," + base64(buffer);
    WarningLog log;

    SECTION(".gltf with an external PNG and a base64 buffer") {
        checkGltfQuad(Mesh::load(dir.write("quad.gltf", gltfQuadJson(base64Buffer, 112, "{\"uri\":\"skin.png\"}"))),
                      image);
        CHECK(log.warnings.empty());
    }
    SECTION(".gltf with the PNG as a data: URI") {
        const std::string uri = "{\"uri\":\"data:image/png;base64," + base64(png) + "\"}";
        checkGltfQuad(Mesh::load(dir.write("quad.gltf", gltfQuadJson(base64Buffer, 112, uri))), image);
        CHECK(log.warnings.empty());
    }
    SECTION(".glb with the PNG in a buffer view") {
        const std::string view = ",{\"buffer\":0,\"byteOffset\":112,\"byteLength\":" + std::to_string(png.size()) + "}";
        const std::string json =
            gltfQuadJson("", 112 + png.size(), "{\"bufferView\":3,\"mimeType\":\"image/png\"}", view);
        checkGltfQuad(Mesh::load(dir.write("quad.glb", glb(json, buffer + png))), image);
        CHECK(log.warnings.empty());
    }
    SECTION("a missing image: the mesh loads without it, with a warning") {
        const auto path = dir.write("quad.gltf", gltfQuadJson(base64Buffer, 112, "{\"uri\":\"gone.png\"}"));
        const Mesh m = Mesh::load(path);
        CHECK(m.texcoords().size() == 5);
        CHECK_FALSE(m.baseColour());
        REQUIRE(log.warnings.size() == 1);
        CHECK_THAT(log.warnings[0], Contains(path.string()) && Contains((dir.path() / "gone.png").string()) &&
                                        Contains("does not exist"));
    }
}

TEST_CASE("Mesh::load reads PLY texture coordinates as the file has them", "[mesh-formats]") {
    sss::test::TempDir dir;
    auto ply = [](const std::string& u, const std::string& v) {
        return "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
               "property float " + u + "\nproperty float " + v + "\n"
               "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
               "0 0 0 0.25 0.125\n1 0 0 0.75 0.125\n0 1 0 0.25 0.875\n3 0 1 2\n";
    };
    const std::vector<std::pair<std::string, std::string>> names = {{"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}};
    for (const auto& [u, v] : names) {
        INFO(u << ", " << v);
        const Mesh m = Mesh::load(dir.write("uv_" + u + ".ply", ply(u, v)));
        REQUIRE(m.texcoords().size() == 3);
        for (std::size_t i = 0; i < 3; ++i) {
            const glm::vec3 p = m.positions()[i];
            const glm::vec2 expected = p.x > 0.5f ? glm::vec2(0.75f, 0.125f)
                                                  : p.y > 0.5f ? glm::vec2(0.25f, 0.875f) : glm::vec2(0.25f, 0.125f);
            CHECK(m.texcoords()[i] == expected);
        }
        CHECK_FALSE(m.baseColour());
    }
    // No texture coordinates, no texcoords().
    CHECK(Mesh::load(dir.write("tetra.ply", kTetraPlyAscii)).texcoords().empty());

    // MeshLab names the texture in a comment; Assimp reads it as the diffuse texture.
    const sss::Image8 image = asymmetricTexture();
    image.savePng(dir.path() / "skin.png");
    std::string textured = ply("u", "v");
    textured.replace(textured.find("element vertex"), 0, "comment TextureFile skin.png\n");
    const Mesh m = Mesh::load(dir.write("textured.ply", textured));
    REQUIRE(m.baseColour());
    CHECK(sameImage(*m.baseColour(), image));
}
