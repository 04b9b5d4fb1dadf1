#pragma once
// The optional second pass of Ropinski et al. 2010, towards the viewer: the light each voxel
// scatters (from the light volumes, shaders/volume/lit_colour.comp) is propagated through the
// volume along the view direction (the light-volume sweep in its EYE_PASS variant), so the ray
// caster can add the cone-blurred light scattered towards the eye from behind each sample.
// View-dependent: it reruns when the camera turns, as well as when the light volumes change.
#include "gl/program.h"
#include "gl/texture.h"
#include "lighting/shadows.h"
#include "sss/light.h"
#include "volume/gpu_volume.h"
#include "volume/light_volume_pass.h"

#include <glm/mat4x4.hpp>

#include <map>
#include <optional>
#include <tuple>
#include <vector>

namespace sss::detail {

struct EyePassInputs {
    const GpuVolume& volume;
    const gl::Texture& transferFunction;
    const std::vector<gl::Texture>& lightVolumes;  ///< one per light, all the same size
    const std::vector<Light>& lights;
    const glm::mat4& model;
    glm::vec3 viewDirection;                       ///< world space (perspective rays taken as parallel)
    float ambientStrength = 0.0f, diffuseStrength = 1.0f;
    LightVolumeSettings settings;
    const gl::Texture* occupiedNeighbourhoods = nullptr;  ///< empty-space skipping (LightVolumeMedium)
    const VolumeClip* clip = nullptr;                     ///< the clip planes and crop box, if any
    const MeshShadowMaps* meshShadows = nullptr;  ///< hybrid scenes: meshes hide the lights (null: none)
};

class EyePass {
public:
    /// Recomputes the scattered light and sweeps it towards the viewer into eyeVolume().
    void run(const EyePassInputs& in);
    const gl::Texture& eyeVolume() const { return m_eyeVolume; }
    /// Frees the textures (the light volumes' resolution changed).
    void release();

private:
    /// lit_colour.comp by LIGHT_COUNT, the field's reconstruction and MESH_SHADOWS.
    using LitColourVariant = std::tuple<std::size_t, VolumeReconstruction, bool>;
    std::map<LitColourVariant, gl::Program> m_litColourPrograms;
    std::optional<LightVolumePass> m_sweep;
    gl::Texture m_litColour, m_eyeVolume;
};

}  // namespace sss::detail
