#pragma once
// Mesh file formats other than OBJ: which reader a file goes to (extension, then content), and
// the Assimp path for PLY, STL, glTF 2.0 and OFF. Used by Mesh::load (src/io/mesh_load.cpp).
#include "sss/mesh.h"

#include <filesystem>
#include <optional>
#include <string_view>

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

/// Loads a PLY, STL, glTF or GLB, or OFF file through Assimp. bytes is the whole file; it is
/// parsed from memory when the extension does not name `format` (Assimp would pick its reader
/// by the extension), else from the path (so glTF files can reference buffers beside them).
/// @throws Error Parse, messages starting with the path as given.
Mesh loadMeshWithAssimp(const std::filesystem::path& path, std::string_view bytes, MeshFormat format);

}  // namespace sss::detail
