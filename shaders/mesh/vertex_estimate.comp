// Evaluate-once radiosity (sss::MeshCombine::VertexEstimate): the radiosity estimated directly at
// each vertex, once per frame, instead of in every scattering-map texel that sees the point. Each
// frame adds samplesPerLight more samples to the vertex's running sum, continuing one
// low-discrepancy sequence per vertex (VERTEX_SEQUENCE: on the bunny at N = 24 it measured 3.8 %
// against 5.7 % with independent random samples); the combine pass reads the mean, interpolated
// over each triangle (shaders/mesh/combine.vert).
layout(local_size_x = 64) in;

#define VERTEX_SEQUENCE 1
#include "mesh/radiosity_estimate.glsl"

layout(std430, binding = 0) readonly buffer Vertices { float vertexData[]; };  // model space: position, normal
layout(std430, binding = 1) buffer Sums { vec4 sums[]; };                      // rgb summed over frames, a: frames
layout(std430, binding = 2) writeonly buffer Radiosity { vec4 radiosityOut[]; };
uniform int vertexCount;
uniform mat4 model;
uniform mat3 normalMatrix;

void main() {
    int i = int(gl_GlobalInvocationID.x);
    if (i >= vertexCount) return;
    vec3 p = vec3(vertexData[6 * i], vertexData[6 * i + 1], vertexData[6 * i + 2]);
    vec3 n = normalMatrix * vec3(vertexData[6 * i + 3], vertexData[6 * i + 4], vertexData[6 * i + 5]);
    float length2 = dot(n, n);
    n = length2 > 0.0 ? n * inversesqrt(length2) : vec3(0.0, 0.0, 1.0);
    uint state = uint(i) * 9277u + 0x9e3779b9u;  // the same per frame: the sequence continues
    pcg(state);
    vec4 sum = (frameSeed == 0u ? vec4(0.0) : sums[i]) + vec4(estimateRadiosity((model * vec4(p, 1.0)).xyz, n, state), 1.0);
    sums[i] = sum;
    radiosityOut[i] = vec4(sum.rgb / sum.a, 1.0);
}
