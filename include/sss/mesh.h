#pragma once
/// @file
/// Indexed triangle mesh on the CPU (positions, per-vertex normals, optional texture coordinates
/// and base-colour texture, 32-bit indices).

#include "sss/api.h"
#include "sss/bounds.h"

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

SSS_BEGIN_API

namespace sss {

class Image8;

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

    /// Loads a triangle mesh file. The reader is picked by the extension (case-insensitive):
    ///  - .obj: Wavefront OBJ through tinyobjloader (v/vt/vn/f, mtllib/usemtl). Polygons are
    ///    triangulated (fan; quads split along the shorter diagonal); all shapes are merged into
    ///    one vertex array with one vertex per distinct (position, normal, texture coordinate)
    ///    index triple. Texture coordinates (vt u v; a w is ignored) are kept as texcoords() only
    ///    if every face corner has one; if only some corners do, none are kept (with a warning).
    ///    If any face corner has no normal, or a referenced normal is zero or non-finite, smooth
    ///    area-weighted normals are computed for the whole mesh instead: one vertex per distinct
    ///    (position, texture coordinate) pair, the vertices at one position sharing one normal
    ///    (texture seams stay split and still shade smoothly). Of the materials, only the map_Kd
    ///    texture is kept, as baseColour(): mtllib files are read from the OBJ's directory, the
    ///    map_Kd path is relative to the MTL file's directory, and its options (-s, -o, -bm ...)
    ///    are ignored; if the faces' materials name several textures, the one on the most faces
    ///    is kept (with a warning), and faces without a textured material get it too. Lines may
    ///    end in "\n", "\r\n" or "\r". Faces with fewer than 3 vertices are skipped with a
    ///    warning in the log.
    ///  - .ply (ASCII, binary little and big endian), .stl (ASCII and binary), .gltf and .glb
    ///    (glTF 2.0), .off: through Assimp, polygons triangulated, identical vertices joined. All
    ///    meshes of the scene are merged into one, each placed by its node's world transform
    ///    (glTF node hierarchies: translation, rotation, scale; a mesh placed by several nodes
    ///    appears several times; a mirroring transform keeps the triangles counter-clockwise;
    ///    placements with a singular (zero-scale) transform are skipped with a warning). Points
    ///    and lines are ignored with a warning. File normals are used if every mesh has usable
    ///    ones; otherwise, and always for STL (whose facet normals are flat and often zero),
    ///    corners at the same position (and texture coordinate) are joined and smooth
    ///    area-weighted normals computed, as for OBJ. The first texture coordinate set is kept
    ///    if every mesh has one (if only some do, none is kept, with a warning): glTF
    ///    TEXCOORD_0, whose top-left origin Assimp turns into Mesh's bottom-left one; PLY vertex
    ///    properties u/v, s/t or texture_u/texture_v, as written (texture_s/texture_t are not
    ///    read). The base-colour texture of the material on the most triangles is kept, as
    ///    baseColour() (with a warning if the meshes name several): glTF baseColorTexture (an
    ///    image file relative to the glTF file, a data: URI, or a GLB buffer view) or a diffuse
    ///    texture (PLY "comment TextureFile", relative to the PLY file). Vertex colours and all
    ///    other material values are ignored.
    /// Textures are read with stb_image (PNG, JPEG, TGA, BMP, ...) as 8-bit sRGB RGBA. One that
    /// is missing or cannot be decoded, or one named by a mesh without texture coordinates, is
    /// left out with a warning naming the file that refers to it, the texture and the reason;
    /// the mesh still loads (baseColour() is null). So does an OBJ whose mtllib file cannot be
    /// read (with a warning too).
    /// A missing or unknown extension is resolved by the content ("ply" first line, "glTF" magic,
    /// an OFF header, a binary STL's size, "solid", a JSON object with "asset"), else read as
    /// OBJ. A PLY, GLB or OFF signature also overrides a known extension that names another
    /// format (with a warning), so a PLY saved as .obj still loads.
    /// Every format is checked alike: coordinates finite and within kMaxCoordinate, face indices
    /// in range, at least one triangle; PLY and OFF files must hold every item their header
    /// declares, a binary STL exactly its triangle count (truncated files are rejected, never
    /// padded). For the Assimp formats, vertices and faces are numbered from 0 within each mesh
    /// as Assimp stores them (for STL, three vertices per facet), and a mesh is named ("mesh 1
    /// vertex 3") when the scene has several.
    /// @throws Error Io if the file is missing or unreadable; Parse if the reader rejects it (its
    ///         own message is included), it has no triangles, a coordinate is not a decimal
    ///         number (OBJ: nan, inf, hex floats) or is non-finite or outside
    ///         [-kMaxCoordinate, kMaxCoordinate], a texture coordinate is not finite (OBJ: not a
    ///         decimal number, or beyond float's range; the message names its line), a face index
    ///         (of a position, normal or texture coordinate) is out of range, or the file is
    ///         truncated. Messages start with the path as given.
    static Mesh load(const std::filesystem::path& path);

    /// Builds a mesh from arrays. If normals is empty, smooth area-weighted normals are
    /// computed; otherwise it must have one finite, non-zero normal per position (they are
    /// normalized). texcoords is empty or holds one finite (u, v) per position (see
    /// texcoords()). name is used in error messages and kept as name().
    /// @throws Error InvalidArgument if there are no triangles, indices.size() % 3 != 0, an index
    ///         is out of range, a coordinate is non-finite or beyond kMaxCoordinate, the normals
    ///         are unusable, or texcoords has another count or a non-finite value.
    static Mesh fromArrays(std::vector<glm::vec3> positions, std::vector<uint32_t> indices,
                           std::vector<glm::vec3> normals = {}, std::string_view name = "mesh",
                           std::vector<glm::vec2> texcoords = {});

    /// A copy that carries `texture` as its base colour (sRGB-encoded 8-bit RGBA, row 0 at the
    /// top, as Image8 stores it); null removes it.
    /// @throws Error InvalidArgument if the texture is set and the mesh has no texcoords().
    Mesh withBaseColour(std::shared_ptr<const Image8> texture) const;

    /// Returns a copy with positions transformed by m (affine: w is ignored) and normals by the
    /// inverse transpose of its upper 3x3. A mirroring m (negative determinant) also reverses
    /// the triangle winding so that front faces stay counter-clockwise.
    /// @throws Error InvalidArgument if m is singular or produces non-finite positions.
    Mesh transformed(const glm::mat4& m) const;

    const std::vector<glm::vec3>& positions() const { return m_positions; }  ///< vertex positions
    const std::vector<glm::vec3>& normals() const { return m_normals; }      ///< unit normals
    const std::vector<uint32_t>& indices() const { return m_indices; }       ///< 3 per triangle
    /// Texture coordinates, one per vertex, or empty when the source had none. (0, 0) is the
    /// bottom-left corner of a texture and (1, 1) its top-right (OBJ's convention; the glTF
    /// reader flips v); textures repeat outside [0, 1].
    const std::vector<glm::vec2>& texcoords() const { return m_texcoords; }
    /// The base-colour texture the file names (OBJ map_Kd, glTF baseColorTexture) or
    /// withBaseColour() set, sRGB-encoded; null if none. Textured translucent materials take it as
    /// the reflectance per texel (TexturedScattering in sss/materials.h).
    const std::shared_ptr<const Image8>& baseColour() const { return m_baseColour; }
    std::size_t vertexCount() const { return m_positions.size(); }           ///< number of vertices
    std::size_t triangleCount() const { return m_indices.size() / 3; }       ///< number of triangles
    const Bounds& bounds() const { return m_bounds; }  ///< box around all vertex positions
    const std::string& name() const { return m_name; }  ///< file path or name given at creation

private:
    Mesh() = default;

    std::vector<glm::vec3> m_positions;
    std::vector<glm::vec3> m_normals;
    std::vector<uint32_t> m_indices;
    std::vector<glm::vec2> m_texcoords;
    std::shared_ptr<const Image8> m_baseColour;
    Bounds m_bounds;
    std::string m_name;
};

}  // namespace sss

SSS_END_API
