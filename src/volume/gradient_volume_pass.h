#pragma once
// The gradient volume: central differences of the data per voxel, computed once per data set on
// the GPU (shaders/volume/gradient.comp) into an RGBA16_SNORM 3D texture (8 bytes per voxel), so
// the gradient shading modes read one texel per sample instead of six.
#include "gl/program.h"
#include "gl/texture.h"
#include "volume/gpu_volume.h"

namespace sss::detail {

class GradientVolumePass {
public:
    GradientVolumePass();
    /// Allocates (checked against the GPU's limits and the memory budget: throws Error
    /// GpuLimit when it does not fit) and fills the gradient volume of `volume`.
    gl::Texture run(const GpuVolume& volume) const;

private:
    gl::Program m_program;
};

}  // namespace sss::detail
