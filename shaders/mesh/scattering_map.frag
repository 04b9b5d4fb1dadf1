// Scattering maps (Dal Corso et al. 2017, pass 2): each texel adds one frame's estimate of the
// radiosity at its surface point (shaders/mesh/radiosity_estimate.glsl).
#include "mesh/radiosity_estimate.glsl"

in vec3 worldPosition;
in vec3 worldNormal;

layout(location = 0) out vec4 outRadiosity;

void main() {
    uint state = uint(gl_FragCoord.x) * 1973u + uint(gl_FragCoord.y) * 9277u + uint(gl_Layer) * 26699u + frameSeed * 104729u;
    pcg(state);
    outRadiosity = vec4(estimateRadiosity(worldPosition, normalize(worldNormal), state), 1.0);
}
