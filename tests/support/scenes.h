#pragma once
// Small scene helpers shared by the GL tests.
#include <sss/bounds.h>
#include <sss/camera.h>
#include <sss/image.h>
#include <sss/transfer_function.h>
#include <sss/volume.h>

#include <glm/vec3.hpp>

#include <cstdint>
#include <utility>
#include <vector>

namespace sss::test {

/// A camera framed on `bounds`, orbited to (yaw, pitch) degrees and moved in to 70 % of the
/// framing distance, so the object fills more of the small test images.
inline Camera orbitCamera(const Bounds& bounds, float yaw, float pitch) {
    Camera camera;
    camera.frame(bounds);
    camera.setYaw(yaw);
    camera.setPitch(pitch);
    camera.setDistance(camera.distance() * 0.7f);
    return camera;
}

/// The transfer function the tests use on makeBlobsVolume(): transparent below 0.2, orange to
/// light blue above, with opacity up to 0.6 per voxel times `opacityScale`.
inline TransferFunction blobsTransferFunction(float opacityScale = 1.0f) {
    return TransferFunction({{0.0f, {0, 0, 0}, 0.0f},
                             {0.2f, {0.9f, 0.4f, 0.1f}, 0.0f},
                             {0.5f, {1.0f, 0.8f, 0.3f}, 0.15f * opacityScale},
                             {1.0f, {0.4f, 0.7f, 1.0f}, 0.6f * opacityScale}});
}

/// A bright, high-albedo transfer function for makeBlobsVolume(): multiple scattering carries
/// about as much light as single scattering with it (the path tracer's and the cache's tests).
inline TransferFunction highAlbedoBlobsTransferFunction(glm::vec3 albedo = {0.95f, 0.85f, 0.7f}) {
    return TransferFunction({{0.0f, albedo, 0.0f}, {0.2f, albedo, 0.0f}, {0.5f, albedo, 0.25f}, {1.0f, albedo, 0.6f}});
}

/// A bright uniform cube, 16^3 voxels of opacity 0.3 (world bounds [-0.5, 0.5]^3): one cell per
/// voxel for a 16-cell multiple-scattering cache. Its transfer function: brightCubeTransferFunction.
inline const Volume& brightCube() {
    static const Volume cube =
        Volume::fromData({16, 16, 16}, VoxelType::UInt8, std::vector<std::uint8_t>(16 * 16 * 16, 255));
    return cube;
}
inline TransferFunction brightCubeTransferFunction() {
    return TransferFunction({{0.0f, glm::vec3(0.9f), 0.3f}, {1.0f, glm::vec3(0.9f), 0.3f}});
}

/// Each channel's sum over `image` (rgb).
inline glm::dvec3 channelSums(const Image& image) {
    glm::dvec3 sum(0.0);
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) sum += glm::dvec3(glm::vec3(image.at(x, y)));
    return sum;
}

/// Sum of `test`'s rgb over the sum of `reference`'s.
inline double meanRatio(const Image& test, const Image& reference) {
    const glm::dvec3 a = channelSums(test), b = channelSums(reference);
    return (a.x + a.y + a.z) / (b.x + b.y + b.z);
}

/// 32^3 uint8: a block (x in [4, 12), y and z in [6, 26)) of 200 and, when `wall`, a wall
/// (x in [24, 28)) of 255 between it and a light travelling towards -x; 0 elsewhere.
inline Volume blockAndWallVolume(bool wall) {
    constexpr int n = 32;
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(n * n * n));
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const bool inner = y >= 6 && y < 26 && z >= 6 && z < 26;
                std::uint8_t& v = bytes[static_cast<std::size_t>((z * n + y) * n + x)];
                v = inner && x >= 4 && x < 12 ? 200 : (wall && x >= 24 && x < 28 ? 255 : 0);
            }
    return Volume::fromData({n, n, n}, VoxelType::UInt8, std::move(bytes));
}

}  // namespace sss::test
