#include "host_gl.h"

#include <GLFW/glfw3.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <array>
#include <stdexcept>
#include <string>

namespace host {
namespace {

template <typename Fn>
void load(Fn& fn, const char* name) {
    fn = reinterpret_cast<Fn>(glfwGetProcAddress(name));
    if (!fn) throw std::runtime_error(std::string("host_app: the GL context lacks ") + name);
}

constexpr const char* kVertexShader = R"(#version 450 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
uniform mat4 modelViewProjection;
uniform mat4 model;
out vec3 worldNormal;
void main() {
    worldNormal = mat3(model) * normal;
    gl_Position = modelViewProjection * vec4(position, 1.0);
}
)";

constexpr const char* kFragmentShader = R"(#version 450 core
in vec3 worldNormal;
uniform vec4 color;
uniform vec3 lightDirection;
out vec4 outColor;
void main() {
    float lambert = max(dot(normalize(worldNormal), -lightDirection), 0.0);
    outColor = vec4(color.rgb * (0.35 + 0.65 * lambert), color.a);
}
)";

// A unit cube (36 vertices, [-1, 1]^3) followed by a unit floor square in y = 0 (6 vertices).
std::vector<float> geometry() {
    std::vector<float> v;
    auto vertex = [&v](glm::vec3 p, glm::vec3 n) { v.insert(v.end(), {p.x, p.y, p.z, n.x, n.y, n.z}); };
    for (int axis = 0; axis < 3; ++axis)
        for (float sign : {-1.0f, 1.0f}) {
            glm::vec3 n(0.0f), u(0.0f), w(0.0f);
            n[axis] = sign;
            u[(axis + 1) % 3] = 1.0f;
            w[(axis + 2) % 3] = 1.0f;
            if (sign < 0.0f) std::swap(u, w);  // counter-clockwise seen from outside
            const std::array<glm::vec3, 4> c{n - u - w, n + u - w, n + u + w, n - u + w};
            for (int i : {0, 1, 2, 0, 2, 3}) vertex(c[static_cast<std::size_t>(i)], n);
        }
    const glm::vec3 up(0.0f, 1.0f, 0.0f);
    const std::array<glm::vec3, 4> f{glm::vec3(-1, 0, 1), glm::vec3(1, 0, 1), glm::vec3(1, 0, -1), glm::vec3(-1, 0, -1)};
    for (int i : {0, 1, 2, 0, 2, 3}) vertex(f[static_cast<std::size_t>(i)], up);
    return v;
}

}  // namespace

Gl Gl::load() {
    Gl gl{};
    host::load(gl.ClearColor, "glClearColor");
    host::load(gl.Clear, "glClear");
    host::load(gl.Enable, "glEnable");
    host::load(gl.Disable, "glDisable");
    host::load(gl.Viewport, "glViewport");
    host::load(gl.CreateShader, "glCreateShader");
    host::load(gl.ShaderSource, "glShaderSource");
    host::load(gl.CompileShader, "glCompileShader");
    host::load(gl.GetShaderiv, "glGetShaderiv");
    host::load(gl.GetShaderInfoLog, "glGetShaderInfoLog");
    host::load(gl.CreateProgram, "glCreateProgram");
    host::load(gl.AttachShader, "glAttachShader");
    host::load(gl.LinkProgram, "glLinkProgram");
    host::load(gl.GetProgramiv, "glGetProgramiv");
    host::load(gl.DeleteShader, "glDeleteShader");
    host::load(gl.DeleteProgram, "glDeleteProgram");
    host::load(gl.UseProgram, "glUseProgram");
    host::load(gl.GetUniformLocation, "glGetUniformLocation");
    host::load(gl.UniformMatrix4fv, "glUniformMatrix4fv");
    host::load(gl.Uniform4fv, "glUniform4fv");
    host::load(gl.Uniform3fv, "glUniform3fv");
    host::load(gl.CreateBuffers, "glCreateBuffers");
    host::load(gl.NamedBufferStorage, "glNamedBufferStorage");
    host::load(gl.DeleteBuffers, "glDeleteBuffers");
    host::load(gl.CreateVertexArrays, "glCreateVertexArrays");
    host::load(gl.DeleteVertexArrays, "glDeleteVertexArrays");
    host::load(gl.VertexArrayVertexBuffer, "glVertexArrayVertexBuffer");
    host::load(gl.EnableVertexArrayAttrib, "glEnableVertexArrayAttrib");
    host::load(gl.VertexArrayAttribFormat, "glVertexArrayAttribFormat");
    host::load(gl.VertexArrayAttribBinding, "glVertexArrayAttribBinding");
    host::load(gl.BindVertexArray, "glBindVertexArray");
    host::load(gl.DrawArrays, "glDrawArrays");
    host::load(gl.ReadPixels, "glReadPixels");
    host::load(gl.PixelStorei, "glPixelStorei");
    host::load(gl.ReadBuffer, "glReadBuffer");
    host::load(gl.BindFramebuffer, "glBindFramebuffer");
    host::load(gl.BlitNamedFramebuffer, "glBlitNamedFramebuffer");
    host::load(gl.Finish, "glFinish");
    return gl;
}

FlatRenderer::FlatRenderer(const Gl& gl) : m_gl(gl) {
    m_program = gl.CreateProgram();
    for (auto [type, text] : {std::pair{GL_VERTEX_SHADER, kVertexShader}, std::pair{GL_FRAGMENT_SHADER, kFragmentShader}}) {
        const GLuint shader = gl.CreateShader(type);
        gl.ShaderSource(shader, 1, &text, nullptr);
        gl.CompileShader(shader);
        GLint ok = GL_FALSE;
        gl.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
        if (!ok) {
            std::array<char, 2048> log{};
            gl.GetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), nullptr, log.data());
            throw std::runtime_error(std::string("host_app: shader: ") + log.data());
        }
        gl.AttachShader(m_program, shader);
        gl.DeleteShader(shader);
    }
    gl.LinkProgram(m_program);
    const std::vector<float> vertices = geometry();
    gl.CreateBuffers(1, &m_buffer);
    gl.NamedBufferStorage(m_buffer, static_cast<GLsizeiptr>(vertices.size() * sizeof(float)), vertices.data(), 0);
    gl.CreateVertexArrays(1, &m_vertexArray);
    gl.VertexArrayVertexBuffer(m_vertexArray, 0, m_buffer, 0, 6 * sizeof(float));
    for (GLuint attribute : {0u, 1u}) {
        gl.EnableVertexArrayAttrib(m_vertexArray, attribute);
        gl.VertexArrayAttribFormat(m_vertexArray, attribute, 3, GL_FLOAT, GL_FALSE, attribute * 3 * sizeof(float));
        gl.VertexArrayAttribBinding(m_vertexArray, attribute, 0);
    }
}

FlatRenderer::~FlatRenderer() {
    m_gl.DeleteProgram(m_program);
    m_gl.DeleteBuffers(1, &m_buffer);
    m_gl.DeleteVertexArrays(1, &m_vertexArray);
}

void FlatRenderer::drawBox(const glm::mat4& viewProjection, glm::vec3 centre, glm::vec3 half, glm::vec4 color) const {
    draw(viewProjection, glm::scale(glm::translate(glm::mat4(1.0f), centre), half), 0, 36, color);
}

void FlatRenderer::drawFloor(const glm::mat4& viewProjection, float y, float half, glm::vec4 color) const {
    const glm::mat4 model = glm::scale(glm::translate(glm::mat4(1.0f), {0.0f, y, 0.0f}), glm::vec3(half));
    draw(viewProjection, model, 36, 6, color);
}

void FlatRenderer::draw(const glm::mat4& viewProjection, const glm::mat4& model, unsigned first, int count,
                        glm::vec4 color) const {
    const glm::vec3 light = glm::normalize(glm::vec3(-0.4f, -1.0f, -0.6f));
    m_gl.UseProgram(m_program);
    const glm::mat4 mvp = viewProjection * model;
    m_gl.UniformMatrix4fv(m_gl.GetUniformLocation(m_program, "modelViewProjection"), 1, GL_FALSE, glm::value_ptr(mvp));
    m_gl.UniformMatrix4fv(m_gl.GetUniformLocation(m_program, "model"), 1, GL_FALSE, glm::value_ptr(model));
    m_gl.Uniform4fv(m_gl.GetUniformLocation(m_program, "color"), 1, glm::value_ptr(color));
    m_gl.Uniform3fv(m_gl.GetUniformLocation(m_program, "lightDirection"), 1, glm::value_ptr(light));
    m_gl.BindVertexArray(m_vertexArray);
    m_gl.DrawArrays(GL_TRIANGLES, static_cast<GLint>(first), count);
    m_gl.BindVertexArray(0);
    m_gl.UseProgram(0);
}

}  // namespace host
