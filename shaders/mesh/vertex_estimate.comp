// Evaluate-once radiosity (sss::MeshCombine::VertexEstimate): the radiosity estimated directly at
// each vertex, once per frame, instead of in every scattering-map texel that sees the point. Each
// frame adds samplesPerLight more samples to the vertex's running sum, continuing one
// low-discrepancy sequence per vertex (VERTEX_SEQUENCE: on the bunny at N = 24 it measured 3.8 %
// against 5.7 % with independent random samples); the combine pass reads the mean, interpolated
// over each triangle (shaders/mesh/combine.vert).
// With a near field (shaders/mesh/near_field.glsl), which the combine pass adds per pixel, a
// vertex keeps the light from beyond its radius (outer) plus, weighted per channel by
// nearFieldCorrection, how much the light from within it (inner) differs from the near field's
// flat-surface value at the vertex: creases, shadow edges and thin parts there. Such a
// difference lives within a few mean free paths of the vertex, where most of the profile's light
// enters; on triangles much wider than that, interpolation spreads it over the whole triangle,
// so the weight falls with the triangles' width in mean free paths (src/mesh/near_field.h).
// Where a vertex faces away from the lights, it takes the whole difference: there the near field
// holds nothing but the light that diffuses past a smooth terminator, and what comes across a
// fold or a crease is all the vertices carry (on the 2 m Buddha 120 of its 187 resolved specks;
// spread over a dark triangle it costs little: docs/near-field.md).
// With TEXTURED_MATERIAL each vertex gathers with its own texel's profile and stores the
// radiosity times the textured rule's entries' part (textured_material.glsl), their mean over all
// its frames; the near field, tabulated for the untextured reference material, is scaled to the
// vertex's gathered. A second output holds the entries' part alone, by which the combine scales
// the near field and the environment per pixel.
layout(local_size_x = 64) in;

#define VERTEX_SEQUENCE 1
#ifndef TEXTURED_MATERIAL
#define TEXTURED_MATERIAL 0
#endif
#include "mesh/radiosity_estimate.glsl"
#include "mesh/near_field.glsl"
#if TEXTURED_MATERIAL
#include "mesh/textured_material.glsl"
#endif

#include "mesh/mesh_vertices.glsl"
// Per vertex: inner, outer (rgb summed over frames, a: frames) and, textured, logWeighted.
layout(std430, binding = 1) buffer Sums { vec4 sums[]; };
layout(std430, binding = 2) writeonly buffer Radiosity { vec4 radiosityOut[]; };
#if TEXTURED_MATERIAL
layout(std430, binding = 3) writeonly buffer Effective { vec4 effectiveOut[]; };
#endif
uniform int vertexCount;
uniform mat4 model;
uniform mat3 normalMatrix;
uniform vec3 nearFieldCorrection;  // per channel, in [0, 1]

// The share of the lights' radiance at x that x faces away from (cos theta below -0.05, a ramp
// to +0.05): where the vertex takes the whole near-field difference.
float facingAwayShare(vec3 x, vec3 n) {
    float away = 0.0, total = 0.0;
    for (int i = 0; i < lightCount; ++i) {
        vec3 radiance;
        vec3 l = lightDirectionAt(i, x, radiance);
        float weight = dot(radiance, vec3(0.2126, 0.7152, 0.0722));
        away += weight * clamp(0.5 - 10.0 * dot(n, l), 0.0, 1.0);
        total += weight;
    }
    return total > 0.0 ? away / total : 0.0;
}

void main() {
    int i = int(gl_GlobalInvocationID.x);
    if (i >= vertexCount) return;
    vec3 p = meshPosition(uint(i));
    vec3 n = normalMatrix * meshNormal(uint(i));
    float length2 = dot(n, n);
    n = length2 > 0.0 ? n * inversesqrt(length2) : vec3(0.0, 0.0, 1.0);
    uint state = uint(i) * 9277u + 0x9e3779b9u;  // the same per frame: the sequence continues
    pcg(state);
    vec3 x = (model * vec4(p, 1.0)).xyz;
    vec3 inner, outer, logWeighted;
#if TEXTURED_MATERIAL
    SurfaceMaterial material = materialAt(dipole, meshTexcoord(uint(i)), 0.0);
    estimateRadiositySplit(material.params, x, n, state, inner, outer, logWeighted);
    vec3 gathered = max(material.gathered, vec3(MIN_GATHERED));
    vec3 nearFieldScale = gathered / max(referenceGathered, vec3(1e-6)) * nearFieldShareAt(vec3(material.params.albedo));
#else
    estimateRadiositySplit(dipole, x, n, state, inner, outer, logWeighted);
    vec3 nearFieldScale = vec3(1.0);
#endif
    vec4 innerSum = (frameSeed == 0u ? vec4(0.0) : sums[3 * i]) + vec4(inner, 1.0);
    vec4 outerSum = (frameSeed == 0u ? vec4(0.0) : sums[3 * i + 1]) + vec4(outer, 1.0);
    sums[3 * i] = innerSum;
    sums[3 * i + 1] = outerSum;
    vec3 difference = innerSum.rgb / innerSum.a - nearFieldScale * nearFieldRadiosity(x, n, dipole.eta);
    vec3 weight = mix(nearFieldCorrection, vec3(1.0), facingAwayShare(x, n));
    vec3 radiosity = outerSum.rgb / outerSum.a + weight * difference;
#if TEXTURED_MATERIAL
    vec3 logSum = (frameSeed == 0u ? vec3(0.0) : sums[3 * i + 2].rgb) + logWeighted;
    sums[3 * i + 2] = vec4(logSum, 0.0);
    vec3 total = innerSum.rgb + outerSum.rgb;
    vec3 meanLog = mix(log(gathered), logSum / max(total, vec3(1e-30)), greaterThan(total, vec3(0.0)));
    radiosityOut[i] = vec4(radiosity / gathered * entriesFactor(meanLog), 1.0);
    effectiveOut[i] = vec4(entriesFactor(meanLog), 1.0);
#else
    radiosityOut[i] = vec4(radiosity, 1.0);
#endif
}
