// Hybrid scenes (MESH_SHADOWS 1): the meshes seen from each light (shadow maps, one layer per
// light: src/lighting/shadows.h, MeshShadowMaps) block its direct light. The ray caster, the
// paper model's eye pass, the multiple-scattering cache's photons and the path tracer's
// next-event estimation all read them here, so meshes shadow single and multiple scattering alike.
#if MESH_SHADOWS
uniform sampler2DArray meshShadowDepth;
uniform mat4 worldToShadowClip[MAX_LIGHTS];
uniform vec4 meshShadowLight[MAX_LIGHTS];  // world space: unit vector towards the light (w 0) or its position (w 1)
uniform float meshShadowTexel;             // world size of one shadow-map texel at the scene
#endif

// 1 where light `light` reaches world-space point w past the meshes, 0 behind one. Outside a
// light's map, and behind a point light, nothing casts a shadow.
float meshVisibility(int light, vec3 w) {
#if !MESH_SHADOWS
    return 1.0;
#else
    vec4 l = meshShadowLight[light];
    vec3 towards = l.w != 0.0 ? l.xyz - w : l.xyz;
    towards = dot(towards, towards) > 0.0 ? normalize(towards) : vec3(0.0);
    // Tested two texels towards the light, not with a bias in window depth: a point light's
    // perspective map compresses depth so much that such a bias let its light through a mesh
    // to points a third of the scene behind it.
    vec4 clip = worldToShadowClip[light] * vec4(w + 2.0 * meshShadowTexel * towards, 1.0);
    if (clip.w <= 0.0) return 1.0;
    vec3 window = clip.xyz / clip.w * 0.5 + 0.5;
    if (any(lessThan(window, vec3(0.0))) || any(greaterThan(window, vec3(1.0)))) return 1.0;
    return window.z > texture(meshShadowDepth, vec3(window.xy, float(light))).r ? 0.0 : 1.0;
#endif
}
