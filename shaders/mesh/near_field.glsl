// The profile's near field (src/mesh/near_field.h): the light that enters within nearRadius of
// a point, for a locally flat surface lit like the point itself. The vertex estimate subtracts
// it at each vertex and the combine pass adds it back per pixel, so the interpolated part is
// what varies slowly and the per-pixel part keeps the detail a triangle cannot hold.
#ifndef NEAR_FIELD_NODES
#define NEAR_FIELD_NODES 33  // kNearFieldNodes
#endif
#ifndef NEAR_FIELD_TAPS
#define NEAR_FIELD_TAPS 8  // kNearFieldTaps
#endif
#include "mesh/light_buffer_lookup.glsl"
#include "common/surface_shadows.glsl"

uniform int nearFieldOn;                   // 0: no near field (the table is zero)
uniform vec3 nearField[NEAR_FIELD_NODES];  // per unit irradiance at cos theta = i / (NEAR_FIELD_NODES - 1)
uniform float nearFieldTapRadius[NEAR_FIELD_TAPS];  // on the light's disk, world units
uniform vec3 nearFieldTapWeight[NEAR_FIELD_TAPS];   // per channel, summing to 1

vec3 nearFieldAt(float cosTheta) {
    float f = clamp(cosTheta, 0.0, 1.0) * float(NEAR_FIELD_NODES - 1);
    int i = min(int(f), NEAR_FIELD_NODES - 2);
    return mix(nearField[i], nearField[i + 1], f - float(i));
}

// Light l's visibility over the near field's disk around x, per channel weighted by the profile:
// a shadow's edge blurred as the subsurface light blurs it. Taps closer than half a light-buffer
// texel are the centre's.
vec3 nearFieldVisibility(int l, vec3 x, vec3 n, vec3 toLight) {
    float centre = selfVisibility(l, x, n, toLight);
    vec3 u = normalize(abs(toLight.x) < 0.9 ? cross(toLight, vec3(1, 0, 0)) : cross(toLight, vec3(0, 1, 0)));
    vec3 v = cross(toLight, u);
    float nDotL = max(dot(n, toLight), 0.05);
    vec3 sum = vec3(0.0);
    for (int k = 0; k < NEAR_FIELD_TAPS; ++k) {
        float r = nearFieldTapRadius[k];
        float visible = centre;
        if (r > 0.5 * lightTexelWorld) {
            float phi = 2.39996323 * float(k);  // the golden angle
            vec3 d = r * (cos(phi) * u + sin(phi) * v);
            d -= toLight * (dot(d, n) / nDotL);  // along the light onto the tangent plane
            visible = selfVisibility(l, x + d, n, toLight);
        }
        sum += nearFieldTapWeight[k] * visible;
    }
    return sum;
}

// Sum over the lights of the near field at x (unit normal n), before the exit Fresnel factor.
vec3 nearFieldRadiosity(vec3 x, vec3 n) {
    vec3 sum = vec3(0.0);
    if (nearFieldOn == 0) return sum;
    for (int i = 0; i < lightCount; ++i) {
        vec3 radiance;
        vec3 l = lightDirectionAt(i, x, radiance);
        float nDotL = dot(n, l);
        if (nDotL <= 0.0) continue;
        sum += nDotL * radiance * nearFieldVisibility(i, x, n, l) * volumeTransmittance(i, x, l) *
               meshShadow(i, x, n, l, 0) * nearFieldAt(nDotL);
    }
    return sum;
}
