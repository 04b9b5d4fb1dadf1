#pragma once
// Light shared between meshes and volumes in a hybrid scene (see sss/hybrid_compositor.h), and
// the internal hooks through which the compositor hands it to the renderers.
#include "gl/program.h"
#include "gl/texture.h"
#include "mesh/gpu_mesh.h"
#include "sss/mesh_scattering_renderer.h"
#include "sss/volume_scattering_renderer.h"

#include <glm/mat4x4.hpp>

#include <cstdint>
#include <vector>

namespace sss::detail {

/// Depth of the meshes seen from each light (one array layer per light), for the volumes' ray
/// caster: a sample behind a mesh, as seen from a light, gets none of that light.
struct MeshShadowMaps {
    gl::Texture depth;                   ///< 2D array, DEPTH_COMPONENT32F
    std::vector<glm::mat4> worldToClip;  ///< per light
    std::uint64_t revision = 0;          ///< changes whenever the maps change
};

/// One volume's light volumes, through which meshes see the lights (intensity only).
struct VolumeShadows {
    const std::vector<gl::Texture>* lightVolumes = nullptr;  ///< per light: (c, l)
    glm::mat4 worldToTexture{1.0f};  ///< world space -> the volume box's [0,1]^3
    std::uint64_t revision = 0;      ///< changes whenever the light volumes change
};

inline constexpr int kVolumeShadowFirstUnit = 8;  // texture units 8.. hold volumeShadowLight[]

/// Sets the uniforms of shaders/common/volume_shadow.glsl (shadows may be null: no volume).
void setVolumeShadowUniforms(const gl::Program& program, const VolumeShadows* shadows, std::size_t lightCount);

struct VolumeRendererAccess {
    /// Shadows the ray caster applies to each light's light volume (null: none).
    static void setMeshShadows(VolumeScatteringRenderer& r, const MeshShadowMaps* shadows);
    /// Brings the light volumes up to date without ray casting (scattering modes only).
    static void updateLightVolumes(VolumeScatteringRenderer& r);
    /// The light volumes and placement, or null when the renderer is not in a scattering mode.
    static std::optional<VolumeShadows> shadows(const VolumeScatteringRenderer& r);
    static Bounds worldBounds(const VolumeScatteringRenderer& r);
};

struct MeshRendererAccess {
    static void setVolumeShadows(MeshScatteringRenderer& r, const VolumeShadows* shadows);
    static const GpuMesh* mesh(const MeshScatteringRenderer& r);
    static const glm::mat4& model(const MeshScatteringRenderer& r);
};

}  // namespace sss::detail
