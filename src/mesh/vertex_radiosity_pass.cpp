#include "mesh/vertex_radiosity_pass.h"

#include <glm/vec4.hpp>

#include <algorithm>
#include <string>

namespace sss::detail {

void setMapLookupUnits(const gl::Program& p) {
    p.set("scatteringMaps", 0);
    p.set("scatteringDepth", 1);
    p.set("cameraCount", 0);
}

void setMapLookupUniforms(const gl::Program& p, const ScatteringCameras& cameras, const ScatteringMapPass& maps,
                          const MapLookupSettings& s) {
    setMapLookupUnits(p);
    p.set("cameraCount", maps.cameras());
    for (int k = 0; k < maps.cameras(); ++k) {
        const std::string index = "[" + std::to_string(k) + "]";
        p.set("cameraViewProjection" + index, cameras.viewProjection[static_cast<size_t>(k)]);
        p.set("cameraAxis" + index, cameras.axis[static_cast<size_t>(k)]);
    }
    p.set("depthBias", s.depthBias);
    p.set("seamShrink", s.seamShrink);
    maps.maps().bind(0);
    maps.depth().bind(1);
}

VertexAdjacency buildVertexAdjacency(const Mesh& mesh) {
    // Each triangle links its three vertices; a neighbour shared by two triangles counts once.
    const std::size_t count = mesh.vertexCount();
    std::vector<std::vector<std::uint32_t>> lists(count);
    const std::vector<std::uint32_t>& indices = mesh.indices();
    for (std::size_t t = 0; t + 2 < indices.size(); t += 3)
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b)
                if (a != b) lists[indices[t + a]].push_back(indices[t + b]);
    VertexAdjacency adjacency;
    adjacency.start.assign(count + 1, 0);
    for (std::size_t v = 0; v < count; ++v) {
        std::sort(lists[v].begin(), lists[v].end());
        lists[v].erase(std::unique(lists[v].begin(), lists[v].end()), lists[v].end());
        adjacency.start[v + 1] = adjacency.start[v] + static_cast<std::uint32_t>(lists[v].size());
    }
    adjacency.neighbours.reserve(adjacency.start.back());
    for (const auto& list : lists) adjacency.neighbours.insert(adjacency.neighbours.end(), list.begin(), list.end());
    return adjacency;
}

VertexRadiosityPass::VertexRadiosityPass(const VertexAdjacency& adjacency)
    : m_resolve(gl::Program::link({{GL_COMPUTE_SHADER, "mesh/vertex_radiosity.comp"}},
                                  {{"MAX_CAMERAS", std::to_string(kMaxScatteringCameras)}})),
      m_fill(gl::Program::link({{GL_COMPUTE_SHADER, "mesh/vertex_fill.comp"}})),
      m_vertexCount(adjacency.vertexCount()) {
    const std::size_t bytes = std::max<std::size_t>(1, m_vertexCount) * sizeof(glm::vec4);
    m_radiosity = gl::Buffer::create(bytes, nullptr, 0, "vertex radiosity");
    const auto upload = [](const std::vector<std::uint32_t>& values, const char* label) {
        const std::uint32_t none = 0;
        return values.empty() ? gl::Buffer::create(sizeof none, &none, 0, label)
                              : gl::Buffer::create(values.size() * sizeof(std::uint32_t), values.data(), 0, label);
    };
    m_neighbourStart = upload(adjacency.start, "vertex adjacency (starts)");
    m_neighbours = upload(adjacency.neighbours, "vertex adjacency (neighbours)");
    m_filled = gl::Buffer::create(kFillRounds * sizeof(std::uint32_t), nullptr, 0, "vertex fill (filled per round)");
}

void VertexRadiosityPass::run(const GpuMesh& mesh, const ScatteringCameras& cameras, const ScatteringMapPass& maps,
                              const MapLookupSettings& settings) {
    if (m_vertexCount == 0) return;
    const auto groups = static_cast<GLuint>((m_vertexCount + 63) / 64);
    setMapLookupUniforms(m_resolve, cameras, maps, settings);
    m_resolve.set("vertexCount", static_cast<int>(m_vertexCount));
    mesh.vertices.bindStorage(0);
    m_radiosity.bindStorage(1);
    m_resolve.use();
    glDispatchCompute(groups, 1, 1);
    glUseProgram(0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, 0);
    fill();
}

void VertexRadiosityPass::fill() {
    if (m_vertexCount == 0) return;
    const auto groups = static_cast<GLuint>((m_vertexCount + 63) / 64);
    const std::uint32_t zero = 0;
    glClearNamedBufferData(m_filled.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    m_radiosity.bindStorage(0);
    m_neighbourStart.bindStorage(1);
    m_neighbours.bindStorage(2);
    m_filled.bindStorage(3);
    m_fill.set("vertexCount", static_cast<int>(m_vertexCount));
    m_fill.use();
    for (int round = 1; round <= kFillRounds; ++round) {
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);  // the previous round's values and counts
        m_fill.set("fillRound", round);
        glDispatchCompute(groups, 1, 1);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);  // the combine pass reads the values
    glUseProgram(0);
    for (GLuint binding = 0; binding < 4; ++binding) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, 0);
}

}  // namespace sss::detail
