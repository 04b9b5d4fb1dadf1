// With TEXTURED_MATERIAL a third target holds a textured material's ln gathered, by which the
// radiosity estimate weighs the entry points (shaders/mesh/textured_material.glsl).
#ifndef TEXTURED_MATERIAL
#define TEXTURED_MATERIAL 0
#endif
#if TEXTURED_MATERIAL
#include "mesh/textured_material.glsl"
#endif
in vec3 worldPosition;
in vec3 worldNormal;
in vec2 texcoord;
layout(location = 0) out vec4 outPosition;  // w = 1 marks a covered texel (cleared to 0)
layout(location = 1) out vec4 outNormal;
#if TEXTURED_MATERIAL
layout(location = 2) out vec4 outLogGathered;
#endif
void main() {
    vec3 n = normalize(worldNormal);
    // Two-sided: the surface the light sees faces it, whichever way the mesh winds.
    if (!gl_FrontFacing) n = -n;
    outPosition = vec4(worldPosition, 1.0);
    outNormal = vec4(n, 0.0);
#if TEXTURED_MATERIAL
    // Level 0: a coarser level (grazing light) would average colours the texel does not hold.
    outLogGathered = vec4(logGathered(texcoord), 1.0);
#endif
}
