// Scene lights, shared by the mesh and volume shaders. The CPU side (src/lighting/light_uniforms.cpp)
// fills these uniforms from sss::Light values.
//   lightVector[i].w == 0: directional; xyz = unit direction *towards* the light
//   lightVector[i].w == 1: point or spot light; xyz = world position
//   lightRadiance[i]   : colour * intensity
//   lightSpotAxis[i], lightSpotCosines[i]: a spot light's cone (unit axis, the way it points;
//                        cos outer, cos inner); (0, 0, 0) and (-2, -2) for other lights: no cone
#include "common/spot_cone.glsl"
#ifndef MAX_LIGHTS
#define MAX_LIGHTS 8  // kMaxLights in src/lighting/light_uniforms.h
#endif
uniform int lightCount;
uniform vec4 lightVector[MAX_LIGHTS];
uniform vec3 lightRadiance[MAX_LIGHTS];
uniform vec3 lightSpotAxis[MAX_LIGHTS];
uniform vec2 lightSpotCosines[MAX_LIGHTS];

// The share of positional light i's intensity it sends towards `position`: its spot cone's
// factor, 1 for a point light.
float lightConeAt(int i, vec3 position) {
    vec3 fromLight = position - lightVector[i].xyz;
    float len = length(fromLight);
    return spotConeFactor(lightSpotCosines[i], len > 0.0 ? dot(fromLight, lightSpotAxis[i]) / len : 1.0);
}

// Unit vector from `position` towards light i, and the radiance arriving there
// (point and spot lights fall off with the inverse square of the distance; spots with their cone).
vec3 lightDirectionAt(int i, vec3 position, out vec3 radiance) {
    if (lightVector[i].w == 0.0) {
        radiance = lightRadiance[i];
        return lightVector[i].xyz;
    }
    vec3 toLight = lightVector[i].xyz - position;
    float distanceSquared = max(dot(toLight, toLight), 1e-8);
    vec3 towards = toLight * inversesqrt(distanceSquared);
    float cone = spotConeFactor(lightSpotCosines[i], -dot(towards, lightSpotAxis[i]));
    radiance = lightRadiance[i] * cone / distanceSquared;
    return towards;
}
