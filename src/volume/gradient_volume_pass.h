#pragma once
// The gradient volume: central differences of the data per voxel, computed once per data set on
// the GPU (shaders/volume/gradient.comp), so the gradient shading modes read one texel per sample
// instead of six. With unorm data the fourth channel holds the data value, and the ray caster
// takes both from one fetch. 8-bit data get an RGBA8 texel (4 bytes per voxel), the rest RGBA16
// (8 bytes): software rasterisers filter 8-bit texels on a fast fixed-point path, and an RGBA8
// gradient frame is about a tenth faster on llvmpipe (benchmarks/README.md, Table 5.4).
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

/// How a gradient texel holds the differences d (in [-1, 1], normalised value units): as
/// d * scale + offset. RGBA8 keeps zero exact (128 / 255) and steps of 1 / 127, one bit short of
/// the 511 central differences of 8-bit data: a gradient component is off by at most 1 / 508 of
/// the value range per voxel, so a normal turns by up to about 8 degrees at the default
/// gradientThreshold's gradient (0.02) and by under 1 degree from 0.2 up (the errors this costs,
/// measured: benchmarks/README.md, "The gradient volume in RGBA8"). RGBA16 holds every
/// difference of 8- and 16-bit data.
struct GradientEncoding {
    float scale;
    float offset;
    /// d = texel * decodeScale() + decodeOffset().
    float decodeScale() const { return 1.0f / scale; }
    float decodeOffset() const { return -offset / scale; }
};

/// The gradient volume's texel format for this volume: RGBA8 for 8-bit data, else RGBA16.
inline GLenum gradientFormatFor(const GpuVolume& volume) {
    return volume.texture.internalFormat() == GL_R8 ? GL_RGBA8 : GL_RGBA16;
}

/// The encoding of a gradient texel format (gradientFormatFor's).
inline GradientEncoding gradientEncoding(GLenum gradientFormat) {
    if (gradientFormat == GL_RGBA8) return {127.0f / 255.0f, 128.0f / 255.0f};
    return {0.5f, 0.5f};
}

/// Whether run() stores the data value in the fourth channel (unorm data), or 0 (float data,
/// whose values need not lie in [0, 1]).
inline bool gradientVolumeHoldsValues(const GpuVolume& volume) { return volume.texture.internalFormat() != GL_R32F; }

}  // namespace sss::detail
