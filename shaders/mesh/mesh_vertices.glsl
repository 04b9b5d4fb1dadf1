// The mesh's vertex buffer read as storage (src/mesh/gpu_mesh.h, GpuMesh::kFloatsPerVertex):
// per vertex, in model space, its position, normal and texture coordinate, 8 floats. A shader
// sets MESH_VERTICES_BINDING to the storage binding its pass gives the buffer (default 0).
#ifndef MESH_VERTICES_BINDING
#define MESH_VERTICES_BINDING 0
#endif
layout(std430, binding = MESH_VERTICES_BINDING) readonly buffer MeshVertices { float meshVertexData[]; };

vec3 meshPosition(uint v) { return vec3(meshVertexData[8u * v], meshVertexData[8u * v + 1u], meshVertexData[8u * v + 2u]); }
vec3 meshNormal(uint v) { return vec3(meshVertexData[8u * v + 3u], meshVertexData[8u * v + 4u], meshVertexData[8u * v + 5u]); }
vec2 meshTexcoord(uint v) { return vec2(meshVertexData[8u * v + 6u], meshVertexData[8u * v + 7u]); }
