#include "sss/mesh.h"

#include "core/mesh_checks.h"
#include "util/format.h"

#include "sss/error.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

namespace sss {
namespace {

std::string str(glm::vec3 v) { return detail::formatVec(v); }

}  // namespace

namespace detail {



bool isInRange(glm::vec3 v) {
    const auto ok = [](float c) { return std::abs(c) <= Mesh::kMaxCoordinate; };  // false for NaN
    return ok(v.x) && ok(v.y) && ok(v.z);
}

// A normal is usable if it is finite and not zero.
bool isUsableNormal(glm::vec3 n) {
    const float largest = std::max({std::abs(n.x), std::abs(n.y), std::abs(n.z)});
    return std::isfinite(largest) && largest > 0.0f;
}

// The unit vector along a usable normal. Divided by its largest component first, so that
// neither tiny vectors (squares in the denormal range, found by tests/fuzz: |n| came out
// 0.98) nor huge ones (squares overflowing float) lose precision.
glm::vec3 unitNormal(glm::vec3 n) {
    const float largest = std::max({std::abs(n.x), std::abs(n.y), std::abs(n.z)});
    return glm::normalize(n / largest);
}

Bounds boundsOf(const std::vector<glm::vec3>& positions) {
    Bounds b;
    for (const glm::vec3& p : positions) b.extend(p);
    return b;
}

// Area-weighted: the unnormalized cross product has length 2*area, so summing it weights each
// face by its area. Vertices whose sum vanishes (only degenerate faces, or opposite faces
// cancelling) fall back to the direction from the mesh centre, which is right for the poles of
// a UV sphere, and finally to +z.
std::vector<glm::vec3> smoothNormals(const std::vector<glm::vec3>& positions,
                                     const std::vector<uint32_t>& indices, glm::vec3 centre) {
    std::vector<glm::vec3> acc(positions.size(), glm::vec3(0.0f));
    for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
        uint32_t i0 = indices[t], i1 = indices[t + 1], i2 = indices[t + 2];
        glm::vec3 n = glm::cross(positions[i1] - positions[i0], positions[i2] - positions[i0]);
        acc[i0] += n;
        acc[i1] += n;
        acc[i2] += n;
    }
    for (std::size_t i = 0; i < acc.size(); ++i) {
        if (isUsableNormal(acc[i])) {
            acc[i] = unitNormal(acc[i]);
            continue;
        }
        glm::vec3 d = positions[i] - centre;
        acc[i] = isUsableNormal(d) ? unitNormal(d) : glm::vec3(0.0f, 0.0f, 1.0f);
    }
    return acc;
}

}  // namespace detail

using detail::boundsOf;
using detail::isInRange;
using detail::isUsableNormal;
using detail::smoothNormals;
using detail::unitNormal;

Mesh Mesh::fromArrays(std::vector<glm::vec3> positions, std::vector<uint32_t> indices,
                      std::vector<glm::vec3> normals, std::string_view name, std::vector<glm::vec2> texcoords) {
    const std::string prefix = std::string(name) + ": ";
    auto fail = [&](const std::string& what) { throw Error(ErrorKind::InvalidArgument, prefix + what); };

    if (indices.empty() || positions.empty())
        fail("has no triangles (" + std::to_string(positions.size()) + " positions, " +
             std::to_string(indices.size()) + " indices)");
    if (indices.size() % 3 != 0)
        fail("index count " + std::to_string(indices.size()) + " is not a multiple of 3");
    if (positions.size() > std::numeric_limits<uint32_t>::max())
        fail("has " + std::to_string(positions.size()) + " vertices, more than 32-bit indices can address");
    for (std::size_t i = 0; i < positions.size(); ++i)
        if (!isInRange(positions[i]))
            fail("vertex " + std::to_string(i) + " has a coordinate " + str(positions[i]) +
                 " that is non-finite or outside the supported range [-1e18, 1e18]");
    for (std::size_t i = 0; i < indices.size(); ++i)
        if (indices[i] >= positions.size())
            fail("triangle " + std::to_string(i / 3) + " (indices[" + std::to_string(i) +
                 "]) references vertex " + std::to_string(indices[i]) + ", but the mesh has " +
                 std::to_string(positions.size()) + " vertices");

    Mesh mesh;
    mesh.m_bounds = boundsOf(positions);
    if (normals.empty()) {
        normals = smoothNormals(positions, indices, mesh.m_bounds.center());
    } else {
        if (normals.size() != positions.size())
            fail(std::to_string(normals.size()) + " normals given for " +
                 std::to_string(positions.size()) + " positions; the counts must match");
        for (std::size_t i = 0; i < normals.size(); ++i) {
            if (!isUsableNormal(normals[i]))
                fail("normal " + std::to_string(i) + " is zero or non-finite " + str(normals[i]));
            normals[i] = unitNormal(normals[i]);
        }
    }
    if (!texcoords.empty()) {
        if (texcoords.size() != positions.size())
            fail(std::to_string(texcoords.size()) + " texture coordinates given for " +
                 std::to_string(positions.size()) + " positions; the counts must match");
        for (std::size_t i = 0; i < texcoords.size(); ++i)
            if (!std::isfinite(texcoords[i].x) || !std::isfinite(texcoords[i].y))
                fail("texture coordinate " + std::to_string(i) + " is non-finite (" +
                     detail::formatNumber(texcoords[i].x) + ", " + detail::formatNumber(texcoords[i].y) + ")");
    }
    mesh.m_positions = std::move(positions);
    mesh.m_normals = std::move(normals);
    mesh.m_texcoords = std::move(texcoords);
    mesh.m_indices = std::move(indices);
    mesh.m_name = std::string(name);
    return mesh;
}

Mesh Mesh::transformed(const glm::mat4& m) const {
    const glm::mat3 linear(m);
    const float det = glm::determinant(linear);
    if (!std::isfinite(det) || det == 0.0f)
        throw Error(ErrorKind::InvalidArgument,
                    m_name + ": Mesh::transformed: the matrix is singular or non-finite (det " +
                        detail::formatNumber(det) + ")");
    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(linear));

    Mesh out;
    out.m_name = m_name;
    out.m_positions.reserve(m_positions.size());
    for (std::size_t i = 0; i < m_positions.size(); ++i) {
        glm::vec3 p = glm::vec3(m * glm::vec4(m_positions[i], 1.0f));
        if (!isInRange(p))
            throw Error(ErrorKind::InvalidArgument, m_name + ": Mesh::transformed: vertex " + std::to_string(i) +
                                                        " becomes " + str(p) +
                                                        ", non-finite or outside the supported range [-1e18, 1e18]");
        out.m_positions.push_back(p);
    }
    out.m_normals.reserve(m_normals.size());
    for (const glm::vec3& n : m_normals) {
        glm::vec3 t = normalMatrix * n;
        out.m_normals.push_back(isUsableNormal(t) ? unitNormal(t) : n);
    }
    out.m_indices = m_indices;
    out.m_texcoords = m_texcoords;
    out.m_baseColour = m_baseColour;
    // A mirror turns counter-clockwise triangles clockwise; swap two corners to undo it.
    if (det < 0.0f)
        for (std::size_t t = 0; t + 2 < out.m_indices.size(); t += 3)
            std::swap(out.m_indices[t + 1], out.m_indices[t + 2]);
    out.m_bounds = boundsOf(out.m_positions);
    return out;
}

Mesh Mesh::withBaseColour(std::shared_ptr<const Image8> texture) const {
    if (texture && m_texcoords.empty())
        throw Error(ErrorKind::InvalidArgument,
                    m_name + ": a base-colour texture needs texture coordinates, and the mesh has none");
    Mesh out = *this;
    out.m_baseColour = std::move(texture);
    return out;
}

}  // namespace sss
