#pragma once
// Decoding of 8-bit images through stb_image (PNG, JPEG, TGA, BMP, ...), from a file or from
// memory, shared by Image8::loadPng and the mesh readers' base-colour textures.
#include "sss/image.h"

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

namespace sss::detail {

/// Reads an image file of any format stb_image decodes, converted to 8-bit RGBA, row 0 at the top.
/// @throws Error Io if the file is missing, a directory or not a regular file; Parse with
///         stb_image's reason if it cannot be decoded; InvalidArgument if it is larger than
///         kMaxImageSide on a side. Messages start with the path.
Image8 readImage8(const std::filesystem::path& path);

/// The same for an image file held in memory; `name` (the file or resource it came from)
/// starts the messages.
Image8 decodeImage8(std::string_view bytes, const std::string& name);

/// A base-colour texture for a mesh: the image file, or null when it cannot be read, after a
/// warning "<context>: <reason>; the mesh loads without a texture". `context` names the file
/// that refers to the texture and how (e.g. "a.obj: map_Kd of material \"skin\" in a.mtl").
std::shared_ptr<const Image8> loadTextureOrWarn(const std::filesystem::path& path, const std::string& context);

/// The same for a texture held in memory (an embedded glTF image) named `name`.
std::shared_ptr<const Image8> decodeTextureOrWarn(std::string_view bytes, const std::string& name,
                                                  const std::string& context);

}  // namespace sss::detail
