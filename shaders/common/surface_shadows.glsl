// What shadows a mesh surface from each light in a hybrid scene (src/lighting/shadows.h):
//  - the meshes, through shadow maps seen from the lights (meshShadow);
//  - every volume, through its light volumes (volumeTransmittance): the light-volume value
//    (c, l) where the light's ray leaves the volume box towards the point (at the point itself
//    inside the box), so the light arrives tinted by c and dimmed by l.
// Both give 1 where nothing is set. With SURFACE_SHADOWS 0 (a scene where nothing shadows the
// surface: src/lighting/shadows.h, castsSurfaceShadows) both are the constant 1, and their
// uniforms do not exist.
#ifndef SURFACE_SHADOWS
#define SURFACE_SHADOWS 1
#endif
#include "common/ray_box.glsl"

#ifndef MAX_LIGHTS
#define MAX_LIGHTS 8
#endif
#define MAX_VOLUME_SHADOW_PAIRS 16  // kMaxVolumeShadowPairs in src/lighting/shadows.h

#if !SURFACE_SHADOWS
float meshShadow(int light, vec3 p, vec3 n, vec3 towardsLight, int radius) { return 1.0; }
vec3 volumeTransmittance(int light, vec3 worldPosition, vec3 towardsLight) { return vec3(1.0); }
#else

uniform int meshShadowEnabled;
uniform sampler2DArray meshShadowDepth;       // per light
uniform usampler2DArray meshShadowIds;        // 1 + index of the nearest mesh, 0: none
uniform mat4 meshShadowWorldToClip[MAX_LIGHTS];
uniform float meshShadowTexel;                // world size of one shadow-map texel
uniform uint meshShadowSelf;                  // this surface's id in the maps (0: not in them),
                                              // whose own entries never shadow it

uniform int volumeShadowCount;
uniform sampler3D volumeShadowLight[MAX_VOLUME_SHADOW_PAIRS];  // volume v, light i: v * lightCount + i
uniform mat4 volumeShadowWorldToTexture[MAX_VOLUME_SHADOW_PAIRS];

// Fraction of light `light` reaching p past the meshes. n: the surface normal on the light's side;
// towardsLight: unit vector; radius: percentage-closer filter radius in texels (0: one tap).
float meshShadow(int light, vec3 p, vec3 n, vec3 towardsLight, int radius) {
    if (meshShadowEnabled == 0) return 1.0;
    // Offset along the normal and towards the light by about a texel each: the surface's own
    // depth, rasterised at the neighbouring texel centre, must not shadow it (acne).
    vec3 q = p + meshShadowTexel * (1.5 * n + towardsLight);
    vec4 clip = meshShadowWorldToClip[light] * vec4(q, 1.0);
    if (clip.w <= 0.0) return 1.0;  // behind a point light
    vec3 window = clip.xyz / clip.w * 0.5 + 0.5;
    // The maps frame every caster: outside them nothing is in the way. Beyond the far plane
    // (Cornell box walls), anything in the map is in front.
    if (any(lessThan(window.xy, vec2(0.0))) || any(greaterThan(window.xy, vec2(1.0)))) return 1.0;
    window.z = clamp(window.z, 0.0, 1.0);
    ivec2 size = textureSize(meshShadowDepth, 0).xy;
    // Percentage-closer filtering with bilinear weights: each tap blends the four comparisons
    // around it, so the shadow's edge is smooth rather than a staircase of texels.
    vec2 texelPosition = window.xy * vec2(size) - 0.5;
    ivec2 base = ivec2(floor(texelPosition));
    vec2 t = texelPosition - vec2(base);
    float lit = 0.0;
    for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx) {
            vec4 corner;
            for (int j = 0; j < 4; ++j) {
                ivec3 texel = ivec3(clamp(base + ivec2(dx + (j & 1), dy + (j >> 1)), ivec2(0), size - 1), light);
                bool occluded = texelFetch(meshShadowDepth, texel, 0).r < window.z &&
                                texelFetch(meshShadowIds, texel, 0).r != meshShadowSelf;
                corner[j] = occluded ? 0.0 : 1.0;
            }
            lit += mix(mix(corner[0], corner[1], t.x), mix(corner[2], corner[3], t.x), t.y);
        }
    float side = float(2 * radius + 1);
    return lit / (side * side);
}

// Light `light` arriving at p through every volume: tint times intensity, per channel.
vec3 volumeTransmittance(int light, vec3 worldPosition, vec3 towardsLight) {
    vec3 transmitted = vec3(1.0);
    for (int v = 0; v < volumeShadowCount; ++v) {
        int pair = v * lightCount + light;
        vec3 p = (volumeShadowWorldToTexture[v] * vec4(worldPosition, 1.0)).xyz;
        vec3 d = mat3(volumeShadowWorldToTexture[v]) * towardsLight;
        // Where the ray from the point towards the light enters the unit box, if it does.
        vec3 inv = safeInverse(d);
        vec3 t0 = (vec3(0.0) - p) * inv, t1 = (vec3(1.0) - p) * inv;
        vec3 tNear = min(t0, t1), tFar = max(t0, t1);
        float enter = max(max(tNear.x, tNear.y), max(tNear.z, 0.0));
        float exit = min(min(tFar.x, tFar.y), tFar.z);
        if (enter > exit) continue;
        vec4 arriving = texture(volumeShadowLight[pair], p + enter * d);
        transmitted *= arriving.rgb * arriving.a;
    }
    return transmitted;
}
#endif  // SURFACE_SHADOWS
