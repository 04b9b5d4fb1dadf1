#pragma once
// The hybrid scene's shadow-map pass: every mesh seen from each light, into the MeshShadowMaps
// that volumes (ray cast) and mesh surfaces (shaders/common/surface_shadows.glsl) test against.
// One view per light frames everything that may be shadowed (meshes and volumes); the Cornell
// box only receives shadows, so it is not drawn.
#include "gl/framebuffer.h"
#include "gl/program.h"
#include "lighting/shadows.h"
#include "mesh/gpu_mesh.h"
#include "sss/bounds.h"
#include "sss/light.h"

#include <glm/mat4x4.hpp>

#include <vector>

namespace sss::detail {

struct ShadowCaster {
    const GpuMesh* mesh = nullptr;
    glm::mat4 model{1.0f};
};

struct MeshShadowMapInputs {
    const std::vector<Light>& lights;
    const std::vector<ShadowCaster>& casters;  ///< ids in the maps: 1 + index here
    Bounds receivers;                          ///< world bounds of what the maps must cover
    int resolution = 1024;
};

class MeshShadowMapPass {
public:
    MeshShadowMapPass();
    /// Redraws `maps` (reallocating them when the size or light count changed); sets
    /// worldToClip and texelWorldSize. The caller bumps maps.revision.
    void run(const MeshShadowMapInputs& in, MeshShadowMaps& maps);

private:
    gl::Program m_program;
    gl::Framebuffer m_framebuffer;
};

}  // namespace sss::detail
