#pragma once
// Single-pass GPU ray casting of a volume with a transfer function (shaders/volume/ray_cast.frag):
// emission-absorption or gradient-shaded, front to back, early ray termination, opacity
// correction and per-pixel jitter.
#include "gl/program.h"
#include "gl/texture.h"
#include "gl/vertex_array.h"
#include "sss/camera.h"
#include "sss/volume_scattering_renderer.h"
#include "hybrid/shared_lighting.h"
#include "volume/empty_space.h"
#include "volume/gpu_volume.h"

#include <vector>

namespace sss::detail {

/// Scattering modes sample light volumes.
bool usesLightVolume(VolumeShading shading);

class RayCastPass {
public:
    RayCastPass(VolumeShading shading, bool emptySpaceSkipping, std::size_t lightCount, bool eyePass);
    /// Whether this pass was built for these options and lights (programs are per variant).
    bool matches(const VolumeRenderOptions& o, std::size_t lightCount) const {
        const bool eyePass = o.eyePass && usesLightVolume(o.shading);
        return o.shading == m_shading && o.emptySpaceSkipping == m_emptySpaceSkipping && lightCount == m_lightCount &&
               eyePass == m_eyePass;
    }
    /// `sceneDepth` is a copy of the target's depth (rays stop there); `lightVolumes` has one
    /// texture per light in the scattering modes. The target is bound.
    void run(const GpuVolume& volume, const gl::Texture& transferFunction, const gl::Texture& sceneDepth,
             const gl::Texture& occupancy, const std::vector<gl::Texture>& lightVolumes,
             const MeshShadowMaps* meshShadows, const gl::Texture* eyeVolume, const glm::mat4& model, const std::vector<Light>& lights,
             const VolumeRenderOptions& options, const Camera& camera, float aspect) const;

private:
    static constexpr int kFirstLightVolumeUnit = 4;  // 0 volume, 1 TF, 2 scene depth, 3 occupancy
    static constexpr int kMeshShadowUnit = 12;       // after the light volumes (4..11)
    VolumeShading m_shading;
    bool m_emptySpaceSkipping;
    std::size_t m_lightCount;
    bool m_eyePass;
    static constexpr int kEyeVolumeUnit = 13;
    gl::Program m_program;
    gl::VertexArray m_emptyVertexArray;  // core profile needs a VAO even without attributes
};

}  // namespace sss::detail
