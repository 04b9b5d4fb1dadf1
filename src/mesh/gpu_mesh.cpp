#include "mesh/gpu_mesh.h"

#include <vector>

namespace sss::detail {

GpuMesh GpuMesh::upload(const Mesh& mesh) {
    std::vector<float> interleaved;
    interleaved.reserve(mesh.vertexCount() * kFloatsPerVertex);
    const bool textured = !mesh.texcoords().empty();
    for (size_t i = 0; i < mesh.vertexCount(); ++i) {
        const glm::vec3& p = mesh.positions()[i];
        const glm::vec3& n = mesh.normals()[i];
        const glm::vec2 t = textured ? mesh.texcoords()[i] : glm::vec2(0.0f);
        interleaved.insert(interleaved.end(), {p.x, p.y, p.z, n.x, n.y, n.z, t.x, t.y});
    }
    GpuMesh gpu;
    gpu.vertices = gl::Buffer::create(interleaved.size() * sizeof(float), interleaved.data(), 0, "mesh vertices");
    gpu.indices = gl::Buffer::create(mesh.indices().size() * sizeof(uint32_t), mesh.indices().data(), 0, "mesh indices");
    gpu.vertexArray = gl::VertexArray::create();
    const GLsizei stride = kFloatsPerVertex * sizeof(float);
    gpu.vertexArray.setAttribute(0, gpu.vertices, 3, 0, stride);
    gpu.vertexArray.setAttribute(1, gpu.vertices, 3, 3 * sizeof(float), stride);
    gpu.vertexArray.setAttribute(2, gpu.vertices, 2, 6 * sizeof(float), stride);
    gpu.vertexArray.setIndexBuffer(gpu.indices);
    gpu.noAttributes = gl::VertexArray::create();
    gpu.indexCount = static_cast<GLsizei>(mesh.indices().size());
    gpu.bounds = mesh.bounds();
    gpu.hasTexcoords = textured;
    return gpu;
}

void GpuMesh::draw() const {
    vertexArray.bind();
    glDrawElements(GL_TRIANGLES, indexCount, GL_UNSIGNED_INT, nullptr);
}

namespace {

void setOpaqueState(const gl::Program& program) {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    program.use();
}

}  // namespace

void GpuMesh::drawOpaque(const gl::Program& program) const {
    setOpaqueState(program);
    draw();
    glBindVertexArray(0);
    glUseProgram(0);
}

void GpuMesh::drawCornersOpaque(const gl::Program& program) const {
    setOpaqueState(program);
    vertices.bindStorage(2);
    indices.bindStorage(3);
    noAttributes.bind();
    glDrawArrays(GL_TRIANGLES, 0, indexCount);
    glBindVertexArray(0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, 0);
    glUseProgram(0);
}

}  // namespace sss::detail
