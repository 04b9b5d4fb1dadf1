#pragma once
// Light buffer (Dal Corso et al. 2017, pass 1): for each light, the world position and normal of
// the surface the light sees, one layer of a 2D array per light, one draw per light.
// Directional lights use an orthographic view along the light, point and spot lights a
// perspective view from the light; both frame the object's bounding sphere.
#include "gl/framebuffer.h"
#include "gl/program.h"
#include "gl/texture.h"
#include "mesh/gpu_mesh.h"
#include "mesh/textured_material.h"
#include "sss/light.h"

#include <glm/mat4x4.hpp>

#include <optional>
#include <vector>

namespace sss::detail {

/// World -> clip transform of the light's view of a sphere (centre, radius) in world space.
glm::mat4 lightViewProjection(const Light& light, glm::vec3 centre, float radius);

class LightBufferPass {
public:
    LightBufferPass();
    /// `material`: a textured material, whose ln gathered then fills logGathered().
    void run(const GpuMesh& mesh, const glm::mat4& model, const std::vector<Light>& lights, int resolution,
             const TexturedMaterialGpu* material = nullptr);

    const gl::Texture& positions() const { return m_positions; }  ///< xyz world, w = 1 where covered
    const gl::Texture& normals() const { return m_normals; }
    /// A textured material's ln gathered per texel (shaders/mesh/textured_material.glsl); empty
    /// after a run without one.
    const gl::Texture& logGathered() const { return m_logGathered; }
    const std::vector<glm::mat4>& viewProjections() const { return m_viewProjections; }
    /// A texel's size at `mesh` placed by `model`, world units (the views frame its bounding sphere).
    float texelWorld(const GpuMesh& mesh, const glm::mat4& model) const;

private:
    gl::Program m_program;
    std::optional<gl::Program> m_texturedProgram;  // TEXTURED_MATERIAL 1, linked on first use
    gl::Texture m_positions, m_normals, m_depth, m_logGathered;
    std::vector<gl::Framebuffer> m_layers;  // one per light: its layer of the three textures
    std::vector<glm::mat4> m_viewProjections;
};

/// Bounding sphere of `bounds` after `model` (centre, radius), in world space.
std::pair<glm::vec3, float> worldSphere(const Bounds& bounds, const glm::mat4& model);

}  // namespace sss::detail
