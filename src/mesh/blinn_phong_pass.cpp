#include "mesh/blinn_phong_pass.h"

#include "lighting/camera_uniforms.h"
#include "lighting/light_uniforms.h"

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

namespace sss::detail {

BlinnPhongPass::BlinnPhongPass()
    : m_program(gl::Program::link({{GL_VERTEX_SHADER, "mesh/blinn_phong.vert"},
                                   {GL_FRAGMENT_SHADER, "mesh/blinn_phong.frag"}})) {}

void BlinnPhongPass::run(const BlinnPhongInputs& in) const {
    m_program.set("model", in.model);
    m_program.set("viewProjection", in.camera.projection(in.aspect) * in.camera.view());
    m_program.set("normalMatrix", glm::mat3(glm::transpose(glm::inverse(in.model))));
    setCameraUniforms(m_program, in.camera);
    m_program.set("ambient", in.material.ambient);
    m_program.set("diffuseColor", in.material.diffuse);
    m_program.set("specularColor", in.material.specular);
    m_program.set("shininess", in.material.shininess);
    setLightUniforms(m_program, in.lights);
    setSurfaceShadowUniforms(m_program, in.shadows, in.lights.size());

    in.mesh.drawOpaque(m_program);
}

}  // namespace sss::detail
