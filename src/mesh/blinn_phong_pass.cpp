#include "mesh/blinn_phong_pass.h"

#include "lighting/camera_uniforms.h"
#include "lighting/light_uniforms.h"

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

namespace sss::detail {

const gl::Program& BlinnPhongPass::program(bool surfaceShadows) const {
    std::optional<gl::Program>& slot = m_programs[surfaceShadows ? 1 : 0];
    if (!slot)
        slot = gl::Program::link({{GL_VERTEX_SHADER, "mesh/blinn_phong.vert"}, {GL_FRAGMENT_SHADER, "mesh/blinn_phong.frag"}},
                                 {{"SURFACE_SHADOWS", surfaceShadows ? "1" : "0"}});
    return *slot;
}

void BlinnPhongPass::run(const BlinnPhongInputs& in) const {
    const gl::Program& p = program(castsSurfaceShadows(in.shadows, in.lights.size()));
    p.set("model", in.model);
    p.set("viewProjection", in.camera.projection(in.aspect) * in.camera.view());
    p.set("normalMatrix", glm::mat3(glm::transpose(glm::inverse(in.model))));
    setCameraUniforms(p, in.camera);
    p.set("ambient", in.material.ambient);
    p.set("diffuseColor", in.material.diffuse);
    p.set("specularColor", in.material.specular);
    p.set("shininess", in.material.shininess);
    setLightUniforms(p, in.lights);
    setSurfaceShadowUniforms(p, in.shadows, in.lights.size());

    in.mesh.drawOpaque(p);
}

}  // namespace sss::detail
