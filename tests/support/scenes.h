#pragma once
// Small scene helpers shared by the GL tests.
#include <sss/bounds.h>
#include <sss/camera.h>
#include <sss/transfer_function.h>

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

}  // namespace sss::test
