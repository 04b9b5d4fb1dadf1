#pragma once
// The mesh baseline: one forward pass, Lambert diffuse + Blinn-Phong specular.
#include "gl/program.h"
#include "mesh/gpu_mesh.h"
#include "sss/camera.h"
#include "sss/light.h"
#include "lighting/shadows.h"
#include "sss/mesh_scattering_renderer.h"

#include <vector>

namespace sss::detail {

struct BlinnPhongInputs {
    const GpuMesh& mesh;
    const glm::mat4& model;
    const BlinnPhongMaterial& material;
    const std::vector<Light>& lights;
    const Camera& camera;
    float aspect = 1.0f;
    const SurfaceShadows* shadows = nullptr;  ///< hybrid scenes
};

class BlinnPhongPass {
public:
    BlinnPhongPass();
    void run(const BlinnPhongInputs& in) const;

private:
    gl::Program m_program;
};

}  // namespace sss::detail
