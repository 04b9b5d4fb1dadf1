#include "volume/gpu_volume.h"

#include "core/voxel_storage.h"

#include <algorithm>

namespace sss::detail {

GpuVolume GpuVolume::upload(const Volume& volume) {
    GpuVolume gpu;
    gpu.dims = volume.dims();
    gpu.box = volume.worldBounds();
    // Texture formats and what a sample holds: see voxel_storage.h.
    switch (volume.type()) {
    case VoxelType::UInt8:
        gpu.texture = gl::Texture::create3D(GL_R8, gpu.dims, "volume");
        gpu.texture.upload(GL_RED, GL_UNSIGNED_BYTE, volume.bytes().data());
        break;
    case VoxelType::UInt16:
        gpu.texture = gl::Texture::create3D(GL_R16, gpu.dims, "volume");
        gpu.texture.upload(GL_RED, GL_UNSIGNED_SHORT, volume.bytes().data());
        break;
    case VoxelType::Int16: {
        // Biased to unsigned codes (sign bit flipped) so R16 unorm holds every value exactly.
        std::vector<uint16_t> codes(volume.voxelCount());
        for (std::size_t i = 0; i < codes.size(); ++i)
            codes[i] = static_cast<uint16_t>(storageCode(volume.bytes().data(), VoxelType::Int16, i));
        gpu.texture = gl::Texture::create3D(GL_R16, gpu.dims, "volume");
        gpu.texture.upload(GL_RED, GL_UNSIGNED_SHORT, codes.data());
        break;
    }
    case VoxelType::Float32: {
        std::vector<float> samples(volume.voxelCount());
        const StorageToRaw m = storageToRaw(volume);
        for (std::size_t i = 0; i < samples.size(); ++i) samples[i] = floatSample(volume.bytes().data(), i, m);
        gpu.texture = gl::Texture::create3D(GL_R32F, gpu.dims, "volume");
        gpu.texture.upload(GL_RED, GL_FLOAT, samples.data());
        break;
    }
    }
    // Volume::transferFunctionRange() (raw lo..hi) onto the TF domain [0,1].
    gpu.valueScaleOffset = glm::vec2(sampleToTfCoordinate(volume));
    const glm::vec3 voxel = gpu.box.size() / glm::vec3(gpu.dims);
    gpu.voxelLength = std::min({voxel.x, voxel.y, voxel.z});
    return gpu;
}

}  // namespace sss::detail
