#pragma once
// Small scene helpers shared by the GL tests.
#include <sss/bounds.h>
#include <sss/camera.h>

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

}  // namespace sss::test
