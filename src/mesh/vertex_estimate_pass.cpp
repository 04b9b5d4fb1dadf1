#include "mesh/vertex_estimate_pass.h"

#include "lighting/light_uniforms.h"

#include <glm/matrix.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <string>

namespace sss::detail {

namespace {

gl::Program linkEstimateProgram(bool textured) {
    ShaderDefines defines = texturedMaterialDefines(textured);
    defines.insert(defines.end(), {{"MAX_LIGHTS", std::to_string(kMaxLights)},
                                   {"NEAR_FIELD_NODES", std::to_string(kNearFieldNodes)},
                                   {"NEAR_FIELD_TAPS", std::to_string(kNearFieldTaps)}});
    return gl::Program::link({{GL_COMPUTE_SHADER, "mesh/vertex_estimate.comp"}}, defines);
}

}  // namespace

VertexEstimatePass::VertexEstimatePass(std::size_t vertexCount)
    : m_program(linkEstimateProgram(false)), m_vertexCount(vertexCount) {
    const std::size_t bytes = std::max<std::size_t>(1, m_vertexCount) * sizeof(glm::vec4);
    m_sums = gl::Buffer::create(3 * bytes, nullptr, 0, "vertex estimate (sums)");  // inner, outer, textured log
    m_radiosity = gl::Buffer::create(bytes, nullptr, 0, "vertex estimate (radiosity)");
}

void VertexEstimatePass::accumulate(const GpuMesh& mesh, const glm::mat4& model, const RadiosityEstimateInputs& in,
                                    const NearFieldTable& nearField, float lightTexelWorld) {
    if (in.material && !m_texturedProgram) m_texturedProgram = linkEstimateProgram(true);
    if (in.material && !m_effective)
        m_effective = gl::Buffer::create(std::max<std::size_t>(1, m_vertexCount) * sizeof(glm::vec4), nullptr, 0,
                                         "vertex estimate (textured factor)");
    const gl::Program& program = in.material ? *m_texturedProgram : m_program;
    if (m_vertexCount > 0) {
        setRadiosityEstimateUniforms(program, in, static_cast<unsigned>(m_frames));
        setNearFieldUniforms(program, nearField);
        program.set("nearFieldCorrection", nearField.correction);
        program.set("lightTexelWorld", lightTexelWorld);
        program.set("vertexCount", static_cast<int>(m_vertexCount));
        program.set("model", model);
        program.set("normalMatrix", glm::mat3(glm::transpose(glm::inverse(model))));
        mesh.vertices.bindStorage(0);
        m_sums.bindStorage(1);
        m_radiosity.bindStorage(2);
        if (in.material) m_effective.bindStorage(3);
        program.use();
        glDispatchCompute(static_cast<GLuint>((m_vertexCount + 63) / 64), 1, 1);
        // The combine pass reads the radiosity as vertex-shader storage.
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        glUseProgram(0);
        for (GLuint b = 0; b < 4; ++b) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, 0);
    }
    ++m_frames;
}

}  // namespace sss::detail
