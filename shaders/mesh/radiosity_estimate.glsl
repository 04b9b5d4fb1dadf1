// The radiosity at a surface point (Dal Corso et al. 2017): light scattered to x_o, a Monte Carlo
// estimate of
//   sum_lights  integral over the lit surface of  T(eta, w_i.n_i) S_d(x_i, w_i; x_o) E_l dA_perp
// where dA_perp is area as seen from the light. Samples lie on a disk of radius R around x_o in
// the plane facing the light; the surface point x_i behind each is read from the light buffer.
// Their distance from x_o is exponentially biased towards x_o. Where Dal Corso draws uniform
// points and keeps them with probability exp(-sigma* r), we draw r directly from exp(-lambda r)
// (no proposal is wasted), and mix two rates with the balance heuristic: sigma* for the
// far, diffuse tail and the reduced extinction for the steep near field, whose 1/r^2-like peak
// would otherwise produce fireflies. Each sample is weighted by 1 / (N pdf).
// The exit Fresnel factor T(eta, w_o) is view-dependent and applied in the combine pass.
// Shared by the scattering maps (per texel, shaders/mesh/scattering_map.frag) and the evaluate-once
// vertex estimate (per vertex, shaders/mesh/vertex_estimate.comp); the uniforms are set by
// setRadiosityEstimateUniforms (src/mesh/radiosity_estimate.h).
#ifndef VERTEX_SEQUENCE
#define VERTEX_SEQUENCE 0
#endif
#ifndef TEXTURED_MATERIAL
#define TEXTURED_MATERIAL 0
#endif
#include "mesh/light_buffer_lookup.glsl"
#include "common/dirpole.glsl"
#include "common/surface_shadows.glsl"

#if TEXTURED_MATERIAL
uniform sampler2DArray lightLogGathered;  // a textured material's ln gathered per light-buffer texel
#endif
uniform DirpoleParams dipole;
uniform float diskRadius;                 // R, scene units
uniform float nearRadius;                 // estimateRadiositySplit's split, scene units
uniform float sigmaStar;                  // far-field sampling rate, scene units^-1
uniform float sigmaNear;                  // near-field sampling rate (>= sigmaStar)
uniform int samplesPerLight;              // N proposals per light
uniform uint frameSeed;                   // differs per accumulated frame

// PCG hash (O'Neill): a well-mixed 32-bit random stream per pixel, layer and frame.
uint pcg(inout uint state) {
    state = state * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}
float random01(inout uint state) { return float(pcg(state) >> 8) * (1.0 / 16777216.0); }

// p: the profile at x_o (`dipole`, or a textured material's at the point,
// docs/textured-materials.md); xo, no: world-space point and unit normal; state: the caller's
// random stream. The estimate comes in two parts: the light entering within nearRadius of x_o on
// the disk (inner) and the rest (outer). Textured, logWeighted sums each sample's value times its
// entry texel's ln gathered (0 otherwise).
void estimateRadiositySplit(DirpoleParams profile, vec3 xo, vec3 no, inout uint state, out vec3 inner, out vec3 outer,
                            out vec3 logWeighted) {
    inner = vec3(0.0);
    outer = vec3(0.0);
    logWeighted = vec3(0.0);
    const float twoPi = 6.28318531;
    for (int l = 0; l < lightCount; ++l) {
        bool point = lightVector[l].w != 0.0;
        // The disk faces the light: its normal is the direction the light travels towards x_o.
        vec3 axis = point ? normalize(xo - lightVector[l].xyz) : -lightVector[l].xyz;
        vec3 u = normalize(abs(axis.x) < 0.9 ? cross(axis, vec3(1, 0, 0)) : cross(axis, vec3(0, 1, 0)));
        vec3 v = cross(axis, u);
#if VERTEX_SEQUENCE
        // One low-discrepancy sequence per vertex across all its frames (R3, Roberts 2018), under
        // a random rotation fixed per vertex and light: sample i of the vertex's whole estimate.
        vec3 rotation = vec3(random01(state), random01(state), random01(state));
#endif
        for (int s = 0; s < samplesPerLight; ++s) {
#if VERTEX_SEQUENCE
            uint i = frameSeed * uint(samplesPerLight) + uint(s);
            vec3 q = fract(rotation + float(i) * vec3(0.8191725134, 0.6710436067, 0.5497004779));
            float rate = q.x < 0.5 ? sigmaNear : sigmaStar;
            float r = -log(1.0 - q.y * (1.0 - exp(-rate * diskRadius))) / rate;
            float phi = twoPi * q.z;
#else
            // Truncated exponential in r on [0, R], rate chosen at random from the two.
            float rate = random01(state) < 0.5 ? sigmaNear : sigmaStar;
            float r = -log(1.0 - random01(state) * (1.0 - exp(-rate * diskRadius))) / rate;
            float phi = twoPi * random01(state);
#endif
            if (!(r > 0.0)) continue;
            // Area density of the mixture at r: each rate gives rate e^(-rate r) / (1 - e^(-rate R)) / (2 pi r).
            float pdf = 0.5 * (sigmaNear * exp(-sigmaNear * r) / (1.0 - exp(-sigmaNear * diskRadius)) +
                               sigmaStar * exp(-sigmaStar * r) / (1.0 - exp(-sigmaStar * diskRadius))) / (twoPi * r);
            vec3 p = xo + r * (cos(phi) * u + sin(phi) * v);
            vec4 clip = lightViewProjection[l] * vec4(p, 1.0);
            vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
            if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) continue;
            // The bilinear blend of the four texels around uv lies on the surface only if they all
            // hold one surface. At a depth edge as seen from the light (a chin over the chest) it
            // would float in the air between the two, right beside the shadowed surface, where the
            // profile's near field makes it bright. One surface tilted by theta spreads the four
            // texels' depths along the light by tan(theta) times their spread across it: a spread
            // above 4 (76 degrees) is taken for an edge, and the nearest texel used instead.
            vec3 layer = vec3(uv, float(l));
            vec4 gx = textureGather(lightPositions, layer, 0), gy = textureGather(lightPositions, layer, 1),
                 gz = textureGather(lightPositions, layer, 2), gw = textureGather(lightPositions, layer, 3);
            bool oneSurface = all(greaterThan(gw, vec4(0.999)));
            if (oneSurface) {
                vec4 depth = gx * axis.x + gy * axis.y + gz * axis.z;
                float depthSpread = max(max(depth.x, depth.y), max(depth.z, depth.w)) -
                                    min(min(depth.x, depth.y), min(depth.z, depth.w));
                vec3 diagonal = vec3(gx.x - gx.z, gy.x - gy.z, gz.x - gz.z);
                float across = length(diagonal - dot(diagonal, axis) * axis);
                oneSurface = depthSpread <= 4.0 * across;
            }
            vec4 xiTexel;
            vec3 ni;
            vec3 entryLog = vec3(0.0);  // the entry texel's ln gathered (textured materials)
            if (oneSurface) {
                xiTexel = texture(lightPositions, layer);
                ni = normalize(texture(lightNormals, layer).xyz);
#if TEXTURED_MATERIAL
                entryLog = texture(lightLogGathered, layer).rgb;
#endif
            } else {
                // An edge, or a neighbour texel is empty: the nearest texel. Dropping the sample
                // would darken every point near a silhouette as seen from the light.
                ivec3 nearest = ivec3(clamp(ivec2(uv * vec2(textureSize(lightPositions, 0).xy)), ivec2(0),
                                            textureSize(lightPositions, 0).xy - 1), l);
                xiTexel = texelFetch(lightPositions, nearest, 0);
                if (xiTexel.w < 0.5) continue;  // no surface there
                ni = normalize(texelFetch(lightNormals, nearest, 0).xyz);
#if TEXTURED_MATERIAL
                entryLog = texelFetch(lightLogGathered, nearest, 0).rgb;
#endif
            }
            vec3 xi = xiTexel.xyz;
            vec3 irradiance;  // per unit disk area
            vec3 wi;
            if (point) {
                vec3 toLight = lightVector[l].xyz - p;
                float d2 = dot(toLight, toLight);
                // Disk area dA_p subtends dw = cos dA_p / |p - L|^2 from the light, and the surface
                // behind it receives I dw in total (the 1/|x_i - L|^2 falloff cancels against the
                // area growth): per unit disk area, I cos / |p - L|^2. A spot light's I is
                // what its cone sends along the ray through p (and on to x_i).
                float cosDisk = max(dot(normalize(-toLight), axis), 0.0);
                irradiance = lightRadiance[l] * cosDisk / d2 * lightConeAt(l, p);
                wi = normalize(lightVector[l].xyz - xi);
            } else {
                irradiance = lightRadiance[l];
                wi = -axis;
            }
            // Volumes and other meshes between the light and x_i (one tap: the samples spread
            // over the disk filter the shadow's edge).
            irradiance *= volumeTransmittance(l, xi, wi) * meshShadow(l, xi, dot(ni, wi) < 0.0 ? -ni : ni, wi, 0);
            float entryT = dirpoleFresnelT(profile.eta, dot(wi, ni));
            vec3 value = dirpoleSd(profile, xi, ni, wi, xo, no) * (entryT / pdf) * irradiance;
            if (r < nearRadius) inner += value;
            else outer += value;
#if TEXTURED_MATERIAL
            logWeighted += value * entryLog;
#endif
        }
    }
    inner /= float(samplesPerLight);
    outer /= float(samplesPerLight);
    logWeighted /= float(samplesPerLight);
}

vec3 estimateRadiosity(DirpoleParams profile, vec3 xo, vec3 no, inout uint state, out vec3 logWeighted) {
    vec3 inner, outer;
    estimateRadiositySplit(profile, xo, no, state, inner, outer, logWeighted);
    return inner + outer;
}
