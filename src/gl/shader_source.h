#pragma once
// Shader sources: the files under shaders/ are embedded into the library at build time
// (cmake/SssEmbedShaders.cmake). For development, SSS_SHADER_DIR=1 reads them from the source
// tree instead (SSS_SHADER_DIR=/some/path reads them from there), so edits need no rebuild.
//
// preprocessShader() prepends `#version 450 core` and the variant defines, expands
// `#include "path"` (paths relative to shaders/, each file included once), and emits `#line`
// directives whose source-string number indexes PreprocessedShader::files, so driver messages
// can be mapped back to file:line by remapShaderLog().

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace sss::detail {

struct EmbeddedShader {
    std::string_view path;    ///< relative to shaders/, e.g. "volume/ray_cast.frag"
    std::string_view source;
};

/// The table generated at build time.
const std::vector<EmbeddedShader>& embeddedShaders();

/// Source of one shader file, embedded or from SSS_SHADER_DIR. Throws Error(Io) if unknown.
std::string loadShaderFile(std::string_view path);

struct PreprocessedShader {
    std::string text;
    std::vector<std::string> files;  ///< index = #line source-string number
};

using ShaderDefines = std::vector<std::pair<std::string, std::string>>;

/// `load` maps a path to its text (loadShaderFile by default; tests pass their own).
PreprocessedShader preprocessShader(std::string_view path, const ShaderDefines& defines,
                                    std::string (*load)(std::string_view) = &loadShaderFile);

/// Rewrites driver log lines "N:L(C): ..." (Mesa) and "N(L) : ..." (NVIDIA) to "file:L: ...".
std::string remapShaderLog(std::string_view log, const std::vector<std::string>& files);

}  // namespace sss::detail
