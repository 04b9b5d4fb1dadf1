#include "mesh/near_field_cache.h"

#include "lighting/light_uniforms.h"
#include "lighting/texture_units.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace sss::detail {

namespace {

std::vector<float> longestEdges(const Mesh& mesh) {
    std::vector<float> longest(mesh.triangleCount());
    const auto& p = mesh.positions();
    const auto& index = mesh.indices();
    for (std::size_t t = 0; t < longest.size(); ++t) {
        const glm::vec3 a = p[index[3 * t]], b = p[index[3 * t + 1]], c = p[index[3 * t + 2]];
        longest[t] = std::max({glm::distance(a, b), glm::distance(b, c), glm::distance(c, a)});
    }
    return longest;
}

gl::Buffer storage(std::size_t bytes, const void* data, std::string_view label) {
    return gl::Buffer::create(std::max<std::size_t>(bytes, 16), data, 0, label);
}

}  // namespace

int nearFieldDivisions(float longestEdge, float spacing) {
    if (!(spacing > 0.0f) || !(longestEdge > spacing)) return 1;
    return static_cast<int>(std::min(std::ceil(longestEdge / spacing), static_cast<float>(kMaxNearFieldDivisions)));
}

NearFieldPointLayout layoutNearFieldPoints(const std::vector<float>& longestEdges, float spacing) {
    NearFieldPointLayout layout;
    layout.triangles.reserve(longestEdges.size());
    for (std::size_t t = 0; t < longestEdges.size(); ++t) {
        const int r = nearFieldDivisions(longestEdges[t], spacing);
        const auto first = static_cast<uint32_t>(layout.pointTriangles.size());
        layout.triangles.push_back(first << 3 | static_cast<uint32_t>(r - 1));
        layout.pointTriangles.insert(layout.pointTriangles.end(), (r + 1) * (r + 2) / 2, static_cast<uint32_t>(t));
    }
    return layout;
}

NearFieldCache::NearFieldCache(const Mesh& mesh) : m_longestEdges(longestEdges(mesh)) {}

void NearFieldCache::evaluate(const NearFieldCacheInputs& in) {
    if (!m_program) {
        m_program = gl::Program::link({{GL_COMPUTE_SHADER, "mesh/near_field_cache.comp"}},
                                      {{"MAX_LIGHTS", std::to_string(kMaxLights)},
                                       {"NEAR_FIELD_NODES", std::to_string(kNearFieldNodes)},
                                       {"NEAR_FIELD_TAPS", std::to_string(kNearFieldTaps)}});
    }
    const int texelsPerPoint = 1 + (static_cast<int>(in.lights.size()) + 2) / 4;  // light 0 in texel 0, 4 per texel after
    if (in.spacing != m_spacing || m_pointCount == 0 || texelsPerPoint != m_texelsPerPoint) {
        const NearFieldPointLayout layout = layoutNearFieldPoints(m_longestEdges, in.spacing);
        m_triangles = storage(layout.triangles.size() * 4, layout.triangles.data(), "near field (triangles)");
        m_pointTriangles =
            storage(layout.pointTriangles.size() * 4, layout.pointTriangles.data(), "near field (point triangles)");
        m_pointCount = layout.pointTriangles.size();
        m_values = storage(m_pointCount * texelsPerPoint * 8, nullptr, "near field (points)");
        m_valuesView = gl::Texture::createBufferView(m_values, GL_RGBA16F, "near field (points)");
        m_spacing = in.spacing;
        m_texelsPerPoint = texelsPerPoint;
    }
    const gl::Program& p = *m_program;
    setLightUniforms(p, in.lights);
    setSurfaceShadowUniforms(p, in.shadows, in.lights.size());
    setNearFieldUniforms(p, in.nearField);
    p.set("lightTexelWorld", in.lightBuffer.texelWorld(in.mesh, in.model));
    p.set("lightPositions", 0);
    p.set("lightNormals", 1);
    for (std::size_t i = 0; i < in.lightBuffer.viewProjections().size(); ++i)
        p.set("lightViewProjection[" + std::to_string(i) + "]", in.lightBuffer.viewProjections()[i]);
    in.lightBuffer.positions().bind(0);
    in.lightBuffer.normals().bind(1);
    p.set("pointCount", static_cast<int>(m_pointCount));
    p.set("model", in.model);
    p.set("normalMatrix", glm::mat3(glm::transpose(glm::inverse(in.model))));
    p.set("eta", in.eta);
    p.set("texelsPerPoint", m_texelsPerPoint);
    // The rise across the terminator where the vertices' correction does not carry it.
    p.set("nearFieldCurvature", glm::vec3(1.0f) - in.nearField.correction);
    // The rings depend on the material and the scale, not the lights: uploaded when they change.
    if (std::vector<glm::vec4> rings = packNearFieldRings(in.nearField); rings != m_ringTables) {
        m_rings = storage(rings.size() * sizeof(glm::vec4), rings.data(), "near field (rings)");
        m_ringTables = std::move(rings);
    }
    in.mesh.vertices.bindStorage(0);
    in.mesh.indices.bindStorage(1);
    m_pointTriangles.bindStorage(2);
    m_triangles.bindStorage(3);
    m_values.bindStorage(4);
    m_rings.bindStorage(5);
    p.use();
    glDispatchCompute(static_cast<GLuint>((m_pointCount + 63) / 64), 1, 1);
    // The combine reads the points as a buffer texture, addRadiosity as storage.
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(0);
    for (GLuint b = 0; b < 6; ++b) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, 0);
}

void NearFieldCache::addRadiosity(const GpuMesh& mesh, const gl::Buffer& vertexRadiosity) {
    if (!m_radiosityProgram)
        m_radiosityProgram = gl::Program::link({{GL_COMPUTE_SHADER, "mesh/near_field_radiosity.comp"}});
    if (const std::size_t bytes = m_pointCount * m_texelsPerPoint * 16; m_withRadiosity.size() < bytes) {
        m_withRadiosity = storage(bytes, nullptr, "near field (points with radiosity)");
        m_withRadiosityView = gl::Texture::createBufferView(m_withRadiosity, GL_RGBA32F, "near field (points with radiosity)");
    }
    const gl::Program& p = *m_radiosityProgram;
    p.set("pointCount", static_cast<int>(m_pointCount));
    p.set("texelsPerPoint", m_texelsPerPoint);
    const gl::Buffer* buffers[] = {&mesh.indices, &m_pointTriangles, &m_triangles, &vertexRadiosity,
                                   &m_values,     &m_withRadiosity};
    for (GLuint b = 0; b < 6; ++b) buffers[b]->bindStorage(b);
    p.use();
    glDispatchCompute(static_cast<GLuint>((m_pointCount + 63) / 64), 1, 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    glUseProgram(0);
    for (GLuint b = 0; b < 6; ++b) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, 0);
}

void NearFieldCache::bind(const gl::Program& program, bool withRadiosity) const {
    program.set("nearFieldPoints", units::kNearFieldPoints);
    program.set("nearFieldTexelsPerPoint", m_texelsPerPoint);
    (withRadiosity ? m_withRadiosityView : m_valuesView).bind(units::kNearFieldPoints);
    m_triangles.bindStorage(4);
}

}  // namespace sss::detail
