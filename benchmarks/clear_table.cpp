// The floor under every frame: clearing the render target (RGBA32F colour and 32-bit float
// depth), four ways side by side. On datacenter GPUs the framebuffer clear runs on the small
// graphics partition; texture clears and compute shaders may not.

#include "bench.h"

#include <glad/gl.h>

#include <string>

namespace {

constexpr const char* kTable = "clear";
constexpr float kColor[4] = {0.08f, 0.08f, 0.10f, 1.0f};
constexpr float kFar = 1.0f;

GLuint linkComputeClear() {
    const char* source = R"(#version 450
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f) uniform writeonly image2D target;
uniform vec4 color;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (all(lessThan(p, imageSize(target)))) imageStore(target, p, color);
})";
    const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    const GLuint program = glCreateProgram();
    glAttachShader(program, shader);
    glLinkProgram(program);
    glDeleteShader(shader);
    GLint linked = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &linked);
    if (!linked) throw BenchFailure("clear table: the compute clear did not link");
    return program;
}

}  // namespace

void runClearTable(BenchmarkContext& bench) {
    const GLuint computeClear = linkComputeClear();
    const auto framebufferClear = [](sss::RenderTarget& t) {
        glClearNamedFramebufferfv(t.framebufferId(), GL_COLOR, 0, kColor);
        glClearNamedFramebufferfv(t.framebufferId(), GL_DEPTH, 0, &kFar);
    };
    const auto textureClear = [](sss::RenderTarget& t) {
        glClearTexImage(t.colorTextureId(), 0, GL_RGBA, GL_FLOAT, kColor);
        glClearTexImage(t.depthTextureId(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, &kFar);
    };
    const auto shaderClear = [computeClear](sss::RenderTarget& t) {
        glProgramUniform4fv(computeClear, glGetUniformLocation(computeClear, "color"), 1, kColor);
        glBindImageTexture(0, t.colorTextureId(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glUseProgram(computeClear);
        glDispatchCompute(static_cast<GLuint>((t.width() + 7) / 8), static_cast<GLuint>((t.height() + 7) / 8), 1);
        glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        glUseProgram(0);
        glClearTexImage(t.depthTextureId(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, &kFar);
    };
    struct Method {
        const char* name;
        std::function<void(sss::RenderTarget&)> clear;
    };
    for (const Method& m : {Method{"library", {}}, Method{"framebuffer", framebufferClear},
                            Method{"texture", textureClear}, Method{"compute colour + texture depth", shaderClear}}) {
        Record r;
        r.table = kTable;
        r.model = "target";
        r.mode = "clear";
        r.params = m.name;
        r.dataSize = "RGBA32F + depth 32F";
        r.width = bench.options().width;
        r.height = bench.options().height;
        r.measurement = bench.measureClearOnly(m.clear);
        r.details = {{"method", m.name}};
        bench.addRecord(std::move(r));
    }
    glDeleteProgram(computeClear);
}
