#include "mesh/vertex_estimate_pass.h"

#include "lighting/light_uniforms.h"

#include <glm/matrix.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <string>

namespace sss::detail {

VertexEstimatePass::VertexEstimatePass(std::size_t vertexCount)
    : m_program(gl::Program::link({{GL_COMPUTE_SHADER, "mesh/vertex_estimate.comp"}},
                                  {{"MAX_LIGHTS", std::to_string(kMaxLights)},
                                   {"NEAR_FIELD_NODES", std::to_string(kNearFieldNodes)},
                                   {"NEAR_FIELD_TAPS", std::to_string(kNearFieldTaps)}})),
      m_vertexCount(vertexCount) {
    const std::size_t bytes = std::max<std::size_t>(1, m_vertexCount) * sizeof(glm::vec4);
    m_sums = gl::Buffer::create(2 * bytes, nullptr, 0, "vertex estimate (sums)");  // inner, outer
    m_radiosity = gl::Buffer::create(bytes, nullptr, 0, "vertex estimate (radiosity)");
}

void VertexEstimatePass::accumulate(const GpuMesh& mesh, const glm::mat4& model, const RadiosityEstimateInputs& in,
                                    const NearFieldTable& nearField, float lightTexelWorld) {
    if (m_vertexCount > 0) {
        setRadiosityEstimateUniforms(m_program, in, static_cast<unsigned>(m_frames));
        setNearFieldUniforms(m_program, nearField);
        m_program.set("nearFieldCorrection", nearField.correction);
        m_program.set("lightTexelWorld", lightTexelWorld);
        m_program.set("vertexCount", static_cast<int>(m_vertexCount));
        m_program.set("model", model);
        m_program.set("normalMatrix", glm::mat3(glm::transpose(glm::inverse(model))));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, mesh.vertices.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, m_sums.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, m_radiosity.id());
        m_program.use();
        glDispatchCompute(static_cast<GLuint>((m_vertexCount + 63) / 64), 1, 1);
        // The combine pass reads the radiosity as vertex-shader storage.
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        glUseProgram(0);
        for (GLuint b = 0; b < 3; ++b) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, 0);
    }
    ++m_frames;
}

}  // namespace sss::detail
