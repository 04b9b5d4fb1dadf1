#pragma once
// The gradient volume: central differences of the data per voxel, computed once per data set on
// the GPU (shaders/volume/gradient.comp) into an RGBA16 3D texture (8 bytes per voxel), so the
// gradient shading modes read one texel per sample instead of six. The differences are stored
// as d / 2 + 1/2; with unorm data (8 and 16 bit, whose values are exact in 16 bits) the fourth
// channel holds the data value, and the ray caster takes both from one fetch.
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

/// Whether run() stores the data value in the fourth channel (unorm data), or 0 (float data,
/// whose values need not lie in [0, 1]).
inline bool gradientVolumeHoldsValues(const GpuVolume& volume) { return volume.texture.internalFormat() != GL_R32F; }

}  // namespace sss::detail
