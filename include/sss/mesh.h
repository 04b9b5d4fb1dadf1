#pragma once
/// @file
/// Indexed triangle mesh on the CPU (positions, per-vertex normals, 32-bit indices).

#include "sss/bounds.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace sss {

/// An indexed triangle mesh with one unit normal per vertex. Triangles are counter-clockwise
/// when seen from the side the normals point to.
///
/// Invariants (checked by every factory): at least one triangle, index count a multiple of 3,
/// every index < vertexCount(), all coordinates finite with magnitude <= kMaxCoordinate,
/// normals().size() == positions().size(), every normal unit length. Degenerate (zero-area)
/// triangles are allowed.
class Mesh {
public:
    /// The largest coordinate magnitude a mesh may have (1e18). Rendering works in float, where
    /// squared lengths across larger meshes overflow (FLT_MAX is 3.4e38); scans in metres or
    /// millimetres are many orders of magnitude inside it.
    static constexpr float kMaxCoordinate = 1e18f;

    /// Loads a Wavefront OBJ file (v/vn/f; texture coordinates and materials are ignored).
    /// Polygons are triangulated (fan; quads split along the shorter diagonal); all shapes are
    /// merged into one vertex array with one vertex per distinct (position, normal) index pair.
    /// If any face corner has no normal, or a referenced normal is zero or non-finite, smooth
    /// area-weighted normals are computed for the whole mesh instead (one vertex per position).
    /// Lines may end in "\n", "\r\n" or "\r". Faces with fewer than 3 vertices are skipped with
    /// a warning in the log.
    /// @throws Error Io if the file is missing or unreadable; Parse if tinyobjloader rejects it,
    ///         it has no faces, a coordinate is not a decimal number (nan, inf, hex floats) or is
    ///         outside [-kMaxCoordinate, kMaxCoordinate], or a face index is out of range.
    ///         Messages start with the path as given.
    static Mesh load(const std::filesystem::path& path);

    /// Builds a mesh from arrays. If normals is empty, smooth area-weighted normals are
    /// computed; otherwise it must have one finite, non-zero normal per position (they are
    /// normalized). name is used in error messages and kept as name().
    /// @throws Error InvalidArgument if there are no triangles, indices.size() % 3 != 0, an index
    ///         is out of range, a coordinate is non-finite or beyond kMaxCoordinate, or the
    ///         normals are unusable.
    static Mesh fromArrays(std::vector<glm::vec3> positions, std::vector<uint32_t> indices,
                           std::vector<glm::vec3> normals = {}, std::string_view name = "mesh");

    /// Returns a copy with positions transformed by m (affine: w is ignored) and normals by the
    /// inverse transpose of its upper 3x3. A mirroring m (negative determinant) also reverses
    /// the triangle winding so that front faces stay counter-clockwise.
    /// @throws Error InvalidArgument if m is singular or produces non-finite positions.
    Mesh transformed(const glm::mat4& m) const;

    const std::vector<glm::vec3>& positions() const { return m_positions; }  ///< vertex positions
    const std::vector<glm::vec3>& normals() const { return m_normals; }      ///< unit normals
    const std::vector<uint32_t>& indices() const { return m_indices; }       ///< 3 per triangle
    std::size_t vertexCount() const { return m_positions.size(); }           ///< number of vertices
    std::size_t triangleCount() const { return m_indices.size() / 3; }       ///< number of triangles
    const Bounds& bounds() const { return m_bounds; }  ///< box around all vertex positions
    const std::string& name() const { return m_name; }  ///< file path or name given at creation

private:
    Mesh() = default;

    std::vector<glm::vec3> m_positions;
    std::vector<glm::vec3> m_normals;
    std::vector<uint32_t> m_indices;
    Bounds m_bounds;
    std::string m_name;
};

}  // namespace sss
