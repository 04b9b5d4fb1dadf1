#pragma once
// A Volume uploaded as a 3D texture (R8 or R16, normalised), plus what shaders need to map its
// samples and its box. Shared by every volume pass.
#include "gl/texture.h"
#include "sss/bounds.h"
#include "sss/volume.h"

#include <glm/vec2.hpp>

namespace sss::detail {

struct GpuVolume {
    gl::Texture texture;
    glm::ivec3 dims{0};
    Bounds box;                  ///< model-space box (Volume::worldBounds)
    glm::vec2 valueScaleOffset;  ///< maps a normalised sample to the TF's [0,1] domain
    float voxelLength = 0;       ///< smallest voxel edge in model units (the opacity reference)

    static GpuVolume upload(const Volume& volume);
};

/// The value of the shaders' CUBIC_RECONSTRUCTION (volume/reconstruction.glsl) for `r`.
inline const char* cubicReconstructionDefine(VolumeReconstruction r) {
    return r == VolumeReconstruction::CubicBSpline ? "1" : "0";
}

}  // namespace sss::detail
