// The profile's near field (src/mesh/near_field.h): the light that enters within nearRadius of
// a point, for a locally flat surface lit like the point itself. The vertex estimate subtracts
// it at each vertex and the combine pass adds it back per pixel, so the interpolated part is
// what varies slowly and the per-pixel part keeps the detail a triangle cannot hold.
#ifndef NEAR_FIELD_NODES
#define NEAR_FIELD_NODES 33  // kNearFieldNodes
#endif
#ifndef TEXTURED_MATERIAL
#define TEXTURED_MATERIAL 0
#endif
#ifndef NEAR_FIELD_TAPS
#define NEAR_FIELD_TAPS 12  // kNearFieldTaps
#endif
#include "mesh/light_buffer_lookup.glsl"
#include "common/dirpole.glsl"
#include "common/surface_shadows.glsl"

uniform int nearFieldOn;                   // 0: no near field (the table is zero)
uniform vec3 nearField[NEAR_FIELD_NODES];  // per unit irradiance at cos theta = i / (NEAR_FIELD_NODES - 1)
uniform float nearFieldTapRadius[NEAR_FIELD_TAPS];  // on the light's disk, world units
uniform vec3 nearFieldTapWeight[NEAR_FIELD_TAPS];   // per channel, summing to 1
uniform vec3 nearFieldBehind[NEAR_FIELD_NODES];     // per unit irradiance at depth behindDepth (i / (N - 1))^2
uniform float nearFieldBehindDepth;                 // scene units; nothing from there on
#if TEXTURED_MATERIAL
// Per reduced albedo 1 - (1 - i / (N - 1))^2: the share of a flat surface's light within the
// near field's radius for that albedo's material over the table's (the widest) material.
uniform vec3 nearFieldTexturedShare[NEAR_FIELD_NODES];

vec3 nearFieldShareAt(vec3 albedo) {
    vec3 f = (1.0 - sqrt(1.0 - clamp(albedo, 0.0, 1.0))) * float(NEAR_FIELD_NODES - 1);
    vec3 share;
    for (int c = 0; c < 3; ++c) {
        int i = min(int(f[c]), NEAR_FIELD_NODES - 2);
        share[c] = mix(nearFieldTexturedShare[i][c], nearFieldTexturedShare[i + 1][c], f[c] - float(i));
    }
    return share;
}
#endif

// The depth a surface must lie in front of x to hide it: lightBufferBias where x faces the light;
// a surface facing away is never what the light sees.
float nearFieldBehindBias(vec3 n, vec3 toLight) {
    return dot(n, toLight) > 0.0 ? lightBufferBias(n, toLight) : 2.0 * lightTexelWorld;
}

vec3 nearFieldAt(float cosTheta) {
    float f = clamp(cosTheta, 0.0, 1.0) * float(NEAR_FIELD_NODES - 1);
    int i = min(int(f), NEAR_FIELD_NODES - 2);
    return mix(nearField[i], nearField[i + 1], f - float(i));
}

// max(c, 0) N(c): the flat near field's light per unit irradiance where cos theta = c.
vec3 nearFieldLit(float c) { return max(c, 0.0) * nearFieldAt(c); }

#ifndef NEAR_FIELD_CURVATURE
#define NEAR_FIELD_CURVATURE 0
#endif
#if NEAR_FIELD_CURVATURE
#define NEAR_FIELD_RING_NODES 33  // kNearFieldRingNodes
// Per tap (src/mesh/near_field.h, NearFieldRingTable): (outer radius), (mean r^2), then per
// node (H), (Q) at t = outer (2 i / (N - 1) - 1).
layout(std430, binding = 5) readonly buffer NearFieldRings { vec4 nearFieldRing[]; };

// Per channel, how much of the rings' rise to take (src/mesh/near_field_cache.cpp: what the
// vertices' correction leaves out).
uniform vec3 nearFieldCurvature;

vec3 nearFieldAt(vec3 cosTheta) {
    return vec3(nearFieldAt(cosTheta.r).r, nearFieldAt(cosTheta.g).g, nearFieldAt(cosTheta.b).b);
}

// Tap k's annulus on a surface whose cos theta is c at x and rises by g per unit length towards
// the light: the light entering it per unit irradiance. Its mean lit cos theta is g H, and the
// table N is read at that mean weighted by itself, g Q / H. Beyond the terminator (c < 0) this is
// the light that diffuses over from the side that turns towards the light.
vec3 nearFieldRingLit(int k, float c, float g) {
    int base = k * (2 + 2 * NEAR_FIELD_RING_NODES);
    float outer = nearFieldRing[base].x, t = -c / g;
    vec3 h, q;
    if (!(t > -outer)) {  // every ring lit (also g = 0 with c > 0)
        h = vec3(-t);
        q = vec3(t * t) + 0.5 * nearFieldRing[base + 1].xyz;
    } else if (!(t < outer)) {
        return vec3(0.0);
    } else {
        float f = 0.5 * (t / outer + 1.0) * float(NEAR_FIELD_RING_NODES - 1);
        int i = min(int(f), NEAR_FIELD_RING_NODES - 2);
        int at = base + 2 + 2 * i;
        h = mix(nearFieldRing[at].xyz, nearFieldRing[at + 2].xyz, f - float(i));
        q = mix(nearFieldRing[at + 1].xyz, nearFieldRing[at + 3].xyz, f - float(i));
    }
    vec3 meanCos = g * h, weightedCos = g * q / max(h, vec3(1e-30));
    return meanCos * nearFieldAt(weightedCos);
}
#endif

// Light l over the near field's disk around x, per channel weighted by the profile: `visible`,
// the share that reaches the surface around x (a shadow's edge blurred as the subsurface light
// blurs it); `covered`, the share where a surface in front of x hides it (how much of the near
// field behind is there: less at the edge of a thin part); `lit`, the light entering the visible
// share per unit irradiance, for a surface whose cos theta changes by `slope` per unit length
// towards the light (0: flat). Taps closer than half a light-buffer texel are the centre's.
void nearFieldTaps(int l, vec3 x, vec3 n, vec3 toLight, float slope, out vec3 visible, out vec3 covered,
                   out vec3 lit) {
    float bias = lightBufferBias(n, toLight), behindBias = nearFieldBehindBias(n, toLight);
    vec2 centre = lightSeenAround(l, x, bias, x, behindBias);
    vec3 u = normalize(abs(toLight.x) < 0.9 ? cross(toLight, vec3(1, 0, 0)) : cross(toLight, vec3(0, 1, 0)));
    vec3 v = cross(toLight, u);
    float cosTheta = dot(n, toLight), nDotL = max(cosTheta, 0.05);
    vec3 flatLit = nearFieldLit(cosTheta);
    visible = vec3(0.0);
    covered = vec3(0.0);
    lit = vec3(0.0);
    for (int k = 0; k < NEAR_FIELD_TAPS; ++k) {
        float r = nearFieldTapRadius[k];
        vec2 seen = centre;
        if (r > 0.5 * lightTexelWorld) {
            float phi = 2.39996323 * float(k);  // the golden angle
            vec3 d = r * (cos(phi) * u + sin(phi) * v);
            d -= toLight * (dot(d, n) / nDotL);  // along the light onto the tangent plane
            seen = lightSeenAround(l, x + d, bias, x, behindBias);
        }
        visible += nearFieldTapWeight[k] * seen.x;
        covered += nearFieldTapWeight[k] * seen.y;
#if NEAR_FIELD_CURVATURE
        vec3 ringLit = slope > 0.0 ? mix(flatLit, nearFieldRingLit(k, cosTheta, slope), nearFieldCurvature) : flatLit;
#else
        vec3 ringLit = flatLit;
#endif
        lit += nearFieldTapWeight[k] * seen.x * ringLit;
    }
}

vec3 nearFieldBehindAt(float depth) {
    if (!(depth < nearFieldBehindDepth)) return vec3(0.0);
    float f = sqrt(max(depth, 0.0) / nearFieldBehindDepth) * float(NEAR_FIELD_NODES - 1);
    int i = min(int(f), NEAR_FIELD_NODES - 2);
    return mix(nearFieldBehind[i], nearFieldBehind[i + 1], f - float(i));
}

// The near field behind x, per unit radiance of light l: where the surface light l sees at x's
// texel lies in front of x (a thin part lit from behind, an overhang), the light entering it
// near x, taken as a flat surface through the point seen, lit at its own angle, at its depth
// along the light times that angle's cosine from x, weighted by how far it faces away from x. Blended over the 2x2 texels around x, then
// scaled by the share of the disk such a surface covers (`covered`, from nearFieldTaps) over
// the centre's own.
vec3 nearFieldBehindRadiosity(int l, vec3 x, vec3 n, vec3 toLight, float eta, vec3 covered) {
    LightTexels t = lightTexelsAround(l, x);
    if (!t.inside) return vec3(0.0);
    float behindBias = nearFieldBehindBias(n, toLight);
    vec3 sum = vec3(0.0);
    float centreCovered = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec3 texel = lightTexel(t, k, l);
        vec4 seen = texelFetch(lightPositions, texel, 0);
        float depth = depthBehind(l, seen.xyz, x, toLight);
        if (seen.w < 0.5 || depth <= behindBias) continue;
        float w = lightTexelWeight(t, k);
        centreCovered += w;
        vec3 ns = normalize(texelFetch(lightNormals, texel, 0).xyz);
        // The model is a surface facing away from x (the far side of a thin part). One facing
        // the way x does lies on x's own side: beside a terminator it is the same surface
        // curving away, whose light the vertices already carry (it drew a bright band there).
        float cosSeen = dot(ns, toLight), facing = -dot(ns, n);
        if (cosSeen <= 0.0 || facing <= 0.0) continue;
        sum += w * facing * cosSeen * dirpoleFresnelT(eta, cosSeen) * nearFieldBehindAt(depth * cosSeen) *
               volumeTransmittance(l, seen.xyz, toLight) * meshShadow(l, seen.xyz, ns, toLight, 0);
    }
    return centreCovered > 1e-3 ? sum * min(covered / centreCovered, vec3(1.0)) : vec3(0.0);
}

// How the interpolated normal varies across a triangle, world space: moving by dp changes
// n . d by (dot(dnB, d) toB + dot(dnC, d) toC) . dp (all zero: a flat near field).
struct NormalVariation {
    vec3 dnB, dnC;  // corner b's and c's unit normal less corner a's
    vec3 toB, toC;  // the gradients of corner b's and c's barycentric weights
};

// Sum over the lights of the near field at x (unit normal n), before the exit Fresnel factor:
// in front where the light reaches x, behind where a lit surface hides it.
vec3 nearFieldRadiosity(vec3 x, vec3 n, float eta, NormalVariation variation) {
    vec3 sum = vec3(0.0);
    if (nearFieldOn == 0) return sum;
    for (int i = 0; i < lightCount; ++i) {
        vec3 radiance, visible, covered, lit;
        vec3 l = lightDirectionAt(i, x, radiance);
        vec3 gradient = dot(variation.dnB, l) * variation.toB + dot(variation.dnC, l) * variation.toC;
        float slope = length(gradient - n * dot(gradient, n));
        nearFieldTaps(i, x, n, l, slope, visible, covered, lit);
        sum += radiance * nearFieldBehindRadiosity(i, x, n, l, eta, covered);
        sum += radiance * lit * volumeTransmittance(i, x, l) * meshShadow(i, x, n, l, 0);
    }
    return sum;
}

vec3 nearFieldRadiosity(vec3 x, vec3 n, float eta) {
    return nearFieldRadiosity(x, n, eta, NormalVariation(vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0)));
}
