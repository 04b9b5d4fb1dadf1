// Mesh::load (declared in sss/mesh.h, built in the io component): OBJ through tinyobjloader,
// the other formats through io/mesh_formats.h.
#include "sss/mesh.h"

#include "core/mesh_checks.h"
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
#include <sstream>
#include <string_view>
#include <unordered_map>
#include <utility>

namespace sss {
namespace {

using detail::boundsOf;
using detail::isInRange;
using detail::isUsableNormal;
using detail::smoothNormals;
using detail::unitNormal;

std::string str(glm::vec3 v) { return detail::formatVec(v); }

std::string trimmed(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
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

// Checks what tinyobjloader would silently misread: vertex coordinates that are not decimal
// numbers or lie outside Mesh::kMaxCoordinate, face indices that do not fit its int, and faces
// of fewer than 3 vertices, which it drops.
ObjTextCheck checkObjText(std::string_view text) {
    ObjTextCheck check;
    auto fail = [&](std::string message) {
        check.error = std::move(message);
        return check;
    };
    std::size_t vertex = 0, face = 0;
    for (const std::string_view line : objLines(text)) {
        if (line.size() < 2 || (line[1] != ' ' && line[1] != '\t')) continue;
        if (line[0] == 'v') {
            ++vertex;
            const std::vector<std::string_view> t = tokens(line.substr(2));
            if (t.size() < 3)
                return fail("vertex " + std::to_string(vertex) + " has " + std::to_string(t.size()) +
                       " coordinates; it needs x, y and z");
            for (std::size_t axis = 0; axis < 3; ++axis) {
                const std::string token(t[axis]);
                if (!isDecimalNumber(token))
                    return fail("vertex " + std::to_string(vertex) + " has a non-finite or non-numeric coordinate \"" +
                                token + "\"");
                // Compared as stored: in float.
                const double value = std::strtod(token.c_str(), nullptr);
                if (!(std::abs(static_cast<float>(value)) <= Mesh::kMaxCoordinate))
                    return fail("vertex " + std::to_string(vertex) + " has the coordinate " + token + ", which is " +
                                (std::isfinite(value) ? "outside" : "non-finite in double, outside") +
                                " the supported range [-1e18, 1e18]");
            }
        } else if (line[0] == 'f') {
            ++face;
            const std::vector<std::string_view> corners = tokens(line.substr(2));
            if (corners.size() < 3 && check.shortFaces++ == 0) check.firstShortFace = face;
            for (const std::string_view corner : corners) {
                const std::string index(corner.substr(0, corner.find('/')));
                char* end = nullptr;
                errno = 0;
                const long long v = std::strtoll(index.c_str(), &end, 10);
                if (index.empty() || *end != '\0')
                    return fail("face " + std::to_string(face) + " has the vertex index \"" + index +
                                "\", which is not an integer");
                if (errno == ERANGE || v > std::numeric_limits<int>::max() ||
                    v < -static_cast<long long>(std::numeric_limits<int>::max()))
                    return fail("face " + std::to_string(face) + " references vertex " + index +
                                ", but the file has " + std::to_string(vertex) +
                                (vertex == 1 ? " vertex" : " vertices") + " before it");
            }
        }
    }
    return check;
}

}  // namespace

namespace {

// What an OBJ file holds, as Mesh::load needs it: one vertex per distinct (position, normal)
// pair, or per position when the mesh gets smooth normals.
struct ObjArrays {
    std::vector<glm::vec3> positions, normals;
    std::vector<uint32_t> indices;
    bool smooth = false;
};

// An OBJ file through tinyobjloader, with the checks Mesh::load promises. Triangulates itself:
// tinyobjloader silently drops polygons with out-of-range indices (and keeps triangles with
// them), so the raw faces are needed to report bad indices. Materials are not read.
class ObjParser {
public:
    ObjParser(std::string file, std::string text) : m_file(std::move(file)), m_text(std::move(text)) {}

    ObjArrays parse() {
        checkText();
        tinyobj::ObjReaderConfig config;
        config.triangulate = false;
        config.vertex_color = false;
        if (!m_reader.ParseFromString(m_text, "", config))
            fail("cannot parse OBJ: " + trimmed(m_reader.Error()));
        const tinyobj::attrib_t& attrib = m_reader.GetAttrib();
        m_vertexCount = attrib.vertices.size() / 3;
        m_normalCount = attrib.normals.size() / 3;
        for (std::size_t i = 0; i < m_vertexCount; ++i)
            if (!isInRange(position(i)))
                fail("vertex " + std::to_string(i + 1) + " has a coordinate " + str(position(i)) +
                     " that is non-finite or outside the supported range [-1e18, 1e18]");
        triangulate();
        if (m_corners.empty()) fail("has no faces");
        return weld();
    }

private:
    [[noreturn]] void fail(const std::string& what) const { throw Error(ErrorKind::Parse, m_file + ": " + what); }

    void checkText() {
        const ObjTextCheck check = checkObjText(m_text);
        if (!check.error.empty()) fail(check.error);
        if (check.shortFaces > 0)
            log(LogLevel::Warning, m_file + ": skipped " + std::to_string(check.shortFaces) +
                                       (check.shortFaces == 1 ? " face" : " faces") +
                                       " with fewer than 3 vertices (the first is face " +
                                       std::to_string(check.firstShortFace) + ")");
        blankVertexWeights(m_text);
    }

    glm::vec3 position(std::size_t i) const {
        const auto& v = m_reader.GetAttrib().vertices;
        return {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
    }
    glm::vec3 normal(std::size_t i) const {
        const auto& n = m_reader.GetAttrib().normals;
        return {n[3 * i], n[3 * i + 1], n[3 * i + 2]};
    }

    // Pass 1: every face checked and triangulated into (position, normal) index corners. Faces
    // are numbered from 1 over all shapes, as users count them.
    void triangulate() {
        std::size_t faceNumber = 0;
        for (const tinyobj::shape_t& shape : m_reader.GetShapes()) {
            std::size_t offset = 0;
            for (auto faceSize : shape.mesh.num_face_vertices) {
                const tinyobj::index_t* face = shape.mesh.indices.data() + offset;
                offset += faceSize;
                checkFace(++faceNumber, face, faceSize);
                if (faceSize >= 3) addTriangles(face, faceSize);  // shorter faces: reported by checkText
            }
        }
    }

    void checkFace(std::size_t number, const tinyobj::index_t* face, std::size_t n) {
        for (std::size_t k = 0; k < n; ++k) {
            const int v = face[k].vertex_index;
            if (v < 0 || static_cast<std::size_t>(v) >= m_vertexCount)
                fail("face " + std::to_string(number) + " references vertex " + std::to_string(v + 1) +
                     ", but the file has " + std::to_string(m_vertexCount) + " vertices");
            const int vn = face[k].normal_index;
            if (vn >= 0 && static_cast<std::size_t>(vn) >= m_normalCount)
                fail("face " + std::to_string(number) + " references normal " + std::to_string(vn + 1) +
                     ", but the file has " + std::to_string(m_normalCount) + " normals");
            if (vn < 0 || !isUsableNormal(normal(static_cast<std::size_t>(vn)))) m_smooth = true;
        }
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

    // Pass 2: one output vertex per distinct (position, normal) pair; per position when smoothing.
    ObjArrays weld() const {
        ObjArrays out;
        out.smooth = m_smooth;
        out.indices.reserve(m_corners.size());
        std::unordered_map<uint64_t, uint32_t> remap;
        remap.reserve(m_corners.size());
        for (const tinyobj::index_t& c : m_corners) {
            const uint64_t v = static_cast<uint32_t>(c.vertex_index);
            const uint64_t key = m_smooth ? v : (v << 32) | static_cast<uint32_t>(c.normal_index);
            auto [it, inserted] = remap.try_emplace(key, static_cast<uint32_t>(out.positions.size()));
            if (inserted) {
                out.positions.push_back(position(static_cast<std::size_t>(v)));
                if (!m_smooth) out.normals.push_back(unitNormal(normal(static_cast<std::size_t>(c.normal_index))));
            }
            out.indices.push_back(it->second);
        }
        return out;
    }

    std::string m_file, m_text;
    tinyobj::ObjReader m_reader;
    std::size_t m_vertexCount = 0, m_normalCount = 0;
    std::vector<tinyobj::index_t> m_corners;
    bool m_smooth = false;
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
    if (format != detail::MeshFormat::Obj) return detail::loadMeshWithAssimp(path, text, format);
    ObjArrays obj = ObjParser(path.string(), std::move(text)).parse();
    Mesh mesh;
    mesh.m_bounds = boundsOf(obj.positions);
    if (obj.smooth) obj.normals = smoothNormals(obj.positions, obj.indices, mesh.m_bounds.center());
    mesh.m_positions = std::move(obj.positions);
    mesh.m_normals = std::move(obj.normals);
    mesh.m_indices = std::move(obj.indices);
    mesh.m_name = path.string();
    return mesh;
}

}  // namespace sss
