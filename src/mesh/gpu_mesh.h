#pragma once
// A Mesh uploaded to the GPU: interleaved position, normal and texture-coordinate vertex buffer
// (zero texture coordinates when the mesh has none), index buffer, VAO (attribute 0 = position,
// 1 = normal, 2 = texture coordinate). Shared by every mesh pass; the compute passes read the
// vertex buffer as storage, kFloatsPerVertex floats per vertex (shaders/mesh/mesh_vertices.glsl).
#include "gl/buffer.h"
#include "gl/program.h"
#include "gl/vertex_array.h"
#include "sss/bounds.h"
#include "sss/mesh.h"

namespace sss::detail {

struct GpuMesh {
    static constexpr int kFloatsPerVertex = 8;

    gl::Buffer vertices;
    gl::Buffer indices;
    gl::VertexArray vertexArray;
    gl::VertexArray noAttributes;  ///< for drawCornersOpaque, whose shaders read the buffers themselves
    GLsizei indexCount = 0;
    Bounds bounds;
    bool hasTexcoords = false;

    static GpuMesh upload(const Mesh& mesh);
    void draw() const;
    /// Draws with `program` as an opaque surface: depth test (less) and depth writes on, no
    /// blending, no culling (open meshes show their inside; both sides are shaded).
    void drawOpaque(const gl::Program& program) const;
    /// As drawOpaque, but each triangle's corners as their own vertices without attributes:
    /// vertex 3t + k is corner k of triangle t, and the program reads `vertices` and `indices`
    /// as storage buffers 2 and 3 (shaders/mesh/combine.vert).
    void drawCornersOpaque(const gl::Program& program) const;
};

}  // namespace sss::detail
