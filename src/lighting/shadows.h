#pragma once
// Shadows one object casts on another, as the passes of the receiving object consume them: the
// lighting layer below src/mesh and src/volume. Hybrid scenes fill these in
// (src/hybrid/hybrid_compositor.cpp); the renderers only read them.
#include "gl/program.h"
#include "gl/texture.h"
#include "sss/light.h"

#include <glm/mat4x4.hpp>

#include <cstdint>
#include <vector>

namespace sss::detail {

/// The meshes seen from each light (one array layer per light): depth, and which mesh is nearest.
/// Volumes test ray-cast samples against the depth; mesh passes test surface points against it
/// (shaders/common/mesh_shadow.glsl).
struct MeshShadowMaps {
    gl::Texture depth;                   ///< 2D array, DEPTH_COMPONENT32F
    gl::Texture ids;                     ///< 2D array, R16UI: 1 + index of the nearest mesh, 0: none
    std::vector<glm::mat4> worldToClip;  ///< per light
    float texelWorldSize = 0.0f;         ///< edge of one texel at the scene, world units
    std::uint64_t revision = 0;          ///< changes whenever the maps change
};

/// One volume's light volumes, through which meshes see the lights (tinted by the light volume's
/// chromaticity, dimmed by its intensity).
struct VolumeShadows {
    const std::vector<gl::Texture>* lightVolumes = nullptr;  ///< per light: (c, l)
    glm::mat4 worldToTexture{1.0f};  ///< world space -> the volume box's [0,1]^3
    std::uint64_t revision = 0;      ///< changes whenever the light volumes change
};

/// Everything that may shadow a mesh surface from the lights.
struct SurfaceShadows {
    const MeshShadowMaps* meshes = nullptr;  ///< null: no mesh casts shadows on this surface
    /// 1 + this mesh's index in `meshes->ids` (0: the surface is not in the maps). A mesh ignores
    /// its own entries: a scattering mesh's light buffer already holds its self-shadowing, and
    /// Blinn-Phong's n.l its attached shadows (cast self-shadows would depend on how the maps
    /// frame the scene, a texel's worth of flicker at the terminator).
    unsigned selfId = 0;
    std::vector<VolumeShadows> volumes;  ///< every volume between the lights and the surface

    /// Changes whenever anything above does (a cache key for what the shadows feed).
    std::uint64_t revision() const;
};

/// At most this many (volume, light) pairs shadow one mesh: each takes a texture unit.
inline constexpr int kMaxVolumeShadowPairs = 16;

/// Whether anything shadows the surface: mesh shadow maps for every light, or a volume with a
/// light volume per light. Where nothing does, passes compile surface_shadows.glsl with
/// SURFACE_SHADOWS 0 and skip its work per pixel.
bool castsSurfaceShadows(const SurfaceShadows* shadows, std::size_t lightCount);

/// Sets the uniforms of shaders/common/surface_shadows.glsl (null: nothing shadows the surface)
/// and binds its textures. Volumes beyond kMaxVolumeShadowPairs / lightCount are left out.
void setSurfaceShadowUniforms(const gl::Program& program, const SurfaceShadows* shadows, std::size_t lightCount);

/// Whether the meshes' maps hold every one of `lightCount` lights: volume passes then compile
/// shaders/volume/mesh_visibility.glsl with MESH_SHADOWS 1 (null: no meshes shadow the volume).
bool castsMeshShadows(const MeshShadowMaps* shadows, std::size_t lightCount);

/// The maps' revision where they shadow a volume's `lightCount` lights, else 0: for the keys of
/// what a volume pass builds from its lights (the multiple-scattering cache, the path tracer).
std::uint64_t meshShadowRevision(const MeshShadowMaps* shadows, std::size_t lightCount);

/// Sets shaders/volume/mesh_visibility.glsl's uniforms for `lights` (the maps' layers, in order)
/// and binds the maps to units::kMeshShadowDepth; castsMeshShadows(&shadows, lights.size()) must hold.
void setMeshVisibilityUniforms(const gl::Program& program, const MeshShadowMaps& shadows,
                               const std::vector<Light>& lights);

}  // namespace sss::detail
