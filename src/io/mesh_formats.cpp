#include "io/mesh_formats.h"

#include "core/mesh_checks.h"
#include "io/image_decoding.h"

#include "util/format.h"

#include "sss/error.h"
#include "sss/log.h"

#if SSS_WITH_ASSIMP
#include <assimp/BaseImporter.h>
#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/mesh.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#endif

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace sss::detail {
namespace {

std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

std::string_view skipSpace(std::string_view s) {
    while (!s.empty() && isSpace(s.front())) s.remove_prefix(1);
    return s;
}

std::string_view firstToken(std::string_view s) {
    s = skipSpace(s);
    std::size_t n = 0;
    while (n < s.size() && n < 64 && !isSpace(s[n])) ++n;
    return s.substr(0, n);
}

// Binary STL: an 80-byte header, a little-endian triangle count, 50 bytes per triangle. The
// header is free text (often "solid ..."), so the size is what identifies the format.
bool isBinaryStlSize(std::string_view bytes) {
    if (bytes.size() < 84) return false;
    uint32_t count = 0;
    for (int i = 3; i >= 0; --i) count = (count << 8) | static_cast<unsigned char>(bytes[80 + static_cast<std::size_t>(i)]);
    return 84 + 50 * static_cast<uint64_t>(count) == bytes.size();
}

const char* assimpHint(MeshFormat format) {
    switch (format) {
        case MeshFormat::Ply: return "ply";
        case MeshFormat::Stl: return "stl";
        case MeshFormat::Gltf: return "gltf";
        case MeshFormat::Glb: return "glb";
        case MeshFormat::Off: return "off";
        case MeshFormat::Obj: break;
    }
    return "obj";
}

bool isInRange(glm::dvec3 v) {
    const auto ok = [](double c) { return std::abs(c) <= Mesh::kMaxCoordinate; };  // false for NaN
    return ok(v.x) && ok(v.y) && ok(v.z);
}

std::string trimmed(std::string s) {
    while (!s.empty() && isSpace(s.back())) s.pop_back();
    return s;
}

#if SSS_WITH_ASSIMP
glm::dmat4 toGlm(const aiMatrix4x4& m) {
    glm::dmat4 g;
    for (unsigned r = 0; r < 4; ++r)
        for (unsigned c = 0; c < 4; ++c) g[static_cast<int>(c)][static_cast<int>(r)] = m[r][c];  // ai: row-major
    return g;
}


// A position's exact bits, and a position's with its texture coordinate's, for joining equal
// corners (smoothing).
using PositionBits = std::array<uint32_t, 3>;
using VertexBits = std::array<uint32_t, 5>;
struct BitsHash {
    template <std::size_t N>
    std::size_t operator()(const std::array<uint32_t, N>& bits) const {
        uint64_t h = 0xcbf29ce484222325ull;
        for (uint32_t b : bits) h = (h ^ b) * 0x100000001b3ull;
        return static_cast<std::size_t>(h ^ (h >> 29));
    }
};

template <std::size_t N>
std::array<uint32_t, N> bitsOf(const float (&values)[N]) {
    std::array<uint32_t, N> bits{};
    for (std::size_t i = 0; i < N; ++i) {
        const float v = values[i] + 0.0f;  // -0 becomes +0
        std::memcpy(&bits[i], &v, sizeof v);
    }
    return bits;
}

bool hasTriangles(const aiMesh& mesh) {
    for (unsigned f = 0; f < mesh.mNumFaces; ++f)
        if (mesh.mFaces[f].mNumIndices == 3) return true;
    return false;
}

// The file a material names as its base colour: glTF's baseColorTexture (BASE_COLOR; Assimp
// also lists it as DIFFUSE), else a DIFFUSE texture (PLY's "comment TextureFile"). Empty if none.
std::string baseColourTextureOf(const aiMaterial& material) {
    for (const aiTextureType type : {aiTextureType_BASE_COLOR, aiTextureType_DIFFUSE}) {
        aiString path;
        if (material.GetTextureCount(type) > 0 && material.GetTexture(type, 0, &path) == AI_SUCCESS &&
            path.length > 0)
            return path.C_Str();
    }
    return "";
}

struct Instance {
    unsigned mesh;
    glm::dmat4 transform;
    std::string node;
};

// Every (mesh, world transform) pair the node tree places, depth first. Iterative, with a cap
// on the nodes visited, so that a deep or (in a corrupt file) cyclic tree cannot exhaust the
// stack or loop forever.
std::vector<Instance> instancesOf(const aiScene& scene, const std::string& file) {
    constexpr std::size_t kMaxNodes = 1'000'000;
    std::vector<Instance> out;
    std::vector<std::pair<const aiNode*, glm::dmat4>> stack;
    if (scene.mRootNode) stack.emplace_back(scene.mRootNode, glm::dmat4(1.0));
    std::size_t visited = 0;
    while (!stack.empty()) {
        auto [node, parent] = stack.back();
        stack.pop_back();
        if (++visited > kMaxNodes)
            throw Error(ErrorKind::Parse, file + ": the scene has more than " + std::to_string(kMaxNodes) + " nodes");
        const glm::dmat4 world = parent * toGlm(node->mTransformation);
        for (unsigned i = 0; i < node->mNumMeshes; ++i)
            if (node->mMeshes && node->mMeshes[i] < scene.mNumMeshes)
                out.push_back({node->mMeshes[i], world, node->mName.C_Str()});
        for (unsigned i = node->mNumChildren; i-- > 0;)
            if (node->mChildren && node->mChildren[i]) stack.emplace_back(node->mChildren[i], world);
    }
    // Scenes whose nodes place no mesh at all (no node tree): every mesh as stored.
    if (out.empty())
        for (unsigned i = 0; i < scene.mNumMeshes; ++i) out.push_back({i, glm::dmat4(1.0), ""});
    return out;
}

#endif

// ---- structure checks run before Assimp ----------------------------------------------------
// Assimp 5.2's PLY reader loops forever on a header without "end_header" and fills a truncated
// body (ASCII or binary) with zeros or repeated vertices; its OFF reader does the same with a
// truncated file. These checks walk the declared structure first, so that such files are
// rejected with a message instead. They read counts only, never the numbers themselves (Assimp
// parses those; the values are checked afterwards).

std::vector<std::string_view> splitBlank(std::string_view line) {
    std::vector<std::string_view> out;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && isSpace(line[i])) ++i;
        const std::size_t start = i;
        while (i < line.size() && !isSpace(line[i])) ++i;
        if (i > start) out.push_back(line.substr(start, i - start));
    }
    return out;
}

// A count in a header or an ASCII list: decimal digits only, at most 2^32 - 1.
std::optional<uint64_t> parseCount(std::string_view t) {
    if (t.empty() || t.size() > 10) return std::nullopt;
    uint64_t v = 0;
    for (char c : t) {
        if (c < '0' || c > '9') return std::nullopt;
        v = v * 10 + static_cast<uint64_t>(c - '0');
    }
    if (v > std::numeric_limits<uint32_t>::max()) return std::nullopt;
    return v;
}

struct PlyProperty {
    bool list = false;
    int countSize = 0;  // list: bytes of the length
    bool countSigned = false;
    int size = 0;  // scalar, or each list item: bytes
};

struct PlyElement {
    std::string name;
    uint64_t count = 0;
    std::vector<PlyProperty> properties;
};

// Bytes of a PLY scalar type, 0 if unknown; sets isSigned.
int plyTypeSize(std::string_view t, bool& isSigned) {
    isSigned = t == "char" || t == "int8" || t == "short" || t == "int16" || t == "int" || t == "int32";
    if (t == "char" || t == "int8" || t == "uchar" || t == "uint8") return 1;
    if (t == "short" || t == "int16" || t == "ushort" || t == "uint16") return 2;
    if (t == "int" || t == "int32" || t == "uint" || t == "uint32" || t == "float" || t == "float32") return 4;
    if (t == "double" || t == "float64") return 8;
    return 0;
}

enum class PlyFormat { None, Ascii, Little, Big };

struct PlyHeader {
    PlyFormat format = PlyFormat::None;
    std::vector<PlyElement> elements;
    std::size_t bodyStart = 0;
};

// One "property ..." line of a PLY header into `p`; an error message, or empty.
std::string parsePlyProperty(const std::vector<std::string_view>& t, std::string_view line, PlyProperty& p) {
    bool itemSigned = false;
    if (t.size() == 5 && t[1] == "list") {
        p.list = true;
        p.countSize = plyTypeSize(t[2], p.countSigned);
        p.size = plyTypeSize(t[3], itemSigned);
        if (p.countSize == 0 || p.size == 0 || p.countSize == 8 || t[2] == "float" || t[2] == "float32")
            return "the PLY header has a bad list property \"" + trimmed(std::string(line)) + "\"";
        return "";
    }
    if (t.size() != 3) return "the PLY header has a bad property line \"" + trimmed(std::string(line)) + "\"";
    p.size = plyTypeSize(t[1], itemSigned);
    if (p.size == 0) return "the PLY header has an unknown property type \"" + std::string(t[1]) + "\"";
    return "";
}

// One header line after "ply"; sets `ended` at end_header. An error message, or empty.
std::string parsePlyHeaderLine(std::string_view line, PlyHeader& header, bool& ended) {
    const std::vector<std::string_view> t = splitBlank(line);
    if (t.empty() || t[0] == "comment" || t[0] == "obj_info") return "";
    if (t[0] == "end_header") {
        ended = true;
        return t.size() == 1 ? "" : "the PLY header has text after end_header on its line";
    }
    if (t[0] == "format") {
        if (t.size() < 2 || header.format != PlyFormat::None) return "the PLY header has a bad format line";
        if (t[1] == "ascii") header.format = PlyFormat::Ascii;
        else if (t[1] == "binary_little_endian") header.format = PlyFormat::Little;
        else if (t[1] == "binary_big_endian") header.format = PlyFormat::Big;
        else return "unknown PLY format \"" + std::string(t[1]) + "\"";
        return "";
    }
    if (t[0] == "element") {
        const std::optional<uint64_t> count = t.size() == 3 ? parseCount(t[2]) : std::nullopt;
        if (!count) return "the PLY header has a bad element line \"" + trimmed(std::string(line)) + "\"";
        header.elements.push_back({std::string(t[1]), *count, {}});
        return "";
    }
    if (t[0] == "property") {
        if (header.elements.empty()) return "the PLY header has a property before any element";
        PlyProperty p;
        const std::string problem = parsePlyProperty(t, line, p);
        if (problem.empty()) header.elements.back().properties.push_back(p);
        return problem;
    }
    return "the PLY header has an unknown line \"" + trimmed(std::string(line.substr(0, 80))) + "\"";
}

// The header's lines up to end_header; an error message, or empty.
std::string parsePlyHeader(std::string_view bytes, PlyHeader& header) {
    std::size_t pos = 0;
    bool first = true, ended = false;
    while (!ended) {
        const std::size_t end = pos < bytes.size() ? bytes.find('\n', pos) : std::string_view::npos;
        if (end == std::string_view::npos) return "the PLY header has no end_header line (the file is truncated)";
        std::string_view line = bytes.substr(pos, end - pos);
        pos = end + 1;
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        // Assimp splits the header differently on other control characters (and then never
        // finds end_header), so the header must be plain text.
        for (char c : line)
            if ((static_cast<unsigned char>(c) < 0x20 && c != '\t') || c == 0x7f)
                return "the PLY header has a control character (byte " + std::to_string(static_cast<unsigned char>(c)) +
                       ")";
        if (first) {
            const std::vector<std::string_view> t = splitBlank(line);
            if (t.size() != 1 || t[0] != "ply") return "the first line is not \"ply\"";
            first = false;
            continue;
        }
        const std::string problem = parsePlyHeaderLine(line, header, ended);
        if (!problem.empty()) return problem;
    }
    if (header.format == PlyFormat::None) return "the PLY header has no format line";
    header.bodyStart = std::min(pos, bytes.size());
    return "";
}

std::string plyTruncated(const PlyElement& e, uint64_t item) {
    return "the file is truncated: it ends in " + e.name + " " + std::to_string(item) + " of the " +
           std::to_string(e.count) + " the PLY header declares";
}

// An ASCII body holds every value and list item the header declares.
std::string checkPlyAsciiBody(std::string_view body, const std::vector<PlyElement>& elements) {
    std::size_t i = 0;
    auto next = [&]() -> std::optional<std::string_view> {
        while (i < body.size() && isSpace(body[i])) ++i;
        if (i >= body.size()) return std::nullopt;
        const std::size_t start = i;
        while (i < body.size() && !isSpace(body[i])) ++i;
        return body.substr(start, i - start);
    };
    for (const PlyElement& e : elements) {
        if (e.properties.empty()) continue;
        for (uint64_t item = 0; item < e.count; ++item)
            for (const PlyProperty& p : e.properties) {
                const std::optional<std::string_view> token = next();
                if (!token) return plyTruncated(e, item);
                if (!p.list) continue;
                const std::optional<uint64_t> n = parseCount(*token);
                if (!n)
                    return e.name + " " + std::to_string(item) + " has the list length \"" + std::string(*token) +
                           "\", which is not a count";
                for (uint64_t k = 0; k < *n; ++k)
                    if (!next()) return plyTruncated(e, item);
            }
    }
    return "";
}

// A binary body is long enough for what the header declares: fixed-size elements are skipped in
// one step, others item by item (each item takes at least one byte, so this is bounded by the
// file size).
std::string checkPlyBinaryBody(std::string_view body, const std::vector<PlyElement>& elements, bool big) {
    std::size_t at = 0;
    auto readCount = [&](const PlyProperty& p, uint64_t& n) {
        uint64_t v = 0;
        for (int b = 0; b < p.countSize; ++b) {
            const auto byte = static_cast<unsigned char>(body[at + static_cast<std::size_t>(big ? b : p.countSize - 1 - b)]);
            v = (v << 8) | byte;
        }
        at += static_cast<std::size_t>(p.countSize);
        if (p.countSigned && (v >> (8 * p.countSize - 1)) != 0) return false;  // negative
        n = v;
        return true;
    };
    for (const PlyElement& e : elements) {
        if (e.properties.empty()) continue;
        const bool fixed = std::none_of(e.properties.begin(), e.properties.end(), [](const PlyProperty& p) { return p.list; });
        if (fixed) {
            uint64_t stride = 0;
            for (const PlyProperty& p : e.properties) stride += static_cast<uint64_t>(p.size);
            const uint64_t left = body.size() - at;
            if (e.count > left / stride) return plyTruncated(e, left / stride);
            at += static_cast<std::size_t>(e.count * stride);
            continue;
        }
        for (uint64_t item = 0; item < e.count; ++item)
            for (const PlyProperty& p : e.properties) {
                const std::size_t need = static_cast<std::size_t>(p.list ? p.countSize : p.size);
                if (body.size() - at < need) return plyTruncated(e, item);
                if (!p.list) {
                    at += need;
                    continue;
                }
                uint64_t n = 0;
                if (!readCount(p, n)) return e.name + " " + std::to_string(item) + " has a negative list length";
                if (n > (body.size() - at) / static_cast<uint64_t>(p.size)) return plyTruncated(e, item);
                at += static_cast<std::size_t>(n) * static_cast<std::size_t>(p.size);
            }
    }
    return "";
}

// An empty string if the PLY file's header is complete and its body holds every item the
// header declares; else what is wrong.
std::string checkPlyStructure(std::string_view bytes) {
    PlyHeader header;
    if (std::string problem = parsePlyHeader(bytes, header); !problem.empty()) return problem;
    const std::string_view body = bytes.substr(header.bodyStart);
    if (header.format == PlyFormat::Ascii) return checkPlyAsciiBody(body, header.elements);
    return checkPlyBinaryBody(body, header.elements, header.format == PlyFormat::Big);
}

// An empty string unless the STL file is neither ASCII (text starting with "solid") nor a
// binary STL of exactly the size its triangle count gives: Assimp would read a truncated
// binary file whose header starts with "solid" as an empty ASCII one.
std::string checkStlStructure(std::string_view bytes) {
    if (isBinaryStlSize(bytes)) return "";
    const bool text = bytes.find('\0') == std::string_view::npos && lower(std::string(firstToken(bytes))) == "solid";
    if (text) return "";
    if (bytes.size() < 84)
        return "is too short for a binary STL (" + std::to_string(bytes.size()) + " bytes; the header alone has 84)";
    uint32_t count = 0;
    for (int i = 3; i >= 0; --i) count = (count << 8) | static_cast<unsigned char>(bytes[80 + static_cast<std::size_t>(i)]);
    return "the file is truncated or has extra bytes: a binary STL of the " + std::to_string(count) +
           " triangles its header declares has " + std::to_string(84 + 50 * static_cast<uint64_t>(count)) +
           " bytes, this file " + std::to_string(bytes.size());
}

uint32_t le32(std::string_view b, std::size_t at) {
    uint32_t v = 0;
    for (int i = 3; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(b[at + static_cast<std::size_t>(i)]);
    return v;
}

// An empty string if the GLB container's lengths agree with the file: Assimp allocates what
// the header declares before reading (4 GiB for a corrupt length field).
std::string checkGlbStructure(std::string_view bytes) {
    if (bytes.size() < 20 || bytes.substr(0, 4) != "glTF") return "is not a GLB file (no glTF header)";
    if (le32(bytes, 4) != 2) return "is a GLB of version " + std::to_string(le32(bytes, 4)) + "; only glTF 2.0 is read";
    if (le32(bytes, 8) != bytes.size())
        return "the GLB header declares " + std::to_string(le32(bytes, 8)) + " bytes, but the file has " +
               std::to_string(bytes.size()) + " (truncated or corrupt)";
    for (std::size_t at = 12; at < bytes.size();) {
        if (bytes.size() - at < 8) return "the GLB file ends inside a chunk header";
        const uint64_t length = le32(bytes, at);
        if (length > bytes.size() - at - 8)
            return "a GLB chunk declares " + std::to_string(length) + " bytes, past the end of the file";
        at += 8 + static_cast<std::size_t>(length);
    }
    return "";
}

// The header token of an OFF file Assimp reads: [ST][C][N]OFF.
bool isOffHeaderToken(std::string_view t) {
    if (t.substr(0, 2) == "ST") t.remove_prefix(2);
    if (!t.empty() && t.front() == 'C') t.remove_prefix(1);
    if (!t.empty() && t.front() == 'N') t.remove_prefix(1);
    return t == "OFF";
}

// An empty string if the OFF file holds the vertex and face lines its counts declare.
std::string checkOffStructure(std::string_view bytes) {
    std::vector<std::vector<std::string_view>> lines;  // non-empty, comments removed
    std::size_t pos = 0;
    while (pos < bytes.size()) {
        std::size_t end = bytes.find_first_of("\r\n", pos);
        if (end == std::string_view::npos) end = bytes.size();
        std::string_view line = bytes.substr(pos, end - pos);
        pos = end + 1;
        line = line.substr(0, line.find('#'));
        std::vector<std::string_view> t = splitBlank(line);
        if (!t.empty()) lines.push_back(std::move(t));
    }
    if (lines.empty() || !isOffHeaderToken(lines[0][0])) return "the first line is not an OFF header";
    std::size_t next = 1;
    std::vector<std::string_view> counts(lines[0].begin() + 1, lines[0].end());
    if (counts.empty()) {
        if (lines.size() < 2) return "the file is truncated: it has no vertex and face counts";
        counts = lines[next++];
    }
    const std::optional<uint64_t> nv = parseCount(counts[0]);
    const std::optional<uint64_t> nf = counts.size() >= 2 ? parseCount(counts[1]) : std::nullopt;
    if (!nv || !nf) return "the OFF counts line is not \"vertices faces [edges]\"";
    if (lines.size() - next < *nv)
        return "the file is truncated: it has " + std::to_string(lines.size() - next) + " of the " +
               std::to_string(*nv) + " vertex lines the header declares";
    for (uint64_t v = 0; v < *nv; ++v, ++next)
        if (lines[next].size() < 3) return "vertex " + std::to_string(v) + " has fewer than 3 coordinates";
    if (lines.size() - next < *nf)
        return "the file is truncated: it has " + std::to_string(lines.size() - next) + " of the " +
               std::to_string(*nf) + " face lines the header declares";
    for (uint64_t f = 0; f < *nf; ++f, ++next) {
        const std::optional<uint64_t> k = parseCount(lines[next][0]);
        if (!k || lines[next].size() - 1 < *k)
            return "face " + std::to_string(f) + " does not list the number of vertices it declares";
        // Assimp drops such faces (and with a zero count reads past its face array).
        if (*k == 0 || *k > 9)
            return "face " + std::to_string(f) + " has " + std::to_string(*k) +
                   " vertices; the OFF reader (Assimp) takes faces of 1 to 9";
        // Assimp replaces an index out of range by the last vertex, without an error.
        for (uint64_t c = 1; c <= *k; ++c) {
            const std::optional<uint64_t> index = parseCount(lines[next][c]);
            if (!index || *index >= *nv)
                return "face " + std::to_string(f) + " references vertex " + std::string(lines[next][c]) +
                       ", but the file has " + std::to_string(*nv) + " vertices";
        }
    }
    return "";
}

}  // namespace

const char* meshFormatName(MeshFormat format) {
    switch (format) {
        case MeshFormat::Obj: return "OBJ";
        case MeshFormat::Ply: return "PLY";
        case MeshFormat::Stl: return "STL";
        case MeshFormat::Gltf: return "glTF";
        case MeshFormat::Glb: return "GLB";
        case MeshFormat::Off: return "OFF";
    }
    return "mesh";
}

std::optional<MeshFormat> meshFormatFromExtension(const std::filesystem::path& path) {
    const std::string ext = lower(path.extension().string());
    if (ext == ".obj") return MeshFormat::Obj;
    if (ext == ".ply") return MeshFormat::Ply;
    if (ext == ".stl") return MeshFormat::Stl;
    if (ext == ".gltf") return MeshFormat::Gltf;
    if (ext == ".glb") return MeshFormat::Glb;
    if (ext == ".off") return MeshFormat::Off;
    return std::nullopt;
}

std::optional<MeshFormat> sniffMeshFormat(std::string_view bytes, bool weakToo) {
    if (bytes.size() >= 4 && bytes.substr(0, 3) == "ply" && (bytes[3] == '\n' || bytes[3] == '\r'))
        return MeshFormat::Ply;
    if (bytes.size() >= 12 && bytes.substr(0, 4) == "glTF") return MeshFormat::Glb;
    const std::string_view token = firstToken(bytes);
    if (isOffHeaderToken(token)) return MeshFormat::Off;
    if (!weakToo) return std::nullopt;
    if (isBinaryStlSize(bytes)) return MeshFormat::Stl;
    if (lower(std::string(token)) == "solid") return MeshFormat::Stl;
    const std::string_view text = skipSpace(bytes);
    if (!text.empty() && text.front() == '{' && text.find("\"asset\"") != std::string_view::npos)
        return MeshFormat::Gltf;
    return std::nullopt;
}

MeshFormat chooseMeshFormat(const std::filesystem::path& path, std::string_view bytes) {
    const std::optional<MeshFormat> byExtension = meshFormatFromExtension(path);
    if (!byExtension) return sniffMeshFormat(bytes, true).value_or(MeshFormat::Obj);
    // A binary STL header is free text and could start like anything.
    if (*byExtension == MeshFormat::Stl && isBinaryStlSize(bytes)) return MeshFormat::Stl;
    const std::optional<MeshFormat> byContent = sniffMeshFormat(bytes, false);
    if (!byContent || *byContent == *byExtension) return *byExtension;
    // Assimp reads both glTF forms whatever the extension.
    if (*byExtension == MeshFormat::Gltf && *byContent == MeshFormat::Glb) return MeshFormat::Glb;
    log(LogLevel::Warning, path.string() + ": the content is " + meshFormatName(*byContent) +
                               ", not what the extension says; reading it as " + meshFormatName(*byContent));
    return *byContent;
}

std::vector<glm::vec3> smoothNormalsPerPosition(const std::vector<glm::vec3>& positions,
                                                const std::vector<uint32_t>& indices,
                                                const std::vector<uint32_t>& position, std::size_t positionCount,
                                                glm::vec3 centre) {
    std::vector<glm::vec3> shared(positionCount, centre);  // positions no vertex uses: never read
    for (std::size_t i = 0; i < positions.size(); ++i) shared[position[i]] = positions[i];
    std::vector<uint32_t> sharedIndices(indices.size());
    for (std::size_t k = 0; k < indices.size(); ++k) sharedIndices[k] = position[indices[k]];
    const std::vector<glm::vec3> normals = smoothNormals(shared, sharedIndices, centre);
    std::vector<glm::vec3> out(positions.size());
    for (std::size_t i = 0; i < positions.size(); ++i) out[i] = normals[position[i]];
    return out;
}

#if SSS_WITH_ASSIMP

namespace {

// One file through Assimp: the structure checks, the read, the checks Mesh::load promises, the
// post-processing and the merge of every placed mesh into one. Messages start with the file.
class AssimpReader {
public:
    AssimpReader(const std::filesystem::path& path, std::string_view bytes, MeshFormat format)
        : m_path(path), m_file(path.string()), m_name(meshFormatName(format)), m_bytes(bytes), m_format(format) {}

    LoadedMesh read() {
        if (skipSpace(m_bytes).empty()) fail("has no triangles (the file is empty)");
        checkStructure();
        readScene();
        checkMeshes();
        postProcess();
        const std::vector<Instance> instances = instancesOf(*m_scene, m_file);
        m_smooth = needsSmoothNormals(instances);
        m_keepTexcoords = allHaveTexcoords(instances);
        for (const Instance& instance : instances) merge(instance);
        return {finish(), baseColour(instances)};
    }

private:
    [[noreturn]] void fail(const std::string& what) const { throw Error(ErrorKind::Parse, m_file + ": " + what); }
    void warn(const std::string& what) const { log(LogLevel::Warning, m_file + ": " + what); }
    std::string where(unsigned m) const {
        return m_scene->mNumMeshes > 1 ? "mesh " + std::to_string(m) + " " : std::string();
    }

    // What Assimp would crash or hang on, found first (tests/fuzz).
    void checkStructure() const {
        std::string problem;
        if (m_format == MeshFormat::Ply) problem = checkPlyStructure(m_bytes);
        if (m_format == MeshFormat::Off) problem = checkOffStructure(m_bytes);
        if (m_format == MeshFormat::Glb || (m_format == MeshFormat::Gltf && m_bytes.substr(0, 4) == "glTF"))
            problem = checkGlbStructure(m_bytes);
        if (m_format == MeshFormat::Stl) problem = checkStlStructure(m_bytes);
        if (!problem.empty()) fail(problem);
    }

    // Where the readers of a file's extension all decline it, Assimp tries every other reader
    // whose signature test matches (a ".gltf" that was not JSON went to the PLY reader, which
    // hung on it: tests/fuzz). Only the chosen format's readers stay registered, so the
    // structure checks above cover whatever reads the file. Assimp does not delete readers it
    // no longer holds; m_otherReaders does.
    void keepOnlyReadersOfFormat() {
        for (std::size_t i = m_importer.GetImporterCount(); i-- > 0;) {
            Assimp::BaseImporter* reader = m_importer.GetImporter(i);
            std::set<std::string> extensions;
            reader->GetExtensionList(extensions);
            if (extensions.count(assimpHint(m_format)) > 0) continue;
            if (m_importer.UnregisterLoader(reader) == aiReturn_SUCCESS) m_otherReaders.emplace_back(reader);
        }
    }

    // From the path where Assimp's choice by extension agrees (glTF buffers beside the file are
    // found then); from memory with a hint otherwise.
    void readScene() {
        keepOnlyReadersOfFormat();
        try {
            const std::optional<MeshFormat> byExtension = meshFormatFromExtension(m_path);
            const bool gltfEither = (m_format == MeshFormat::Gltf || m_format == MeshFormat::Glb) &&
                                    (byExtension == MeshFormat::Gltf || byExtension == MeshFormat::Glb);
            if (byExtension == m_format || gltfEither)
                m_scene = m_importer.ReadFile(m_file, 0);
            else
                m_scene = m_importer.ReadFileFromMemory(m_bytes.data(), m_bytes.size(), 0, assimpHint(m_format));
        } catch (const std::exception& e) {
            fail("cannot read " + m_name + " (Assimp): " + e.what());
        }
        if (!m_scene) fail("cannot read " + m_name + " (Assimp): " + trimmed(m_importer.GetErrorString()));
    }

    // The checks Mesh::load promises, on the meshes as read and before any post-processing step
    // (which would index out of range or hash NaNs). Vertices and faces are numbered from 0
    // within each mesh, as Assimp stores them; "mesh M" is named only when there are several.
    void checkMeshes() const {
        for (unsigned m = 0; m < m_scene->mNumMeshes; ++m) {
            const aiMesh* mesh = m_scene->mMeshes ? m_scene->mMeshes[m] : nullptr;
            if (!mesh) fail("mesh " + std::to_string(m) + " is missing");
            if ((mesh->mNumVertices > 0 && !mesh->mVertices) || (mesh->mNumFaces > 0 && !mesh->mFaces))
                fail(where(m) + "has no vertex or face data");
            for (unsigned v = 0; v < mesh->mNumVertices; ++v) checkVertex(m, v, mesh->mVertices[v]);
            if (mesh->mTextureCoords[0])
                for (unsigned v = 0; v < mesh->mNumVertices; ++v) checkTexcoord(m, v, mesh->mTextureCoords[0][v]);
            for (unsigned f = 0; f < mesh->mNumFaces; ++f) checkFace(m, f, mesh->mFaces[f], mesh->mNumVertices);
        }
    }

    void checkVertex(unsigned m, unsigned v, const aiVector3D& p) const {
        const glm::dvec3 d(p.x, p.y, p.z);
        if (!std::isfinite(d.x) || !std::isfinite(d.y) || !std::isfinite(d.z))
            fail(where(m) + "vertex " + std::to_string(v) + " has a non-finite coordinate " +
                 formatVec(glm::vec3(p.x, p.y, p.z)));
        if (!isInRange(d))
            fail(where(m) + "vertex " + std::to_string(v) + " has a coordinate " + formatVec(glm::vec3(p.x, p.y, p.z)) +
                 " outside the supported range [-1e18, 1e18]");
    }

    void checkTexcoord(unsigned m, unsigned v, const aiVector3D& uv) const {
        if (!std::isfinite(uv.x) || !std::isfinite(uv.y))
            fail(where(m) + "vertex " + std::to_string(v) + " has a non-finite texture coordinate (" +
                 formatNumber(uv.x) + ", " + formatNumber(uv.y) + ")");
    }

    void checkFace(unsigned m, unsigned f, const aiFace& face, unsigned vertexCount) const {
        // Assimp's triangulation aborts on empty faces (an ai_assert in Debian's build).
        if (face.mNumIndices == 0 || !face.mIndices) fail(where(m) + "face " + std::to_string(f) + " has no vertices");
        for (unsigned k = 0; k < face.mNumIndices; ++k)
            if (face.mIndices[k] >= vertexCount)
                fail(where(m) + "face " + std::to_string(f) + " references vertex " + std::to_string(face.mIndices[k]) +
                     ", but the mesh has " + std::to_string(vertexCount) + " vertices");
    }

    // STL facet normals are per face (flat shading) and often zero: they are dropped, and the
    // corners of adjacent facets are joined, so that the mesh gets smooth normals like an OBJ
    // without normals.
    void postProcess() {
        unsigned steps = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices;
        if (m_format == MeshFormat::Stl) {
            m_importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS, aiComponent_NORMALS);
            steps |= aiProcess_RemoveComponent;
        }
        try {
            m_scene = m_importer.ApplyPostProcessing(steps);
        } catch (const std::exception& e) {
            fail("cannot process " + m_name + " (Assimp): " + e.what());
        }
        if (!m_scene) fail("cannot process " + m_name + " (Assimp): " + trimmed(m_importer.GetErrorString()));
    }

    // File normals are used only if every placed mesh with triangles has usable ones, as for
    // OBJ; otherwise the whole mesh gets smooth area-weighted normals. Counts the points and
    // lines on the way.
    bool needsSmoothNormals(const std::vector<Instance>& instances) {
        bool smooth = false;
        for (const Instance& instance : instances) {
            const aiMesh* mesh = m_scene->mMeshes[instance.mesh];
            if (!mesh || !mesh->mFaces) continue;
            bool hasTriangles = false;
            for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
                if (mesh->mFaces[f].mNumIndices == 3)
                    hasTriangles = true;
                else
                    ++m_pointsAndLines;
            }
            if (!hasTriangles) continue;
            if (!mesh->mNormals) {
                smooth = true;
                continue;
            }
            for (unsigned v = 0; v < mesh->mNumVertices && !smooth; ++v) {
                const aiVector3D& n = mesh->mNormals[v];
                if (!isUsableNormal(glm::vec3(n.x, n.y, n.z))) smooth = true;
            }
        }
        return smooth;
    }

    // Texture coordinates (the first UV channel) are kept when every placed mesh with triangles
    // has them; a mesh has them on every vertex or on none.
    bool allHaveTexcoords(const std::vector<Instance>& instances) const {
        std::size_t meshes = 0, withTexcoords = 0;
        for (const Instance& instance : instances) {
            const aiMesh* mesh = m_scene->mMeshes[instance.mesh];
            if (!mesh || !mesh->mFaces || !hasTriangles(*mesh)) continue;
            ++meshes;
            if (mesh->mTextureCoords[0]) ++withTexcoords;
        }
        if (withTexcoords > 0 && withTexcoords < meshes)
            warn(std::to_string(withTexcoords) + " of its " + std::to_string(meshes) +
                 " placed meshes have texture coordinates; they are kept only when every mesh has them, so the "
                 "mesh has none");
        return meshes > 0 && withTexcoords == meshes;
    }

    // When smoothing, corners at the same position (and texture coordinate) share one vertex
    // across meshes, so there are no seams in the normals; m_position numbers each vertex's
    // position, so that vertices split by a texture seam get one normal.
    uint32_t weld(glm::vec3 p, glm::vec2 uv) {
        const PositionBits position = bitsOf({p.x, p.y, p.z});
        const VertexBits key = bitsOf({p.x, p.y, p.z, uv.x, uv.y});
        auto [it, inserted] = m_welded.try_emplace(key, static_cast<uint32_t>(m_positions.size()));
        if (!inserted) return it->second;
        m_positions.push_back(p + glm::vec3(0.0f));  // -0 becomes +0
        if (m_keepTexcoords) m_texcoords.push_back(uv);
        m_position.push_back(m_positionIds.try_emplace(position, static_cast<uint32_t>(m_positionIds.size())).first->second);
        return it->second;
    }

    // One placed mesh into the merged arrays, in world space (its node's transform applied).
    void merge(const Instance& instance) {
        const bool smooth = m_smooth;
        const aiMesh* mesh = m_scene->mMeshes[instance.mesh];
        if (!mesh || !mesh->mFaces || !mesh->mVertices) return;
        const glm::dmat3 linear(instance.transform);
        const double det = glm::determinant(linear);
        if (!std::isfinite(det)) fail("node \"" + instance.node + "\" has a non-finite transform");
        if (det == 0.0) {  // a zero scale hides the node; its triangles would all be degenerate
            ++m_skippedInstances;
            return;
        }
        const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(linear));
        std::vector<uint32_t> remap(mesh->mNumVertices, std::numeric_limits<uint32_t>::max());
        auto vertex = [&](unsigned v) -> uint32_t {
            if (!smooth && remap[v] != std::numeric_limits<uint32_t>::max()) return remap[v];
            const aiVector3D& a = mesh->mVertices[v];
            const glm::dvec3 p = glm::dvec3(instance.transform * glm::dvec4(a.x, a.y, a.z, 1.0));
            if (!isInRange(p))
                fail(where(instance.mesh) + "vertex " + std::to_string(v) + " lies at " + formatVec(p) +
                     " after the transform of node \"" + instance.node +
                     "\": non-finite or outside the supported range [-1e18, 1e18]");
            if (m_positions.size() >= std::numeric_limits<uint32_t>::max())
                fail("has more vertices than 32-bit indices can address");
            const glm::vec2 uv = m_keepTexcoords ? glm::vec2(mesh->mTextureCoords[0][v].x, mesh->mTextureCoords[0][v].y)
                                                 : glm::vec2(0.0f);
            if (smooth) return weld(glm::vec3(p), uv);
            const aiVector3D& an = mesh->mNormals[v];
            const glm::dvec3 n = normalMatrix * glm::dvec3(an.x, an.y, an.z);
            const double largest = std::max({std::abs(n.x), std::abs(n.y), std::abs(n.z)});
            remap[v] = static_cast<uint32_t>(m_positions.size());
            m_positions.emplace_back(p);
            m_normals.emplace_back(n / largest);  // scaled so that float keeps it usable
            if (m_keepTexcoords) m_texcoords.push_back(uv);
            return remap[v];
        };
        for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
            const aiFace& face = mesh->mFaces[f];
            if (face.mNumIndices != 3) continue;
            const uint32_t a = vertex(face.mIndices[0]), b = vertex(face.mIndices[1]), c = vertex(face.mIndices[2]);
            if (m_indices.size() > std::numeric_limits<std::size_t>::max() / 2) fail("has too many triangles");
            m_indices.push_back(a);
            // A mirroring transform turns counter-clockwise triangles clockwise; undo it.
            m_indices.push_back(det < 0.0 ? c : b);
            m_indices.push_back(det < 0.0 ? b : c);
        }
    }

    Mesh finish() {
        if (m_pointsAndLines > 0)
            log(LogLevel::Warning, m_file + ": ignored " + std::to_string(m_pointsAndLines) +
                                       " point and line primitives (only triangles are rendered)");
        if (m_skippedInstances > 0)
            log(LogLevel::Warning, m_file + ": skipped " + std::to_string(m_skippedInstances) +
                                       " mesh placements whose node transform is singular (zero scale)");
        if (m_indices.empty())
            fail(m_pointsAndLines > 0 ? "has no triangles, only " + std::to_string(m_pointsAndLines) + " points and lines"
                                      : "has no triangles");
        if (m_smooth)
            m_normals = smoothNormalsPerPosition(m_positions, m_indices, m_position, m_positionIds.size(),
                                                 boundsOf(m_positions).center());
        try {
            return Mesh::fromArrays(std::move(m_positions), std::move(m_indices), std::move(m_normals), m_file,
                                    std::move(m_texcoords));
        } catch (const Error& e) {
            throw Error(ErrorKind::Parse, e.what());  // the message already starts with the file
        }
    }

    // The base-colour texture of the materials the placed meshes use. A Mesh has one texture:
    // when they use several, the one on the most triangles is taken (the first on a tie).
    std::shared_ptr<const Image8> baseColour(const std::vector<Instance>& instances) const {
        std::vector<std::pair<std::string, std::size_t>> uses;  // texture, triangles
        for (const Instance& instance : instances) {
            const std::string texture = textureOfMesh(instance.mesh);
            if (texture.empty()) continue;
            auto it = std::find_if(uses.begin(), uses.end(), [&](const auto& use) { return use.first == texture; });
            if (it == uses.end()) it = uses.insert(uses.end(), {texture, 0});
            it->second += triangleCount(*m_scene->mMeshes[instance.mesh]);
        }
        if (uses.empty()) return nullptr;
        auto best = uses.begin();
        for (auto it = uses.begin(); it != uses.end(); ++it)
            if (it->second > best->second) best = it;
        const std::string context = "base-colour texture \"" + best->first + "\"";
        if (uses.size() > 1)
            warn("its meshes use " + std::to_string(uses.size()) + " base-colour textures, but a mesh has one; only " +
                 context + " (on " + std::to_string(best->second) + " triangles) is used");
        if (!m_keepTexcoords) {
            warn(context + " is not used: the mesh has no texture coordinates");
            return nullptr;
        }
        return loadTexture(best->first, m_file + ": " + context);
    }

    std::string textureOfMesh(unsigned m) const {
        const aiMesh* mesh = m_scene->mMeshes[m];
        if (!mesh || !mesh->mFaces || !hasTriangles(*mesh) || !m_scene->mMaterials ||
            mesh->mMaterialIndex >= m_scene->mNumMaterials)
            return "";
        const aiMaterial* material = m_scene->mMaterials[mesh->mMaterialIndex];
        return material ? baseColourTextureOf(*material) : "";
    }

    static std::size_t triangleCount(const aiMesh& mesh) {
        std::size_t n = 0;
        for (unsigned f = 0; f < mesh.mNumFaces; ++f) n += mesh.mFaces[f].mNumIndices == 3 ? 1 : 0;
        return n;
    }

    // "*N" names the scene's embedded texture N (a GLB buffer view or a data: URI, as the image
    // file's bytes); any other name is a file relative to the mesh file's directory.
    std::shared_ptr<const Image8> loadTexture(const std::string& name, const std::string& context) const {
        if (name.front() != '*') return loadTextureOrWarn(m_path.parent_path() / name, context);
        const std::optional<uint64_t> index = parseCount(std::string_view(name).substr(1));
        const aiTexture* texture =
            index && *index < m_scene->mNumTextures && m_scene->mTextures ? m_scene->mTextures[*index] : nullptr;
        std::string problem;
        if (!texture || !texture->pcData) problem = "the file has no such embedded texture";
        else if (texture->mHeight != 0) problem = "it is stored as raw pixels, which libsss does not read";
        if (!problem.empty()) {
            log(LogLevel::Warning, context + ": " + problem + "; the mesh loads without a texture");
            return nullptr;
        }
        const std::string_view bytes(reinterpret_cast<const char*>(texture->pcData), texture->mWidth);
        return decodeTextureOrWarn(bytes, m_file + " (embedded texture " + name + ")", context);
    }

    const std::filesystem::path& m_path;
    std::string m_file, m_name;
    std::string_view m_bytes;
    MeshFormat m_format;
    Assimp::Importer m_importer;
    std::vector<std::unique_ptr<Assimp::BaseImporter>> m_otherReaders;  // unregistered from m_importer
    const aiScene* m_scene = nullptr;
    bool m_smooth = false, m_keepTexcoords = false;
    std::vector<glm::vec3> m_positions, m_normals;
    std::vector<glm::vec2> m_texcoords;
    std::vector<uint32_t> m_indices;
    std::vector<uint32_t> m_position;  // when smoothing: each vertex's position, numbered by m_positionIds
    std::unordered_map<VertexBits, uint32_t, BitsHash> m_welded;
    std::unordered_map<PositionBits, uint32_t, BitsHash> m_positionIds;
    std::size_t m_pointsAndLines = 0, m_skippedInstances = 0;
};

}  // namespace

LoadedMesh loadMeshWithAssimp(const std::filesystem::path& path, std::string_view bytes, MeshFormat format) {
    return AssimpReader(path, bytes, format).read();
}

#else

LoadedMesh loadMeshWithAssimp(const std::filesystem::path& path, std::string_view, MeshFormat format) {
    throw Error(ErrorKind::Unsupported, path.string() + ": " + meshFormatName(format) +
                                            " files need libsss built with SSS_WITH_ASSIMP=ON (libassimp-dev)");
}

#endif

}  // namespace sss::detail
