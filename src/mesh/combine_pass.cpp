#include "mesh/combine_pass.h"

#include "lighting/camera_uniforms.h"
#include "lighting/light_uniforms.h"

#include <glm/matrix.hpp>

#include <string>

namespace sss::detail {

CombinePass::CombinePass()
    : m_program(gl::Program::link({{GL_VERTEX_SHADER, "mesh/combine.vert"}, {GL_FRAGMENT_SHADER, "mesh/combine.frag"}},
                                  {{"MAX_CAMERAS", std::to_string(kMaxScatteringCameras)}})) {}

void CombinePass::run(const GpuMesh& mesh, const glm::mat4& model, const ScatteringCameras& cameras,
                      const ScatteringMapPass& maps, const std::vector<Light>& lights, const Camera& camera,
                      float aspect, const CombineSettings& s, const SurfaceShadows* shadows) const {
    const gl::Program& p = m_program;
    p.set("model", model);
    p.set("viewProjection", camera.projection(aspect) * camera.view());
    p.set("normalMatrix", glm::mat3(glm::transpose(glm::inverse(model))));
    setCameraUniforms(p, camera);
    p.set("scatteringMaps", 0);
    p.set("scatteringDepth", 1);
    p.set("cameraCount", maps.cameras());
    for (int k = 0; k < maps.cameras(); ++k) {
        const std::string index = "[" + std::to_string(k) + "]";
        p.set("cameraViewProjection" + index, cameras.viewProjection[static_cast<size_t>(k)]);
        p.set("cameraAxis" + index, cameras.axis[static_cast<size_t>(k)]);
    }
    p.set("depthBias", s.depthBias);
    p.set("seamShrink", s.seamShrink);
    p.set("eta", s.eta);
    p.set("specularStrength", s.specularStrength);
    p.set("shininess", s.shininess);
    p.set("environment", s.environment);
    setLightUniforms(p, lights);
    setSurfaceShadowUniforms(p, shadows, lights.size());
    maps.maps().bind(0);
    maps.depth().bind(1);

    mesh.drawOpaque(m_program);
}

}  // namespace sss::detail
