#pragma once
// Mesh file formats other than OBJ: which reader a file goes to (extension, then content), and
// the Assimp path for PLY, STL, glTF 2.0 and OFF. Used by Mesh::load (src/io/mesh_load.cpp).
#include "sss/mesh.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

namespace sss::detail {

enum class MeshFormat { Obj, Ply, Stl, Gltf, Glb, Off };

/// "OBJ", "PLY", "STL", "glTF", "GLB", "OFF".
const char* meshFormatName(MeshFormat format);

/// The format the extension names (case-insensitive: .obj .ply .stl .gltf .glb .off), or
/// nullopt for a missing or unknown extension.
std::optional<MeshFormat> meshFormatFromExtension(const std::filesystem::path& path);

/// The format the file's first bytes show, or nullopt. Strong signatures (a "ply" line, the
/// binary glTF magic, an OFF header line) are returned always; weak ones (a file size that fits
/// binary STL, "solid ... facet", a JSON object with an "asset" member) only if weakToo.
std::optional<MeshFormat> sniffMeshFormat(std::string_view bytes, bool weakToo);

/// The reader for a file: the extension's format unless the content has a strong signature of
/// another format (a warning is logged then); for a missing or unknown extension, whatever the
/// content shows, else OBJ.
MeshFormat chooseMeshFormat(const std::filesystem::path& path, std::string_view bytes);

/// A mesh as a reader makes it, and the base-colour texture its materials name (null if none),
/// which Mesh::load attaches.
struct LoadedMesh {
    Mesh mesh;
    std::shared_ptr<const Image8> baseColour;
};

/// Loads a PLY, STL, glTF or GLB, or OFF file through Assimp. bytes is the whole file; it is
/// parsed from memory when the extension does not name `format` (Assimp would pick its reader
/// by the extension), else from the path (so glTF files can reference buffers and images beside
/// them). A texture that cannot be read is left out with a warning (src/io/image_decoding.h).
/// @throws Error Parse, messages starting with the path as given.
LoadedMesh loadMeshWithAssimp(const std::filesystem::path& path, std::string_view bytes, MeshFormat format);

/// Smooth area-weighted normals (as detail::smoothNormals) shared by the vertices at one
/// position: position[i] numbers vertex i's position (< positionCount), and every vertex of a
/// position gets the normal summed over the triangles around all of them. So the vertices that
/// a texture seam splits still shade as one smooth surface.
std::vector<glm::vec3> smoothNormalsPerPosition(const std::vector<glm::vec3>& positions,
                                                const std::vector<uint32_t>& indices,
                                                const std::vector<uint32_t>& position, std::size_t positionCount,
                                                glm::vec3 centre);

}  // namespace sss::detail
