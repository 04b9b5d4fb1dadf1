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
    // 8-bit data maps 0..255 onto the TF domain as is (the thesis's convention); 16-bit data
    // usually fills only part of its range (12-bit CT), so its actual min..max is used.
    if (wide) {
        const auto [lo, hi] = volume.valueRange();
        const float range = std::max(1.0f, static_cast<float>(hi) - static_cast<float>(lo));
        gpu.valueScaleOffset = {65535.0f / range, -static_cast<float>(lo) / range};
    } else {
        gpu.valueScaleOffset = {1.0f, 0.0f};
    }
    const glm::vec3 voxel = gpu.box.size() / glm::vec3(gpu.dims);
    gpu.voxelLength = std::min({voxel.x, voxel.y, voxel.z});
    return gpu;
}

}  // namespace sss::detail
