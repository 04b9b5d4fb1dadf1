#include "lighting/camera_uniforms.h"

namespace sss::detail {

void setCameraUniforms(const gl::Program& program, const Camera& camera) {
    program.set("cameraPosition", camera.position());
    program.set("cameraForward", camera.forward());
    program.set("cameraOrthographic", camera.projectionType() == Projection::Orthographic ? 1 : 0);
}

}  // namespace sss::detail
