// Hybrid scenes (MESH_SHADOWS 1): the meshes seen from each light (shadow maps, one layer per
// light: src/lighting/shadows.h, MeshShadowMaps) block its direct light. The ray caster, the
// multiple-scattering cache's photons and the path tracer's next-event estimation all read them
// here, so meshes shadow single and multiple scattering alike.
#if MESH_SHADOWS
uniform sampler2DArray meshShadowDepth;
uniform mat4 worldToShadowClip[MAX_LIGHTS];
uniform float meshShadowBias;
#endif

// 1 where light `light` reaches world-space point w past the meshes, 0 behind one. Outside a
// light's map nothing casts a shadow.
float meshVisibility(int light, vec3 w) {
#if !MESH_SHADOWS
    return 1.0;
#else
    vec4 clip = worldToShadowClip[light] * vec4(w, 1.0);
    vec3 window = clip.xyz / clip.w * 0.5 + 0.5;
    if (any(lessThan(window, vec3(0.0))) || any(greaterThan(window, vec3(1.0)))) return 1.0;
    return window.z - meshShadowBias > texture(meshShadowDepth, vec3(window.xy, float(light))).r ? 0.0 : 1.0;
#endif
}
