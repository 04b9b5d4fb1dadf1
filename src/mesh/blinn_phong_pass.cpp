#include "mesh/blinn_phong_pass.h"

#include "lighting/camera_uniforms.h"
#include "lighting/light_uniforms.h"

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

namespace sss::detail {

BlinnPhongPass::BlinnPhongPass()
    : m_program(gl::Program::link({{GL_VERTEX_SHADER, "mesh/blinn_phong.vert"},
                                   {GL_FRAGMENT_SHADER, "mesh/blinn_phong.frag"}})) {}

void BlinnPhongPass::run(const GpuMesh& mesh, const glm::mat4& model, const BlinnPhongMaterial& material,
                         const std::vector<Light>& lights, const Camera& camera, float aspect,
                         const SurfaceShadows* shadows) const {
    m_program.set("model", model);
    m_program.set("viewProjection", camera.projection(aspect) * camera.view());
    m_program.set("normalMatrix", glm::mat3(glm::transpose(glm::inverse(model))));
    setCameraUniforms(m_program, camera);
    m_program.set("ambient", material.ambient);
    m_program.set("diffuseColor", material.diffuse);
    m_program.set("specularColor", material.specular);
    m_program.set("shininess", material.shininess);
    setLightUniforms(m_program, lights);
    setSurfaceShadowUniforms(m_program, shadows, lights.size());

    mesh.drawOpaque(m_program);
}

}  // namespace sss::detail
