// libFuzzer target: sss::Mesh::load (Wavefront OBJ through tinyobjloader).
//
// The input is the OBJ file. Oracle (see fuzz_support.h): load() returns or throws sss::Error;
// a returned mesh keeps the invariants of include/sss/mesh.h (at least one triangle, indices in
// range, finite positions, unit normals, one normal per position) and its bounds are finite:
// min, max, center(), size() and radius() (renderers frame the camera with them).
//
// Reference check of vertex coordinates (text-only inputs: printable ASCII, space, tab, CR,
// LF): lines are split at LF, CRLF and CR, and a line whose first non-blank characters are
// "v" and a blank is a vertex line, as tinyobjloader reads them. Its first three blank-separated
// tokens must each read completely as a finite number with strtod, otherwise the load has to
// fail (Mesh::load promises a Parse error for a non-finite or non-numeric coordinate). If the
// load succeeds, every mesh position must be one of the file's vertices as strtod reads them
// (missing coordinates count as 0), so a coordinate read as a different number is caught too.
#include "fuzz_support.h"

#include "sss/error.h"
#include "sss/mesh.h"

#include "io/mesh_formats.h"

#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

namespace {

bool finite3(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

struct ReferenceVertices {
    bool anyBad = false;                 // a vertex line has a non-numeric or non-finite coordinate
    std::string firstBad;                // that line, for the report
    std::vector<std::array<double, 3>> vertices;
};

bool isBlank(char c) { return c == ' ' || c == '\t'; }

// nullopt when the input is not plain text (the check is skipped then: tokenizers differ on
// other control characters, and the check would judge the tokenizer, not the numbers).
std::optional<ReferenceVertices> referenceVertices(std::string_view text) {
    for (char c : text) {
        const auto u = static_cast<unsigned char>(c);
        if (!(u >= 0x20 && u < 0x7f) && c != '\t' && c != '\r' && c != '\n') return std::nullopt;
    }
    ReferenceVertices ref;
    std::size_t pos = 0;
    while (pos < text.size()) {
        std::size_t end = text.find_first_of("\r\n", pos);
        if (end == std::string_view::npos) end = text.size();
        std::string_view line = text.substr(pos, end - pos);
        pos = end + 1;
        if (end < text.size() && text[end] == '\r' && pos < text.size() && text[pos] == '\n') ++pos;

        std::size_t i = 0;
        while (i < line.size() && isBlank(line[i])) ++i;
        if (i + 1 >= line.size() || line[i] != 'v' || !isBlank(line[i + 1])) continue;
        i += 2;
        std::array<double, 3> v{0.0, 0.0, 0.0};
        for (int axis = 0; axis < 3; ++axis) {
            while (i < line.size() && isBlank(line[i])) ++i;
            if (i >= line.size()) break;
            std::size_t j = i;
            while (j < line.size() && !isBlank(line[j])) ++j;
            const std::string token(line.substr(i, j - i));
            i = j;
            char* stop = nullptr;
            const double value = std::strtod(token.c_str(), &stop);
            if (stop != token.c_str() + token.size() || !std::isfinite(value)) {
                if (!ref.anyBad) ref.firstBad = std::string(line.substr(0, 120));
                ref.anyBad = true;
            }
            v[static_cast<std::size_t>(axis)] = value;
        }
        ref.vertices.push_back(v);
    }
    return ref;
}

bool matchesFloat(float actual, double expected) {
    const auto e = static_cast<float>(expected);
    return std::fabs(actual - e) <= 1e-5f * std::fabs(e) + 1e-37f;
}

void checkMesh(const sss::Mesh& mesh, const std::optional<ReferenceVertices>& ref, std::string_view text) {
    const auto& positions = mesh.positions();
    const auto& normals = mesh.normals();
    const auto& indices = mesh.indices();
    SSS_FUZZ_CHECK(!positions.empty() && !indices.empty() && indices.size() % 3 == 0,
                   "%zu positions, %zu indices", positions.size(), indices.size());
    SSS_FUZZ_CHECK(normals.size() == positions.size(), "%zu normals for %zu positions", normals.size(),
                   positions.size());
    for (uint32_t index : indices)
        SSS_FUZZ_CHECK(index < positions.size(), "index %u, %zu vertices", index, positions.size());
    for (std::size_t i = 0; i < positions.size(); ++i) {
        const glm::vec3 p = positions[i], n = normals[i];
        SSS_FUZZ_CHECK(finite3(p), "position %zu is (%g, %g, %g)", i, p.x, p.y, p.z);
        SSS_FUZZ_CHECK(finite3(n) && std::fabs(glm::length(n) - 1.0f) < 1e-3f, "normal %zu is (%g, %g, %g)", i, n.x,
                       n.y, n.z);
    }

    const sss::Bounds& b = mesh.bounds();
    SSS_FUZZ_CHECK(!b.empty() && finite3(b.min) && finite3(b.max), "bounds (%g, %g, %g)..(%g, %g, %g)", b.min.x,
                   b.min.y, b.min.z, b.max.x, b.max.y, b.max.z);
    for (const glm::vec3& p : positions)
        SSS_FUZZ_CHECK(glm::all(glm::lessThanEqual(b.min, p)) && glm::all(glm::lessThanEqual(p, b.max)),
                       "position (%g, %g, %g) outside the bounds", p.x, p.y, p.z);
    const glm::vec3 c = b.center(), s = b.size();
    SSS_FUZZ_CHECK(finite3(c), "bounds center (%g, %g, %g)", c.x, c.y, c.z);
    SSS_FUZZ_CHECK(finite3(s), "bounds size (%g, %g, %g) for (%g, %g, %g)..(%g, %g, %g)", s.x, s.y, s.z, b.min.x,
                   b.min.y, b.min.z, b.max.x, b.max.y, b.max.z);
    SSS_FUZZ_CHECK(std::isfinite(b.radius()), "bounds radius %g for size (%g, %g, %g)", b.radius(), s.x, s.y, s.z);

    if (!ref) return;
    SSS_FUZZ_CHECK(!ref->anyBad, "the load succeeded, but a vertex line has a non-numeric or non-finite "
                                 "coordinate: \"%s\"", ref->firstBad.c_str());
    // Quadratic, so bounded; the default -max_len keeps far below the limit.
    if (positions.size() * ref->vertices.size() > 4'000'000) return;
    for (const glm::vec3& p : positions) {
        const bool found = std::any_of(ref->vertices.begin(), ref->vertices.end(), [&](const auto& r) {
            return matchesFloat(p.x, r[0]) && matchesFloat(p.y, r[1]) && matchesFloat(p.z, r[2]);
        });
        SSS_FUZZ_CHECK(found, "mesh position (%.9g, %.9g, %.9g) is none of the file's %zu vertices (read with "
                              "strtod); input of %zu bytes", p.x, p.y, p.z, ref->vertices.size(), text.size());
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
    const std::filesystem::path path = sss::fuzz::writeScratchFile("input.obj", data, size);
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    std::optional<sss::Mesh> mesh;
    try {
        mesh = sss::Mesh::load(path);
    } catch (const sss::Error&) {
        return 0;  // any other exception escapes: a bug
    }
    // Content with a PLY, GLB or OFF signature goes to Assimp whatever the extension
    // (src/io/mesh_formats.h); the OBJ reference check does not apply to it.
    const bool obj = !sss::detail::sniffMeshFormat(text, false).has_value();
    checkMesh(*mesh, obj ? referenceVertices(text) : std::nullopt, text);
    return 0;
}
