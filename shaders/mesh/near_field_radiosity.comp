// The points of the near field (mesh/near_field_points.glsl) with the vertices' radiosity added,
// interpolated to each point: untextured, the combine then reads one value per point where it
// would read the near field from the points and the radiosity from the vertices (a vertex
// storage read and an interpolated value per corner of every triangle drawn). Light 0's
// visibility and the other lights' texels are copied as they are. In full floats: the sum's dim
// values (the radiosity far from the light) lose too much as halves.
layout(local_size_x = 64) in;

#include "mesh/near_field_points.glsl"

layout(std430, binding = 0) readonly buffer Indices { uint indexData[]; };
layout(std430, binding = 1) readonly buffer PointTriangles { uint triangleOfPoint[]; };
layout(std430, binding = 2) readonly buffer Triangles { uint nearFieldTriangle[]; };
layout(std430, binding = 3) readonly buffer VertexRadiosity { vec4 radiosityOfVertex[]; };
// texelsPerPoint RGBA16F texels per point, as pairs of halves (near_field_cache.comp).
layout(std430, binding = 4) readonly buffer NearField { uvec2 nearFieldTexels[]; };
layout(std430, binding = 5) writeonly buffer Points { vec4 pointTexels[]; };  // as NearField, RGBA32F
uniform int texelsPerPoint;
uniform int pointCount;

void main() {
    int s = int(gl_GlobalInvocationID.x);
    if (s >= pointCount) return;
    uint t = triangleOfPoint[s];
    uint entry = nearFieldTriangle[t];
    vec3 w = nearFieldPointWeights(s - nearFieldFirstPoint(entry), nearFieldDivisions(entry));
    vec3 radiosity = w.x * radiosityOfVertex[indexData[3 * t]].rgb + w.y * radiosityOfVertex[indexData[3 * t + 1]].rgb +
                     w.z * radiosityOfVertex[indexData[3 * t + 2]].rgb;
    int first = texelsPerPoint * s;
    for (int k = 0; k < texelsPerPoint; ++k) {
        uvec2 halves = nearFieldTexels[first + k];
        vec4 texel = vec4(unpackHalf2x16(halves.x), unpackHalf2x16(halves.y));
        pointTexels[first + k] = k == 0 ? texel + vec4(radiosity, 0.0) : texel;
    }
}
