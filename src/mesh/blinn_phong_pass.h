#pragma once
// The mesh baseline: one forward pass, Lambert diffuse + Blinn-Phong specular.
#include "gl/program.h"
#include "mesh/gpu_mesh.h"
#include "sss/camera.h"
#include "sss/light.h"
#include "lighting/shadows.h"
#include "sss/mesh_scattering_renderer.h"

#include <array>
#include <optional>
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
    void run(const BlinnPhongInputs& in) const;

private:
    /// With or without surface shadows (compiled out where nothing casts them), linked the first
    /// time it is needed.
    const gl::Program& program(bool surfaceShadows) const;

    mutable std::array<std::optional<gl::Program>, 2> m_programs;
};

}  // namespace sss::detail
