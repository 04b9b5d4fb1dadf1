// Scattering maps (Dal Corso et al. 2017, pass 2): each texel adds one frame's estimate of the
// radiosity at its surface point (shaders/mesh/radiosity_estimate.glsl).
// With TEXTURED_MATERIAL each texel gathers with its own point's profile and stores the radiosity
// divided by what that profile gathers under even light (shaders/mesh/textured_material.glsl).
#ifndef TEXTURED_MATERIAL
#define TEXTURED_MATERIAL 0
#endif
#include "mesh/radiosity_estimate.glsl"
#if TEXTURED_MATERIAL
#include "mesh/textured_material.glsl"
#endif

in vec3 worldPosition;
in vec3 worldNormal;
in vec2 texcoord;

layout(location = 0) out vec4 outRadiosity;

void main() {
    uint state = uint(gl_FragCoord.x) * 1973u + uint(gl_FragCoord.y) * 9277u + uint(gl_Layer) * 26699u + frameSeed * 104729u;
    pcg(state);
#if TEXTURED_MATERIAL
    SurfaceMaterial material = materialAt(dipole, texcoord, textureQueryLod(materialReflectance, texcoord).y);
    vec3 radiosity = estimateRadiosity(material.params, worldPosition, normalize(worldNormal), state);
    outRadiosity = vec4(radiosity / max(material.gathered, vec3(1e-9)), 1.0);
#else
    outRadiosity = vec4(estimateRadiosity(dipole, worldPosition, normalize(worldNormal), state), 1.0);
#endif
}
