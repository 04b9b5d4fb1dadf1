// The near field (mesh/near_field.glsl) and each light's visibility (the single scattering's)
// evaluated once per light change at the points of every triangle's grid
// (mesh/near_field_points.glsl), for the combine pass to interpolate per pixel: they depend on
// the lights and the surface, not on the camera, so a camera move reuses them.
layout(local_size_x = 64) in;

#define NEAR_FIELD_CURVATURE 1
#include "mesh/near_field.glsl"
#include "mesh/near_field_points.glsl"

#include "mesh/mesh_vertices.glsl"
layout(std430, binding = 1) readonly buffer Indices { uint indexData[]; };
layout(std430, binding = 2) readonly buffer PointTriangles { uint triangleOfPoint[]; };
layout(std430, binding = 3) readonly buffer Triangles { uint nearFieldTriangle[]; };
// Per point texelsPerPoint RGBA16F texels (as pairs of halves): the near field before the exit
// Fresnel factor, summed over the lights, and light 0's selfVisibility; then lights 1-4's, 5-7's.
layout(std430, binding = 4) writeonly buffer Points { uvec2 pointTexels[]; };
uniform int texelsPerPoint;
uniform int pointCount;
uniform mat4 model;
uniform mat3 normalMatrix;
uniform float eta;

// The triangle's normal variation (near_field.glsl), world space; zero for a degenerate one.
NormalVariation normalVariation(uint a, uint b, uint c) {
    vec3 pa = meshPosition(a), e1 = meshPosition(b) - pa, e2 = meshPosition(c) - pa;
    float d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2), det = d11 * d22 - d12 * d12;
    NormalVariation v = NormalVariation(vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0));
    if (!(det > 1e-12 * d11 * d22)) return v;
    vec3 na = normalize(normalMatrix * meshNormal(a));
    v.dnB = normalize(normalMatrix * meshNormal(b)) - na;
    v.dnC = normalize(normalMatrix * meshNormal(c)) - na;
    v.toB = normalMatrix * ((d22 * e1 - d12 * e2) / det);  // model-space gradients to world space
    v.toC = normalMatrix * ((d11 * e2 - d12 * e1) / det);
    return v;
}

void main() {
    int s = int(gl_GlobalInvocationID.x);
    if (s >= pointCount) return;
    uint t = triangleOfPoint[s];
    uint entry = nearFieldTriangle[t];
    vec3 w = nearFieldPointWeights(s - nearFieldFirstPoint(entry), nearFieldDivisions(entry));
    uint a = indexData[3 * t], b = indexData[3 * t + 1], c = indexData[3 * t + 2];
    vec3 p = w.x * meshPosition(a) + w.y * meshPosition(b) + w.z * meshPosition(c);
    vec3 n = normalMatrix * (w.x * meshNormal(a) + w.y * meshNormal(b) + w.z * meshNormal(c));
    float length2 = dot(n, n);
    n = length2 > 0.0 ? n * inversesqrt(length2) : vec3(0.0, 0.0, 1.0);
    vec3 x = (model * vec4(p, 1.0)).xyz;
    vec3 nearLight = nearFieldRadiosity(x, n, eta, normalVariation(a, b, c));
    float visible[12] = float[12](0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);  // 3 texels' worth
    for (int i = 0; i < lightCount; ++i) {
        vec3 radiance;
        visible[i] = selfVisibility(i, x, n, lightDirectionAt(i, x, radiance));
    }
    pointTexels[texelsPerPoint * s] = uvec2(packHalf2x16(nearLight.rg), packHalf2x16(vec2(nearLight.b, visible[0])));
    for (int k = 1; k < texelsPerPoint; ++k)
        pointTexels[texelsPerPoint * s + k] = uvec2(packHalf2x16(vec2(visible[4 * k - 3], visible[4 * k - 2])),
                                                    packHalf2x16(vec2(visible[4 * k - 1], visible[4 * k])));
}
