// With TEXTURED_MATERIAL a third target holds the entry weight of a textured material, its
// reflectance to the power ENTRY_REFLECTANCE_EXPONENT (shaders/mesh/textured_material.glsl).
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
layout(location = 2) out vec4 outEntryWeight;
#endif
void main() {
    vec3 n = normalize(worldNormal);
    // Two-sided: the surface the light sees faces it, whichever way the mesh winds.
    if (!gl_FrontFacing) n = -n;
    outPosition = vec4(worldPosition, 1.0);
    outNormal = vec4(n, 0.0);
#if TEXTURED_MATERIAL
    outEntryWeight = vec4(entryWeight(texcoord, textureQueryLod(materialReflectance, texcoord).y), 1.0);
#endif
}
