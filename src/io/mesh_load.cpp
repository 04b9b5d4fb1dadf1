// Mesh::load (declared in sss/mesh.h, built in the io component): OBJ through tinyobjloader,
// the other formats through io/mesh_formats.h.
#include "sss/mesh.h"

#include "core/mesh_checks.h"
#include "io/image_decoding.h"
#include "io/mesh_formats.h"
#include "util/format.h"

#include "sss/error.h"
#include "sss/log.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <string_view>
#include <unordered_map>
#include <utility>

namespace sss {
namespace {

using detail::boundsOf;
using detail::isInRange;
using detail::isUsableNormal;
using detail::unitNormal;

std::string str(glm::vec3 v) { return detail::formatVec(v); }

std::string trimmed(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ' || s.back() == '\t')) s.pop_back();
    return s;
}

// The part of a line after leading blanks, and the lines of a file split at "\n", "\r\n" and a
// lone "\r" (old Mac files), as tinyobjloader splits them.
std::vector<std::string_view> objLines(std::string_view text) {
    std::vector<std::string_view> lines;
    std::size_t begin = 0;
    for (std::size_t i = 0; i <= text.size(); ++i) {
        if (i < text.size() && text[i] != '\n' && text[i] != '\r') continue;
        std::string_view line = text.substr(begin, i - begin);
        while (!line.empty() && (line.front() == ' ' || line.front() == '\t')) line.remove_prefix(1);
        lines.push_back(line);
        if (i + 1 < text.size() && text[i] == '\r' && text[i + 1] == '\n') ++i;
        begin = i + 1;
    }
    return lines;
}

std::vector<std::string_view> tokens(std::string_view line) {
    std::vector<std::string_view> out;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
        const std::size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
        if (i > start) out.push_back(line.substr(start, i - start));
    }
    return out;
}

// A decimal number as tinyobjloader reads it: [+-] digits [. digits] [(e|E) [+-] digits], with
// digits on at least one side of the point. Everything else ("nan", "inf", hex floats, "1,5")
// it would read as 0 without a word, so such files are rejected here.
bool isDecimalNumber(std::string_view t) {
    std::size_t i = 0;
    auto digits = [&] {
        const std::size_t start = i;
        while (i < t.size() && t[i] >= '0' && t[i] <= '9') ++i;
        return i - start;
    };
    if (i < t.size() && (t[i] == '+' || t[i] == '-')) ++i;
    std::size_t mantissa = digits();
    if (i < t.size() && t[i] == '.') {
        ++i;
        mantissa += digits();
    }
    if (mantissa == 0) return false;
    if (i < t.size() && (t[i] == 'e' || t[i] == 'E')) {
        ++i;
        if (i < t.size() && (t[i] == '+' || t[i] == '-')) ++i;
        if (digits() == 0) return false;
    }
    return i == t.size();
}

// Blanks "vw" (vertex weight) lines in place, keeping the line numbers of tinyobjloader's
// messages. libsss does not use skin weights, and tinyobjloader converts their joint ids from
// float to int without a range check (undefined behaviour, found by tests/fuzz).
void blankVertexWeights(std::string& text) {
    std::size_t i = 0;
    while (i < text.size()) {
        std::size_t start = i;
        while (start < text.size() && (text[start] == ' ' || text[start] == '\t')) ++start;
        std::size_t end = start;
        while (end < text.size() && text[end] != '\n' && text[end] != '\r') ++end;
        if (end - start >= 3 && text[start] == 'v' && text[start + 1] == 'w' &&
            (text[start + 2] == ' ' || text[start + 2] == '\t'))
            std::fill(text.begin() + static_cast<std::ptrdiff_t>(start), text.begin() + static_cast<std::ptrdiff_t>(end), ' ');
        i = end + 1;
    }
}

struct ObjTextCheck {
    std::string error;  // empty if none
    std::size_t shortFaces = 0, firstShortFace = 0;  // faces of fewer than 3 vertices (dropped)
};

// Counts of the attribute lines read so far, for messages about indices.
struct ObjCounts {
    std::size_t vertices = 0, texcoords = 0, normals = 0, faces = 0;
};

// A vertex coordinate: a decimal number within Mesh::kMaxCoordinate; an error message, or empty.
std::string checkVertexCoordinate(std::size_t vertex, std::string_view t) {
    const std::string token(t);
    if (!isDecimalNumber(token))
        return "vertex " + std::to_string(vertex) + " has a non-finite or non-numeric coordinate \"" + token + "\"";
    // Compared as stored: in float.
    const double value = std::strtod(token.c_str(), nullptr);
    if (!(std::abs(static_cast<float>(value)) <= Mesh::kMaxCoordinate))
        return "vertex " + std::to_string(vertex) + " has the coordinate " + token + ", which is " +
               (std::isfinite(value) ? "outside" : "non-finite in double, outside") +
               " the supported range [-1e18, 1e18]";
    return "";
}

// A "vt" line: u and v (w is not used) decimal numbers, finite in float; an error, or empty.
std::string checkTexcoordLine(std::size_t texcoord, std::size_t lineNumber, std::string_view rest) {
    const std::vector<std::string_view> t = tokens(rest);
    for (std::size_t k = 0; k < std::min<std::size_t>(t.size(), 2); ++k) {
        const std::string token(t[k]);
        const std::string which =
            "texture coordinate " + std::to_string(texcoord) + " (line " + std::to_string(lineNumber) + ")";
        if (!isDecimalNumber(token)) return which + " has a non-finite or non-numeric value \"" + token + "\"";
        if (!std::isfinite(static_cast<float>(std::strtod(token.c_str(), nullptr))))
            return which + " has the value " + token + ", which is beyond the range of float";
    }
    return "";
}

// What a face corner's index refers to, for messages.
struct IndexKind {
    const char* one;
    const char* many;
};
constexpr IndexKind kCornerKinds[3] = {
    {"vertex", "vertices"}, {"texture coordinate", "texture coordinates"}, {"normal", "normals"}};

// One index of a face corner ("v", "vt" or "vn" part): an integer that fits tinyobjloader's int,
// which would otherwise wrap it (silently, into another index). An error message, or empty.
std::string checkCornerIndex(std::size_t face, std::string_view part, const IndexKind& kind, std::size_t count) {
    const std::string index(part);
    char* end = nullptr;
    errno = 0;
    const long long v = std::strtoll(index.c_str(), &end, 10);
    if (index.empty() || *end != '\0')
        return "face " + std::to_string(face) + " has the " + kind.one + " index \"" + index +
               "\", which is not an integer";
    if (errno == ERANGE || v > std::numeric_limits<int>::max() ||
        v < -static_cast<long long>(std::numeric_limits<int>::max()))
        return "face " + std::to_string(face) + " references " + kind.one + " " + index + ", but the file has " +
               std::to_string(count) + " " + (count == 1 ? kind.one : kind.many) + " before it";
    return "";
}

// A face corner "v", "v/vt", "v//vn" or "v/vt/vn"; empty vt and vn parts are left to tinyobjloader.
std::string checkCorner(std::string_view corner, const ObjCounts& counts) {
    const std::size_t count[3] = {counts.vertices, counts.texcoords, counts.normals};
    for (std::size_t k = 0; k < 3; ++k) {
        const std::size_t slash = corner.find('/');
        const std::string_view part = corner.substr(0, slash);
        if (k == 0 || !part.empty()) {
            std::string problem = checkCornerIndex(counts.faces, part, kCornerKinds[k], count[k]);
            if (!problem.empty()) return problem;
        }
        if (slash == std::string_view::npos) break;
        corner.remove_prefix(slash + 1);
    }
    return "";
}

// A line that starts with `keyword` and a blank, as tinyobjloader recognises them.
bool isKeywordLine(std::string_view line, std::string_view keyword) {
    return line.size() > keyword.size() && line.substr(0, keyword.size()) == keyword &&
           (line[keyword.size()] == ' ' || line[keyword.size()] == '\t');
}

std::string checkVertexLine(std::size_t vertex, std::string_view rest) {
    const std::vector<std::string_view> t = tokens(rest);
    if (t.size() < 3)
        return "vertex " + std::to_string(vertex) + " has " + std::to_string(t.size()) +
               " coordinates; it needs x, y and z";
    for (std::size_t axis = 0; axis < 3; ++axis) {
        std::string problem = checkVertexCoordinate(vertex, t[axis]);
        if (!problem.empty()) return problem;
    }
    return "";
}

// Checks what tinyobjloader would silently misread: vertex coordinates that are not decimal
// numbers or lie outside Mesh::kMaxCoordinate, texture coordinates that are not finite numbers,
// face indices that do not fit its int, and faces of fewer than 3 vertices, which it drops.
ObjTextCheck checkObjText(std::string_view text) {
    ObjTextCheck check;
    ObjCounts counts;
    const std::vector<std::string_view> lines = objLines(text);
    for (std::size_t number = 1; number <= lines.size() && check.error.empty(); ++number) {
        const std::string_view line = lines[number - 1];
        if (isKeywordLine(line, "vt")) {
            check.error = checkTexcoordLine(++counts.texcoords, number, line.substr(3));
        } else if (isKeywordLine(line, "vn")) {
            ++counts.normals;
        } else if (isKeywordLine(line, "v")) {
            check.error = checkVertexLine(++counts.vertices, line.substr(2));
        } else if (isKeywordLine(line, "f")) {
            ++counts.faces;
            const std::vector<std::string_view> corners = tokens(line.substr(2));
            if (corners.size() < 3 && check.shortFaces++ == 0) check.firstShortFace = counts.faces;
            for (std::size_t k = 0; k < corners.size() && check.error.empty(); ++k)
                check.error = checkCorner(corners[k], counts);
        }
    }
    return check;
}

}  // namespace

namespace {

// What an OBJ file holds, as Mesh::load needs it: one vertex per distinct (position, normal,
// texture coordinate) index triple, or per (position, texture coordinate) pair when the mesh gets
// smooth normals. position[i] is vertex i's index among the file's positions (of which there
// are positionCount), so that smooth normals are shared by the vertices a UV seam splits.
struct ObjArrays {
    std::vector<glm::vec3> positions, normals;
    std::vector<glm::vec2> texcoords;  // empty, or one per vertex
    std::vector<uint32_t> indices, position;
    std::size_t positionCount = 0;
    std::shared_ptr<const Image8> baseColour;
    bool smooth = false;
};

// The MTL files an OBJ names (mtllib), read from the OBJ's directory. tinyobjloader's own
// MaterialFileReader splits that directory at ':' and opens whatever the name gives; this one
// opens regular files only (a device or FIFO would block), warns about those it cannot read, and
// keeps which file each material came from, for messages and for the texture paths in it.
class MtlFiles : public tinyobj::MaterialReader {
public:
    MtlFiles(std::string objFile, std::filesystem::path dir) : m_objFile(std::move(objFile)), m_dir(std::move(dir)) {}

    bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* names, std::string* warn, std::string* err) override {
        const std::filesystem::path path = m_dir / name;
        std::error_code ec;
        std::ifstream in;
        if (std::filesystem::is_regular_file(path, ec)) in.open(path);
        if (!in.is_open()) {
            log(LogLevel::Warning, m_objFile + ": cannot read the material library " + path.string() +
                                       " (mtllib); its materials and textures are not used");
            return false;
        }
        tinyobj::LoadMtl(names, materials, &in, warn, err);
        m_fileOf.resize(materials->size(), path);
        return true;
    }

    /// The MTL file that material `id` came from (every material comes through here).
    const std::filesystem::path& fileOf(std::size_t id) const { return id < m_fileOf.size() ? m_fileOf[id] : m_dir; }

private:
    std::string m_objFile;
    std::filesystem::path m_dir;
    std::vector<std::filesystem::path> m_fileOf;
};

// Where a map_Kd file is: relative to the MTL file's directory. Exporters on Windows write '\'
// separators, which are tried as '/' when the name as written is not found.
std::filesystem::path texturePath(const std::filesystem::path& mtl, std::string name) {
    std::filesystem::path path = mtl.parent_path() / name;
    std::error_code ec;
    if (std::filesystem::exists(path, ec) || name.find('\\') == std::string::npos) return path;
    std::replace(name.begin(), name.end(), '\\', '/');
    return mtl.parent_path() / name;
}

// One texture the faces use, with the faces of every material that names it.
struct TextureUse {
    std::filesystem::path path;
    std::size_t faces = 0;
    std::size_t material = 0;  // the first material naming it
};

// The map_Kd textures of the materials in use, by file, in the order of the materials.
std::vector<TextureUse> textureUses(const std::map<int, std::size_t>& facesPerMaterial,
                                    const std::vector<tinyobj::material_t>& materials, const MtlFiles& mtl) {
    std::vector<TextureUse> uses;
    for (const auto& [id, faces] : facesPerMaterial) {
        if (id < 0 || static_cast<std::size_t>(id) >= materials.size()) continue;
        const std::string name = trimmed(materials[static_cast<std::size_t>(id)].diffuse_texname);
        if (name.empty()) continue;
        const std::filesystem::path path = texturePath(mtl.fileOf(static_cast<std::size_t>(id)), name);
        auto it = std::find_if(uses.begin(), uses.end(), [&](const TextureUse& u) { return u.path == path; });
        if (it == uses.end()) it = uses.insert(uses.end(), {path, 0, static_cast<std::size_t>(id)});
        it->faces += faces;
    }
    return uses;
}

// A vertex key: indices into the file's positions, normals and texture coordinates (-1: unused).
struct CornerKey {
    int position, normal, texcoord;
    bool operator==(const CornerKey&) const = default;
};
struct CornerKeyHash {
    std::size_t operator()(const CornerKey& k) const {
        uint64_t h = static_cast<uint32_t>(k.position);
        h = (h * 0x9e3779b97f4a7c15ull) ^ static_cast<uint32_t>(k.normal);
        h = (h * 0x9e3779b97f4a7c15ull) ^ static_cast<uint32_t>(k.texcoord);
        return static_cast<std::size_t>(h ^ (h >> 31));
    }
};

// An OBJ file through tinyobjloader, with the checks Mesh::load promises. Triangulates itself:
// tinyobjloader silently drops polygons with out-of-range indices (and keeps triangles with
// them), so the raw faces are needed to report bad indices. Of the materials, only the map_Kd
// texture is read.
class ObjParser {
public:
    ObjParser(const std::filesystem::path& path, std::string text)
        : m_file(path.string()), m_text(std::move(text)), m_mtl(m_file, path.parent_path()) {}

    ObjArrays parse() {
        checkText();
        read();
        triangulate();
        if (m_corners.empty()) fail("has no faces");
        decideTexcoords();
        ObjArrays out = weld();
        out.baseColour = baseColour();
        return out;
    }

private:
    [[noreturn]] void fail(const std::string& what) const { throw Error(ErrorKind::Parse, m_file + ": " + what); }
    void warn(const std::string& what) const { log(LogLevel::Warning, m_file + ": " + what); }

    void checkText() {
        const ObjTextCheck check = checkObjText(m_text);
        if (!check.error.empty()) fail(check.error);
        if (check.shortFaces > 0)
            warn("skipped " + std::to_string(check.shortFaces) + (check.shortFaces == 1 ? " face" : " faces") +
                 " with fewer than 3 vertices (the first is face " + std::to_string(check.firstShortFace) + ")");
        blankVertexWeights(m_text);
    }

    // The OBJ from memory (the text checked and cleaned above), the MTL files through m_mtl.
    void read() {
        std::istringstream stream(m_text);
        std::string warnings, errors;
        if (!tinyobj::LoadObj(&m_attrib, &m_shapes, &m_materials, &warnings, &errors, &stream, &m_mtl,
                              /*triangulate=*/false, /*default_vcols_fallback=*/false))
            fail("cannot parse OBJ: " + trimmed(errors));
        m_vertexCount = m_attrib.vertices.size() / 3;
        m_normalCount = m_attrib.normals.size() / 3;
        m_texcoordCount = m_attrib.texcoords.size() / 2;
        for (std::size_t i = 0; i < m_vertexCount; ++i)
            if (!isInRange(position(i)))
                fail("vertex " + std::to_string(i + 1) + " has a coordinate " + str(position(i)) +
                     " that is non-finite or outside the supported range [-1e18, 1e18]");
    }

    glm::vec3 position(std::size_t i) const {
        const auto& v = m_attrib.vertices;
        return {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
    }
    glm::vec3 normal(std::size_t i) const {
        const auto& n = m_attrib.normals;
        return {n[3 * i], n[3 * i + 1], n[3 * i + 2]};
    }
    glm::vec2 texcoord(std::size_t i) const { return {m_attrib.texcoords[2 * i], m_attrib.texcoords[2 * i + 1]}; }

    // Pass 1: every face checked and triangulated into (position, normal, texcoord) index
    // corners. Faces are numbered from 1 over all shapes, as users count them.
    void triangulate() {
        std::size_t faceNumber = 0;
        for (const tinyobj::shape_t& shape : m_shapes) {
            std::size_t offset = 0;
            for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
                const std::size_t faceSize = shape.mesh.num_face_vertices[f];
                const tinyobj::index_t* face = shape.mesh.indices.data() + offset;
                offset += faceSize;
                checkFace(++faceNumber, face, faceSize);
                if (faceSize < 3) continue;  // reported by checkText
                addTriangles(face, faceSize);
                const int material = f < shape.mesh.material_ids.size() ? shape.mesh.material_ids[f] : -1;
                ++m_facesPerMaterial[material];
            }
        }
    }

    void checkFace(std::size_t number, const tinyobj::index_t* face, std::size_t n) {
        auto outOfRange = [&](const char* what, int index, std::size_t count, const char* plural) {
            fail("face " + std::to_string(number) + " references " + what + " " + std::to_string(index + 1) +
                 ", but the file has " + std::to_string(count) + " " + plural);
        };
        for (std::size_t k = 0; k < n; ++k) {
            const int v = face[k].vertex_index;
            if (v < 0 || static_cast<std::size_t>(v) >= m_vertexCount) outOfRange("vertex", v, m_vertexCount, "vertices");
            const int vn = face[k].normal_index;
            if (vn >= 0 && static_cast<std::size_t>(vn) >= m_normalCount) outOfRange("normal", vn, m_normalCount, "normals");
            if (vn < 0 || !isUsableNormal(normal(static_cast<std::size_t>(vn)))) m_smooth = true;
            const int vt = face[k].texcoord_index;
            if (vt >= 0 && static_cast<std::size_t>(vt) >= m_texcoordCount)
                outOfRange("texture coordinate", vt, m_texcoordCount, "texture coordinates");
            if (n >= 3 && vt >= 0) ++m_cornersWithTexcoords;
        }
        if (n >= 3) m_cornerCount += n;
    }

    void addTriangles(const tinyobj::index_t* face, std::size_t n) {
        auto emit = [&](std::size_t a, std::size_t b, std::size_t c) {
            m_corners.insert(m_corners.end(), {face[a], face[b], face[c]});
        };
        if (n != 4) {
            for (std::size_t k = 1; k + 1 < n; ++k) emit(0, k, k + 1);
            return;
        }
        // A quad is split along its shorter diagonal (as tinyobjloader does) for better triangles.
        auto p = [&](std::size_t k) { return position(static_cast<std::size_t>(face[k].vertex_index)); };
        if (glm::length(p(2) - p(0)) <= glm::length(p(3) - p(1))) {
            emit(0, 1, 2);
            emit(0, 2, 3);
        } else {
            emit(0, 1, 3);
            emit(1, 2, 3);
        }
    }

    // A mesh has texture coordinates on every vertex or on none; a file with them on some face
    // corners only (a partly unwrapped model) gets none.
    void decideTexcoords() {
        m_keepTexcoords = m_cornersWithTexcoords == m_cornerCount;
        if (m_cornersWithTexcoords > 0 && !m_keepTexcoords)
            warn(std::to_string(m_cornersWithTexcoords) + " of its " + std::to_string(m_cornerCount) +
                 " face corners have texture coordinates (vt); they are kept only when every corner has one, so "
                 "the mesh has none");
    }

    // Pass 2: one output vertex per distinct (position, normal, texcoord) triple; the normal is
    // left out when smoothing (normals are computed per position afterwards), the texcoord when
    // they are not kept.
    ObjArrays weld() const {
        ObjArrays out;
        out.smooth = m_smooth;
        out.positionCount = m_vertexCount;
        out.indices.reserve(m_corners.size());
        std::unordered_map<CornerKey, uint32_t, CornerKeyHash> remap;
        remap.reserve(m_corners.size());
        for (const tinyobj::index_t& c : m_corners) {
            const CornerKey key{c.vertex_index, m_smooth ? -1 : c.normal_index, m_keepTexcoords ? c.texcoord_index : -1};
            auto [it, inserted] = remap.try_emplace(key, static_cast<uint32_t>(out.positions.size()));
            if (inserted) addVertex(key, out);
            out.indices.push_back(it->second);
        }
        return out;
    }

    void addVertex(const CornerKey& key, ObjArrays& out) const {
        out.positions.push_back(position(static_cast<std::size_t>(key.position)));
        out.position.push_back(static_cast<uint32_t>(key.position));
        if (key.normal >= 0) out.normals.push_back(unitNormal(normal(static_cast<std::size_t>(key.normal))));
        if (key.texcoord >= 0) out.texcoords.push_back(texcoord(static_cast<std::size_t>(key.texcoord)));
    }

    // The map_Kd texture of the materials the faces use. A Mesh has one texture: when the faces
    // use several, the one covering the most faces is taken (the first material's on a tie).
    std::shared_ptr<const Image8> baseColour() const {
        const std::vector<TextureUse> uses = textureUses(m_facesPerMaterial, m_materials, m_mtl);
        if (uses.empty()) return nullptr;
        const TextureUse* best = &uses.front();
        for (const TextureUse& use : uses)
            if (use.faces > best->faces) best = &use;
        const std::string context = "map_Kd " + best->path.string() + " of material \"" +
                                    m_materials[best->material].name + "\" in " + m_mtl.fileOf(best->material).string();
        if (uses.size() > 1)
            warn("its faces use " + std::to_string(uses.size()) + " textures, but a mesh has one; only " + context +
                 " (on " + std::to_string(best->faces) + " faces) is used");
        if (!m_keepTexcoords) {
            warn(context + " is not used: the mesh has no texture coordinates");
            return nullptr;
        }
        return detail::loadTextureOrWarn(best->path, m_file + ": " + context);
    }

    std::string m_file, m_text;
    MtlFiles m_mtl;
    tinyobj::attrib_t m_attrib;
    std::vector<tinyobj::shape_t> m_shapes;
    std::vector<tinyobj::material_t> m_materials;
    std::size_t m_vertexCount = 0, m_normalCount = 0, m_texcoordCount = 0;
    std::size_t m_cornerCount = 0, m_cornersWithTexcoords = 0;  // of faces with 3 or more corners
    std::map<int, std::size_t> m_facesPerMaterial;  // -1: no material
    std::vector<tinyobj::index_t> m_corners;
    bool m_smooth = false, m_keepTexcoords = false;
};

std::string readWholeFile(const std::filesystem::path& path) {
    const std::string file = path.string();
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw Error(ErrorKind::Io, file + ": file does not exist");
    if (std::filesystem::is_directory(path, ec))
        throw Error(ErrorKind::Io, file + ": is a directory, not a mesh file");
    if (!std::ifstream(path)) throw Error(ErrorKind::Io, file + ": cannot be opened for reading");
    std::ifstream in(path, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw Error(ErrorKind::Io, file + ": read error");
    return text;
}

}  // namespace

Mesh Mesh::load(const std::filesystem::path& path) {
    std::string text = readWholeFile(path);
    const detail::MeshFormat format = detail::chooseMeshFormat(path, text);
    if (format != detail::MeshFormat::Obj) {
        detail::LoadedMesh loaded = detail::loadMeshWithAssimp(path, text, format);
        loaded.mesh.m_baseColour = std::move(loaded.baseColour);
        return std::move(loaded.mesh);
    }
    ObjArrays obj = ObjParser(path, std::move(text)).parse();
    Mesh mesh;
    mesh.m_bounds = boundsOf(obj.positions);
    if (obj.smooth)
        obj.normals = detail::smoothNormalsPerPosition(obj.positions, obj.indices, obj.position, obj.positionCount,
                                                       mesh.m_bounds.center());
    mesh.m_positions = std::move(obj.positions);
    mesh.m_normals = std::move(obj.normals);
    mesh.m_texcoords = std::move(obj.texcoords);
    mesh.m_indices = std::move(obj.indices);
    mesh.m_baseColour = std::move(obj.baseColour);
    mesh.m_name = path.string();
    return mesh;
}

}  // namespace sss
