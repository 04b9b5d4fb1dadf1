#include "volume/gpu_volume.h"

#include <algorithm>

namespace sss::detail {

GpuVolume GpuVolume::upload(const Volume& volume) {
    GpuVolume gpu;
    gpu.dims = volume.dims();
    gpu.box = volume.worldBounds();
    const bool wide = volume.type() == VoxelType::UInt16;
    gpu.texture = gl::Texture::create3D(wide ? GL_R16 : GL_R8, gpu.dims, "volume");
    gpu.texture.upload(GL_RED, wide ? GL_UNSIGNED_SHORT : GL_UNSIGNED_BYTE, volume.bytes().data());
    // Volume::transferFunctionRange() (raw lo..hi) onto the TF domain [0,1]; samples arrive
    // normalised by the type's maximum (255 or 65535).
    const auto [lo, hi] = volume.transferFunctionRange();
    const double typeMax = wide ? 65535.0 : 255.0;
    gpu.valueScaleOffset = {static_cast<float>(typeMax / (hi - lo)), static_cast<float>(-lo / (hi - lo))};
    const glm::vec3 voxel = gpu.box.size() / glm::vec3(gpu.dims);
    gpu.voxelLength = std::min({voxel.x, voxel.y, voxel.z});
    return gpu;
}

}  // namespace sss::detail
