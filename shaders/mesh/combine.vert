// The combine's vertices (shaders/mesh/combine.frag). With NEAR_FIELD 2 every triangle's
// corners arrive apart (GpuMesh::drawCornersOpaque: vertex 3t + k is corner k of triangle t) and the
// shader reads the mesh itself, so each fragment gets its triangle's near-field grid as a flat
// value and where it lies in the grid as interpolated weights, instead of fetching them per
// pixel: on small triangles a fragment costs about what its triangle does.
#ifndef VERTEX_EFFECTIVE
#define VERTEX_EFFECTIVE 0
#endif
#ifndef NEAR_FIELD
#define NEAR_FIELD 1
#endif
#ifndef TEXTURED_MATERIAL
#define TEXTURED_MATERIAL 0
#endif
#define CORNERS_APART (NEAR_FIELD == 2)
// Untextured, the near field's points hold the radiosity too (mesh/near_field_radiosity.comp).
#define RADIOSITY_IN_POINTS (NEAR_FIELD == 2 && !TEXTURED_MATERIAL)
uniform mat4 model;
uniform mat4 viewProjection;
uniform mat3 normalMatrix;
out vec3 modelPosition;
out vec3 modelNormal;
out vec3 worldPosition;
out vec3 worldNormal;
out vec2 texcoord;
#if !RADIOSITY_IN_POINTS
out vec3 vertexRadiosity;
// Per vertex, from src/mesh/vertex_radiosity_pass.cpp: rgb radiosity (filled everywhere).
layout(std430, binding = 0) readonly buffer VertexRadiosity { vec4 radiosityOfVertex[]; };
#endif
#if VERTEX_EFFECTIVE
// A textured vertex estimate's entries' part of the rule per vertex (shaders/mesh/vertex_estimate.comp).
out vec3 vertexEffective;
layout(std430, binding = 1) readonly buffer VertexEffective { vec4 effectiveOfVertex[]; };
#endif

#if CORNERS_APART
// The mesh as storage (GpuMesh::drawCornersOpaque): its vertices and 3 indices per triangle; per
// triangle its near-field entry (near_field_points.glsl).
#define MESH_VERTICES_BINDING 2
#include "mesh/mesh_vertices.glsl"
layout(std430, binding = 3) readonly buffer Indices { uint indexData[]; };
layout(std430, binding = 4) readonly buffer NearFieldTriangles { uint nearFieldTriangle[]; };
flat out uint nearFieldEntry;
out vec2 nearFieldWeights;  // of corners b and c

uint cornerVertex() {
    int corner = gl_VertexID % 3;
    nearFieldEntry = nearFieldTriangle[gl_VertexID / 3];
    nearFieldWeights = vec2(corner == 1, corner == 2);
    return indexData[gl_VertexID];
}
#else
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inTexcoord;
#endif

void main() {
#if CORNERS_APART
    uint v = cornerVertex();
    modelPosition = meshPosition(v);
    modelNormal = meshNormal(v);
    texcoord = meshTexcoord(v);
#else
    uint v = uint(gl_VertexID);
    modelPosition = inPosition;
    modelNormal = inNormal;
    texcoord = inTexcoord;
#endif
#if !RADIOSITY_IN_POINTS
    vertexRadiosity = radiosityOfVertex[v].rgb;
#endif
#if VERTEX_EFFECTIVE
    vertexEffective = effectiveOfVertex[v].rgb;
#endif
    vec4 world = model * vec4(modelPosition, 1.0);
    worldPosition = world.xyz;
    worldNormal = normalMatrix * modelNormal;
    gl_Position = viewProjection * world;
}
