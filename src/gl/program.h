#pragma once
#include "gl/object.h"
#include "gl/shader_source.h"

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <initializer_list>
#include <map>
#include <string>
#include <string_view>
#include <unordered_map>

namespace sss::gl {

struct ShaderTraits {
    static constexpr GLenum labelNamespace = GL_SHADER;
    static void destroy(GLuint id) { glDeleteShader(id); }
};

/// One compiled shader stage. Compile errors throw Error(Gl) with file:line locations.
class Shader : public Object<ShaderTraits> {
public:
    Shader() = default;
    /// Compiles shaders/<path> (after include expansion and defines) as `stage`; `load` reads
    /// the files (as in detail::preprocessShader; tests pass their own).
    static Shader compile(GLenum stage, std::string_view path, const detail::ShaderDefines& defines = {},
                          std::string (*load)(std::string_view) = &detail::loadShaderFile);
    /// Compiles already-preprocessed text; `files` maps #line source numbers to names.
    static Shader compileText(GLenum stage, const detail::PreprocessedShader& source);

private:
    explicit Shader(GLuint id) : Object(id) {}
};

struct ProgramTraits {
    static constexpr GLenum labelNamespace = GL_PROGRAM;
    static void destroy(GLuint id) { glDeleteProgram(id); }
};

struct ShaderStage {
    GLenum stage;
    std::string_view path;
};

/// A linked program with cached uniform locations. Setters ignore uniforms the linker removed
/// (location -1), as GL does, so optional variants need no special cases.
class Program : public Object<ProgramTraits> {
public:
    Program() = default;
    static Program link(std::initializer_list<ShaderStage> stages, const detail::ShaderDefines& defines = {},
                        std::string (*load)(std::string_view) = &detail::loadShaderFile);

    void use() const { glUseProgram(id()); }
    GLint uniformLocation(std::string_view name) const;
    void set(std::string_view name, int v) const { glProgramUniform1i(id(), uniformLocation(name), v); }
    void set(std::string_view name, unsigned v) const { glProgramUniform1ui(id(), uniformLocation(name), v); }
    void set(std::string_view name, float v) const { glProgramUniform1f(id(), uniformLocation(name), v); }
    void set(std::string_view name, glm::vec2 v) const;
    void set(std::string_view name, glm::vec3 v) const;
    void set(std::string_view name, glm::vec4 v) const;
    void set(std::string_view name, glm::ivec2 v) const;
    void set(std::string_view name, glm::ivec3 v) const;
    void set(std::string_view name, const glm::mat3& v) const;
    void set(std::string_view name, const glm::mat4& v) const;
    /// local_size of a compute program, so dispatches follow the shader's declaration.
    glm::ivec3 workGroupSize() const;

private:
    explicit Program(GLuint id) : Object(id) {}
    mutable std::unordered_map<std::string, GLint> m_locations;
};

/// The compute program `shader` for `variant`, linked with defines() on its first use and kept
/// in `programs` (passes compiled per variant of their inputs).
template <class Variant, class Defines>
const Program& linkedOnce(std::map<Variant, Program>& programs, const Variant& variant, const char* shader,
                          Defines defines) {
    auto found = programs.find(variant);
    if (found == programs.end())
        found = programs.emplace(variant, Program::link({{GL_COMPUTE_SHADER, shader}}, defines())).first;
    return found->second;
}

}  // namespace sss::gl
