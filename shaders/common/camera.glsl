// The viewer, for shading: set by detail::setCameraUniforms (src/camera_uniforms.cpp).
uniform vec3 cameraPosition;
uniform vec3 cameraForward;      // unit view direction
uniform int cameraOrthographic;  // 1: all view rays are parallel to cameraForward

// Unit vector from a world-space point towards the viewer.
vec3 towardsViewer(vec3 worldPosition) {
    return cameraOrthographic != 0 ? -cameraForward : normalize(cameraPosition - worldPosition);
}
