#include "support/light_volumes.h"

#include "gl/texture.h"
#include "volume/empty_space.h"
#include "volume/gpu_volume.h"

#include <glm/geometric.hpp>

#include <optional>
#include <utility>

namespace sss::test::light_volumes {

Volume makeVolume(int n, const std::function<uint8_t(int, int, int)>& value) {
    std::vector<uint8_t> bytes(static_cast<size_t>(n * n * n));
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) bytes[static_cast<size_t>((z * n + y) * n + x)] = value(x, y, z);
    return Volume::fromData({n, n, n}, VoxelType::UInt8, std::move(bytes));
}

TransferFunction stepTf(float opacity, glm::vec3 color) {
    return TransferFunction({{0.0f, color, 0.0f}, {0.49f, color, 0.0f}, {0.51f, color, opacity}, {1.0f, color, opacity}});
}

Volume twoBlobsVolume() {
    return makeVolume(48, [](int x, int y, int z) {
        const auto inside = [&](glm::vec3 c, float r) { return glm::length(glm::vec3(x, y, z) + 0.5f - c) < r; };
        return (inside({14, 15, 18}, 6.0f) || inside({33, 30, 26}, 5.0f)) ? 200 : 20;
    });
}
TransferFunction twoBlobsTf() {
    return TransferFunction({{0.0f, {0.9f, 0.5f, 0.3f}, 0.0f}, {0.45f, {0.9f, 0.5f, 0.3f}, 0.0f},
                             {0.55f, {0.3f, 0.6f, 0.9f}, 0.8f}, {1.0f, {0.3f, 0.6f, 0.9f}, 0.8f}});
}

const SweepCase kSweepCases[4] = {{DirectionalLight{.direction = {0.8f, -0.7f, 0.35f}}, 1.0f},
                                  {DirectionalLight{.direction = {0.05f, 1.0f, 0.02f}}, 1.0f},
                                  {PointLight{.position = {0.02f, -0.05f, 0.1f}}, 1.0f},
                                  {DirectionalLight{.direction = {0.8f, -0.5f, 0.35f}}, 0.35f}};

LightVolumeReadback propagate(const Volume& volume, const TransferFunction& tf, const Light& light,
                              detail::LightVolumeSettings settings, Skipping skipping,
                              detail::LightVolumePass::SweepLayout* layout, const VolumeClip* clip) {
    const detail::GpuVolume gpu = detail::GpuVolume::upload(volume);
    const std::vector<glm::vec4> table = tf.table(256);
    gl::Texture tfTexture = gl::Texture::create2D(GL_RGBA32F, 256, 1, "test transfer function");
    tfTexture.upload(GL_RGBA, GL_FLOAT, table.data());
    std::optional<detail::OccupancyGrid> occupancy;
    if (skipping.on) {
        occupancy.emplace(volume);
        occupancy->update(skipping.skipTf ? skipping.skipTf->table(256) : table, gpu.valueScaleOffset,
                          VolumeReconstruction::Trilinear);
    }
    detail::LightVolumePass pass;
    gl::Texture output;
    pass.run({.volume = gpu,
              .transferFunction = tfTexture,
              .occupiedNeighbourhoods = occupancy ? &occupancy->occupiedNeighbourhoods() : nullptr,
              .clip = clip},
             light, glm::mat4(1.0f), settings, output);
    if (layout) *layout = pass.lastLayout();
    const size_t count = static_cast<size_t>(output.size().x * output.size().y * output.size().z);
    LightVolumeReadback r{output.size(), std::vector<glm::vec4>(count)};
    if (output.internalFormat() == GL_R16F) {
        // The intensity alone, which sampling returns as (1, 1, 1, l) (the texture's swizzle;
        // reading the image back ignores it).
        std::vector<float> intensity(count);
        glGetTextureImage(output.id(), 0, GL_RED, GL_FLOAT, static_cast<GLsizei>(count * sizeof(float)), intensity.data());
        for (size_t i = 0; i < count; ++i) r.texels[i] = glm::vec4(1.0f, 1.0f, 1.0f, intensity[i]);
    } else {
        glGetTextureImage(output.id(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(count * sizeof(glm::vec4)),
                          r.texels.data());
    }
    return r;
}

}  // namespace sss::test::light_volumes
