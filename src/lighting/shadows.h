#pragma once
// Shadows one kind of object casts on another, as the passes of the other kind consume them:
// the lighting layer below src/mesh and src/volume. Hybrid scenes fill these in
// (src/hybrid/hybrid_compositor.cpp); the renderers only read them.
#include "gl/program.h"
#include "gl/texture.h"

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

/// Sets the uniforms of shaders/common/volume_shadow.glsl (shadows may be null: no volume) and
/// binds the light volumes to units::kVolumeShadows...
void setVolumeShadowUniforms(const gl::Program& program, const VolumeShadows* shadows, std::size_t lightCount);

}  // namespace sss::detail
