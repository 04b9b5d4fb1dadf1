// Attenuation of each light by a scattering volume, for mesh shading in hybrid scenes: the
// light-volume intensity l where the light's ray leaves the volume box towards the point (at the
// point itself inside the box). 1 where no volume is set. See src/hybrid/shared_lighting.h.
#include "common/ray_box.glsl"

#ifndef MAX_LIGHTS
#define MAX_LIGHTS 8
#endif
uniform int volumeShadowEnabled;
uniform sampler3D volumeShadowLight[MAX_LIGHTS];
uniform mat4 volumeShadowWorldToTexture;

float volumeTransmittance(int light, vec3 worldPosition, vec3 towardsLight) {
    if (volumeShadowEnabled == 0) return 1.0;
    vec3 p = (volumeShadowWorldToTexture * vec4(worldPosition, 1.0)).xyz;
    vec3 d = mat3(volumeShadowWorldToTexture) * towardsLight;
    // Where the ray from the point towards the light enters the unit box, if it does.
    vec3 inv = safeInverse(d);
    vec3 t0 = (vec3(0.0) - p) * inv, t1 = (vec3(1.0) - p) * inv;
    vec3 tNear = min(t0, t1), tFar = max(t0, t1);
    float enter = max(max(tNear.x, tNear.y), max(tNear.z, 0.0));
    float exit = min(min(tFar.x, tFar.y), tFar.z);
    if (enter > exit) return 1.0;
    return texture(volumeShadowLight[light], p + enter * d).a;
}
