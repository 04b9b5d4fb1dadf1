#pragma once
// Combine (Dal Corso et al. 2017, pass 3): the mesh from the viewer; each visible point reads
// the scattering maps that see it (3x3 percentage-closer visibility against each layer's depth,
// with a depth bias and a seam shrink), averages them, and applies exit Fresnel, an optional
// specular highlight; linear output (shaders/mesh/combine.frag).
#include "gl/program.h"
#include "lighting/shadows.h"
#include "mesh/gpu_mesh.h"
#include "mesh/light_buffer_pass.h"
#include "mesh/near_field.h"
#include "mesh/near_field_cache.h"
#include "mesh/textured_material.h"
#include "sss/bssrdf.h"
#include "mesh/scattering_map_pass.h"
#include "mesh/vertex_radiosity_pass.h"
#include "sss/camera.h"
#include "sss/light.h"

#include <array>
#include <optional>
#include <vector>

namespace sss::detail {

struct CombineSettings {
    MapLookupSettings lookup;
    float eta = 1.3f;
    float specularStrength = 1.0f;
    float shininess = 40.0f;
    glm::vec3 environment{0.0f};  ///< the environment's radiance times R_d: added as is
    DipoleConstants dipole;       ///< the profile; its single-scattering term is added per pixel
    NearFieldTable nearField;     ///< added per pixel: what the vertex estimate left out (radius 0: none)
    /// The near field evaluated once per light change, interpolated per pixel instead (or none).
    /// Untextured, its points hold the vertices' radiosity too (NearFieldCache::addRadiosity).
    const NearFieldCache* nearFieldCache = nullptr;
    bool perVertex = false;       ///< no map lookups, the vertices' radiosity (MeshCombine::PerVertex, VertexEstimate)
    /// A textured material: the cached radiosity takes each pixel's own texel (textured_material.glsl).
    const TexturedMaterialGpu* material = nullptr;
    double millimetresPerUnit = 1000.0;  ///< scales the textured material's mean free path
};

struct CombineInputs {
    const GpuMesh& mesh;
    const glm::mat4& model;
    const ScatteringCameras& cameras;
    const ScatteringMapPass* maps;        ///< none with MeshCombine::VertexEstimate (perVertex set)
    const gl::Buffer& vertexRadiosity;    ///< rgb per vertex: where no layer sees the point, or everywhere
    const std::vector<Light>& lights;
    const Camera& camera;
    float aspect = 1.0f;
    const LightBufferPass& lightBuffer;       ///< self-shadowing of the single-scattering term
    const SurfaceShadows* shadows = nullptr;  ///< hybrid scenes (specular and single scattering)
    /// A textured vertex estimate's factor per vertex (VertexEstimatePass::effective), or none.
    const gl::Buffer* vertexEffective = nullptr;
    /// The lights' radiance now over that the radiosity and the near field's points were
    /// accumulated with, per channel (the per-pixel terms read `lights` directly).
    glm::vec3 accumulatedRadianceScale{1.0f};
};

class CombinePass {
public:
    void run(const CombineInputs& in, const CombineSettings& settings) const;

private:
    /// The program compiled for this frame's needs, linked the first time they occur: without
    /// map lookups for the per-vertex combines, without surface shadows where nothing casts them.
    /// `nearField`: 0 none, 1 per pixel, 2 from the cache's points (combine.frag's NEAR_FIELD).
    const gl::Program& program(bool perVertex, bool surfaceShadows, bool textured, bool vertexEffective,
                               int nearField) const;

    mutable std::array<std::optional<gl::Program>, 48> m_programs;
};

}  // namespace sss::detail
