#include "gl/program.h"

#include "sss/error.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cstring>

#include <vector>

namespace sss::gl {
namespace {

const char* stageName(GLenum stage) {
    switch (stage) {
        case GL_VERTEX_SHADER: return "vertex";
        case GL_FRAGMENT_SHADER: return "fragment";
        case GL_GEOMETRY_SHADER: return "geometry";
        case GL_COMPUTE_SHADER: return "compute";
        default: return "shader";
    }
}

}  // namespace

Shader Shader::compileText(GLenum stage, const detail::PreprocessedShader& source) {
    Shader shader(glCreateShader(stage));
    const char* text = source.text.c_str();
    glShaderSource(shader.id(), 1, &text, nullptr);
    glCompileShader(shader.id());
    GLint ok = GL_FALSE;
    glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetShaderiv(shader.id(), GL_INFO_LOG_LENGTH, &length);
        std::string log(static_cast<size_t>(std::max(length, 1)), '\0');
        glGetShaderInfoLog(shader.id(), length, nullptr, log.data());
        log.resize(std::strlen(log.c_str()));
        const std::string name = source.files.empty() ? "<shader>" : source.files.front();
        throw Error(ErrorKind::Gl, std::string("cannot compile ") + stageName(stage) + " shader " + name + ":\n" +
                                       detail::remapShaderLog(log, source.files));
    }
    if (!source.files.empty()) shader.setLabel(source.files.front());
    return shader;
}

Shader Shader::compile(GLenum stage, std::string_view path, const detail::ShaderDefines& defines,
                       std::string (*load)(std::string_view)) {
    return compileText(stage, detail::preprocessShader(path, defines, load));
}

Program Program::link(std::initializer_list<ShaderStage> stages, const detail::ShaderDefines& defines,
                      std::string (*load)(std::string_view)) {
    std::vector<Shader> shaders;
    std::string names;
    for (const ShaderStage& s : stages) {
        shaders.push_back(Shader::compile(s.stage, s.path, defines, load));
        names += (names.empty() ? "" : " + ") + std::string(s.path);
    }
    Program program(glCreateProgram());
    for (const Shader& s : shaders) glAttachShader(program.id(), s.id());
    glLinkProgram(program.id());
    for (const Shader& s : shaders) glDetachShader(program.id(), s.id());
    GLint ok = GL_FALSE;
    glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetProgramiv(program.id(), GL_INFO_LOG_LENGTH, &length);
        std::string log(static_cast<size_t>(std::max(length, 1)), '\0');
        glGetProgramInfoLog(program.id(), length, nullptr, log.data());
        log.resize(std::strlen(log.c_str()));
        throw Error(ErrorKind::Gl, "cannot link program " + names + ":\n" + log);
    }
    program.setLabel(names);
    return program;
}

GLint Program::uniformLocation(std::string_view name) const {
    auto it = m_locations.find(std::string(name));
    if (it != m_locations.end()) return it->second;
    const std::string key(name);
    const GLint location = glGetUniformLocation(id(), key.c_str());
    m_locations.emplace(key, location);
    return location;
}

void Program::set(std::string_view name, glm::vec2 v) const {
    glProgramUniform2fv(id(), uniformLocation(name), 1, glm::value_ptr(v));
}
void Program::set(std::string_view name, glm::vec3 v) const {
    glProgramUniform3fv(id(), uniformLocation(name), 1, glm::value_ptr(v));
}
void Program::set(std::string_view name, glm::vec4 v) const {
    glProgramUniform4fv(id(), uniformLocation(name), 1, glm::value_ptr(v));
}
void Program::set(std::string_view name, glm::ivec2 v) const {
    glProgramUniform2i(id(), uniformLocation(name), v.x, v.y);
}
void Program::set(std::string_view name, glm::ivec3 v) const {
    glProgramUniform3iv(id(), uniformLocation(name), 1, glm::value_ptr(v));
}
glm::ivec3 Program::workGroupSize() const {
    glm::ivec3 size(1);
    glGetProgramiv(id(), GL_COMPUTE_WORK_GROUP_SIZE, glm::value_ptr(size));
    return size;
}
void Program::set(std::string_view name, const glm::mat3& v) const {
    glProgramUniformMatrix3fv(id(), uniformLocation(name), 1, GL_FALSE, glm::value_ptr(v));
}
void Program::set(std::string_view name, const glm::mat4& v) const {
    glProgramUniformMatrix4fv(id(), uniformLocation(name), 1, GL_FALSE, glm::value_ptr(v));
}

}  // namespace sss::gl
