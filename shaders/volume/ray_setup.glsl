// Ray through the current pixel, in the volume's model space (the volume box spans
// [boxMin, boxMax]). Works for perspective and orthographic cameras because the ray is built
// by unprojecting the pixel at the near and far planes.
#include "common/ray_box.glsl"

uniform mat4 inverseViewProjection;
uniform mat4 worldToModel;

struct Ray {
    vec3 origin;     // model space, on the near plane
    vec3 direction;  // unit length
    float tMax;      // distance to the far plane
};

Ray pixelRay(vec2 ndc) {
    vec4 nearWorld = inverseViewProjection * vec4(ndc, -1.0, 1.0);
    vec4 farWorld = inverseViewProjection * vec4(ndc, 1.0, 1.0);
    vec3 nearModel = (worldToModel * vec4(nearWorld.xyz / nearWorld.w, 1.0)).xyz;
    vec3 farModel = (worldToModel * vec4(farWorld.xyz / farWorld.w, 1.0)).xyz;
    vec3 d = farModel - nearModel;
    float len = length(d);
    return Ray(nearModel, d / len, len);
}

// Slab test; returns (tEnter, tExit), empty when tEnter >= tExit.
vec2 intersectBox(Ray ray, vec3 boxMin, vec3 boxMax) {
    vec3 inv = safeInverse(ray.direction);
    vec3 t0 = (boxMin - ray.origin) * inv;
    vec3 t1 = (boxMax - ray.origin) * inv;
    vec3 tNear = min(t0, t1), tFar = max(t0, t1);
    float enter = max(max(tNear.x, tNear.y), max(tNear.z, 0.0));
    float exit = min(min(tFar.x, tFar.y), min(tFar.z, ray.tMax));
    return vec2(enter, exit);
}

// Interleaved gradient noise (Jimenez 2014): a per-pixel offset in [0,1) that breaks up
// wood-grain artifacts without temporal flicker (the same pixel always gets the same value).
float pixelJitter(vec2 fragCoord) {
    return fract(52.9829189 * fract(dot(fragCoord, vec2(0.06711056, 0.00583715))));
}
