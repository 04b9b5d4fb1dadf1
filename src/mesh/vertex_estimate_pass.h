#pragma once
// Evaluate-once radiosity (sss::MeshCombine::VertexEstimate): the radiosity estimated at each
// vertex of the mesh directly (shaders/mesh/vertex_estimate.comp), instead of in every texel of
// the K scattering maps that see the point (about K/2 of them). No maps exist in this mode; the
// combine pass interpolates the vertices' values, as the cached per-vertex combine does.
#include "gl/buffer.h"
#include "gl/program.h"
#include "mesh/gpu_mesh.h"
#include "mesh/near_field.h"
#include "mesh/radiosity_estimate.h"

#include <glm/mat4x4.hpp>

#include <cstddef>
#include <optional>

namespace sss::detail {

class VertexEstimatePass {
public:
    explicit VertexEstimatePass(std::size_t vertexCount);
    /// The next accumulate() starts from frame 0.
    void reset() { m_frames = 0; }
    /// Adds one frame of samples at every vertex of `mesh` placed by `model`: radiosity() holds
    /// the light from beyond `nearField`'s radius plus its correction of the rest
    /// (shaders/mesh/vertex_estimate.comp).
    /// `lightTexelWorld`: LightBufferPass::texelWorld.
    void accumulate(const GpuMesh& mesh, const glm::mat4& model, const RadiosityEstimateInputs& in,
                    const NearFieldTable& nearField, float lightTexelWorld);
    int frames() const { return m_frames; }
    /// rgb: the mean radiosity per vertex so far (a = 1), for combine.vert's VertexRadiosity block.
    const gl::Buffer& radiosity() const { return m_radiosity; }
    /// With a textured material: per vertex the textured rule's factor (shaders/mesh/
    /// textured_material.glsl, cachedTexturedRadiosity of 1), for combine.vert's VertexEffective
    /// block; null before a textured frame.
    const gl::Buffer* effective() const { return m_effective ? &m_effective : nullptr; }

private:
    gl::Program m_program;
    std::optional<gl::Program> m_texturedProgram;  // TEXTURED_MATERIAL 1, linked on first use
    gl::Buffer m_sums, m_radiosity, m_effective;
    std::size_t m_vertexCount = 0;
    int m_frames = 0;
};

}  // namespace sss::detail
