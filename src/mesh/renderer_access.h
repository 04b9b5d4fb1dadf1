#pragma once
// The internal hooks through which a hybrid scene (src/hybrid) hands shared lighting to a mesh
// renderer and reads its geometry. Implemented in mesh_scattering_renderer.cpp.
#include "lighting/shadows.h"
#include "mesh/gpu_mesh.h"
#include "sss/mesh_scattering_renderer.h"

#include <glm/mat4x4.hpp>

namespace sss::detail {

struct MeshRendererAccess {
    /// What shadows the mesh from the lights (null: nothing); a copy is kept.
    static void setShadows(MeshScatteringRenderer& r, const SurfaceShadows* shadows);
    static const GpuMesh* mesh(const MeshScatteringRenderer& r);
    static const glm::mat4& model(const MeshScatteringRenderer& r);
};

}  // namespace sss::detail
