#pragma once
// Progressive GPU volume path tracing (VolumeRenderOptions::multipleScattering,
// shaders/volume/path_trace.comp): each accumulate() adds paths per pixel to running sums of
// (radiance, hit) in an RGBA32F texture; composite() draws their mean over the bound target.
// The estimator and its model are renderVolumePathTraced()'s (sss/volume_path_tracer.h).
#include "gl/program.h"
#include "gl/texture.h"
#include "gl/vertex_array.h"
#include "sss/camera.h"
#include "sss/light.h"
#include "sss/volume_scattering_renderer.h"
#include "volume/empty_space.h"
#include "volume/gpu_volume.h"

#include <glm/mat4x4.hpp>

#include <vector>

namespace sss::detail {

/// Majorants (sigma_t per model unit, R32F) per kBrickVoxels^3 brick of `grid`, from the
/// largest opacity its trilinear samples can reach (OccupancyGrid::maxOpacity), raised a little
/// so float rounding on the GPU stays below them.
gl::Texture brickMajorants(const OccupancyGrid& grid, float voxelLength);

/// What one accumulate() reads. References stay owned by the renderer.
struct PathTraceInputs {
    const GpuVolume& volume;
    const gl::Texture& transferFunction;
    const gl::Texture& majorants;   ///< brickMajorants()
    const gl::Texture& sceneDepth;  ///< a copy of the target's depth: camera rays stop there
    const glm::mat4& model;
    const std::vector<Light>& lights;
    const VolumeRenderOptions& options;  ///< samplesPerFrame, maxBounces, anisotropy
    const Camera& camera;
    float aspect = 1.0f;
    unsigned firstSample = 0;  ///< paths per pixel already in the sums (keys the random streams)
};

class PathTracePass {
public:
    PathTracePass();
    /// Adds options.samplesPerFrame paths per pixel to `sums` (RGBA32F, the target's size).
    void accumulate(const PathTraceInputs& in, const gl::Texture& sums) const;
    /// Draws sums / samples with premultiplied "over" into the bound target.
    void composite(const gl::Texture& sums, int samples) const;

private:
    gl::Program m_trace;
    gl::Program m_resolve;
    gl::VertexArray m_emptyVertexArray;  // core profile needs a VAO even without attributes
};

}  // namespace sss::detail
