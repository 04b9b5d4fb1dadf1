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
    : m_program(gl::Program::link({{GL_COMPUTE_SHADER, "mesh/vertex_radiosity.comp"}},
                                  {{"MAX_CAMERAS", std::to_string(kMaxScatteringCameras)}})),
      m_adjacency(adjacency),
      m_vertexCount(adjacency.vertexCount()) {
    const std::size_t bytes = std::max<std::size_t>(1, m_vertexCount) * sizeof(glm::vec4);
    m_resolved = gl::Buffer::create(bytes, nullptr, 0, "vertex radiosity (resolved)");
    m_radiosity = gl::Buffer::create(bytes, nullptr, GL_DYNAMIC_STORAGE_BIT, "vertex radiosity");
}

void VertexRadiosityPass::run(const GpuMesh& mesh, const ScatteringCameras& cameras, const ScatteringMapPass& maps,
                              const MapLookupSettings& settings) {
    if (m_vertexCount == 0) return;
    setMapLookupUniforms(m_program, cameras, maps, settings);
    m_program.set("vertexCount", static_cast<int>(m_vertexCount));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, mesh.vertices.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, m_resolved.id());
    m_program.use();
    glDispatchCompute(static_cast<GLuint>((m_vertexCount + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glUseProgram(0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, 0);

    std::vector<glm::vec4> values(m_vertexCount);
    glGetNamedBufferSubData(m_resolved.id(), 0, static_cast<GLsizeiptr>(values.size() * sizeof(glm::vec4)), values.data());
    // Breadth-first fill: each round, every unknown vertex with a known neighbour takes the mean
    // of its known neighbours; values set in a round count from the next one, so the fill does
    // not depend on vertex order.
    std::vector<char> known(m_vertexCount);
    std::vector<std::uint32_t> pending;
    for (std::size_t v = 0; v < m_vertexCount; ++v) {
        known[v] = values[v].w > 0.0f;
        if (!known[v]) pending.push_back(static_cast<std::uint32_t>(v));
    }
    m_unseen = pending.size();
    std::vector<std::pair<std::uint32_t, glm::vec4>> filled;
    while (!pending.empty()) {
        filled.clear();
        std::vector<std::uint32_t> still;
        for (std::uint32_t v : pending) {
            glm::vec4 sum(0.0f);
            for (std::uint32_t e = m_adjacency.start[v]; e < m_adjacency.start[v + 1]; ++e) {
                const std::uint32_t n = m_adjacency.neighbours[e];
                if (known[n]) sum += glm::vec4(glm::vec3(values[n]), 1.0f);
            }
            if (sum.w > 0.0f) filled.emplace_back(v, glm::vec4(glm::vec3(sum) / sum.w, 1.0f));
            else still.push_back(v);
        }
        if (filled.empty()) break;  // islands no map sees at all: left black
        for (const auto& [v, value] : filled) {
            values[v] = value;
            known[v] = 1;
        }
        pending.swap(still);
    }
    for (std::size_t v = 0; v < m_vertexCount; ++v) values[v].w = known[v] ? 1.0f : 0.0f;
    m_radiosity.upload(0, values.size() * sizeof(glm::vec4), values.data());
}

}  // namespace sss::detail
