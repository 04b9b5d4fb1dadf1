// Scattering maps (Dal Corso et al. 2017, pass 2): each texel adds one frame's estimate of the
// radiosity at its surface point (shaders/mesh/radiosity_estimate.glsl).
// With TEXTURED_MATERIAL each texel gathers with its own point's profile and stores the radiosity
// times the textured rule's entries' part (shaders/mesh/textured_material.glsl), each frame's mean
// taken over that frame's samples.
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
    vec3 logWeighted;
    vec3 radiosity = estimateRadiosity(material.params, worldPosition, normalize(worldNormal), state, logWeighted);
    vec3 gathered = max(material.gathered, vec3(MIN_GATHERED));
    vec3 meanLog = mix(log(gathered), logWeighted / max(radiosity, vec3(1e-30)), greaterThan(radiosity, vec3(0.0)));
    outRadiosity = vec4(radiosity / gathered * entriesFactor(meanLog), 1.0);
#else
    vec3 logWeighted;
    outRadiosity = vec4(estimateRadiosity(dipole, worldPosition, normalize(worldNormal), state, logWeighted), 1.0);
#endif
}
