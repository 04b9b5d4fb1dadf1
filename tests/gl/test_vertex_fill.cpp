// The vertex-radiosity fill on the GPU against the breadth-first fill it replaced on the CPU:
// the same values, and the same vertices left unknown.
#include "support/gl_test.h"

#include "gl/gl.h"
#include "mesh/vertex_radiosity_pass.h"

#include <catch2/catch.hpp>
#include <sss/procedural.h>

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

using namespace sss;

namespace {

/// The CPU fill: each round, every unknown vertex with a known neighbour takes the mean of its
/// known neighbours; values set in a round count from the next one. Returns the rounds that
/// filled something.
int fillOnCpu(std::vector<glm::vec4>& values, const detail::VertexAdjacency& adjacency) {
    std::vector<char> known(values.size());
    for (std::size_t v = 0; v < values.size(); ++v) known[v] = values[v].w > 0.0f;
    int rounds = 0;
    for (;;) {
        std::vector<std::pair<std::size_t, glm::vec4>> filled;
        for (std::size_t v = 0; v < values.size(); ++v) {
            if (known[v]) continue;
            glm::vec4 sum(0.0f);
            for (std::uint32_t e = adjacency.start[v]; e < adjacency.start[v + 1]; ++e)
                if (const std::uint32_t n = adjacency.neighbours[e]; known[n]) sum += glm::vec4(glm::vec3(values[n]), 1.0f);
            if (sum.w > 0.0f) filled.emplace_back(v, glm::vec4(glm::vec3(sum) / sum.w, 1.0f));
        }
        if (filled.empty()) return rounds;
        ++rounds;
        for (const auto& [v, value] : filled) values[v] = value, known[v] = 1;
    }
}

/// Runs the GPU fill on `values` (a > 0: known) and reads the result back.
std::vector<glm::vec4> fillOnGpu(const std::vector<glm::vec4>& values, const detail::VertexAdjacency& adjacency) {
    detail::VertexRadiosityPass pass(adjacency);
    const GLsizeiptr bytes = static_cast<GLsizeiptr>(values.size() * sizeof(glm::vec4));
    GLuint staging = 0;
    glCreateBuffers(1, &staging);
    glNamedBufferStorage(staging, bytes, values.data(), 0);
    glCopyNamedBufferSubData(staging, pass.radiosity().id(), 0, 0, bytes);
    glDeleteBuffers(1, &staging);
    pass.fill();
    std::vector<glm::vec4> out(values.size());
    glGetNamedBufferSubData(pass.radiosity().id(), 0, bytes, out.data());
    return out;
}

}  // namespace

TEST_CASE("the GPU vertex fill gives the CPU breadth-first fill's values", "[gl][mesh][vertex-fill]") {
    test::GlTestScope gl;
    const Mesh mesh = makeTorus(0.7f, 0.3f, 64, 32);
    const detail::VertexAdjacency adjacency = detail::buildVertexAdjacency(mesh);
    const std::vector<glm::vec3>& positions = mesh.positions();
    // Known: a band around the torus and a few scattered vertices, with colours that vary.
    std::vector<glm::vec4> values(positions.size(), glm::vec4(0.0f));
    int knownCount = 0;
    for (std::size_t v = 0; v < positions.size(); ++v) {
        const glm::vec3 p = positions[v];
        if (p.x > 0.55f || v % 97 == 0) {
            values[v] = glm::vec4(0.5f + 0.5f * std::sin(7.0f * p.y), std::abs(p.z), 0.2f + p.x * p.x, 1.0f);
            ++knownCount;
        }
    }
    REQUIRE(knownCount > 100);
    std::vector<glm::vec4> expected = values;
    const int rounds = fillOnCpu(expected, adjacency);
    INFO("rounds the CPU fill took: " << rounds);
    REQUIRE(rounds > 3);  // the fill reaches several rings, so the round order matters
    REQUIRE(rounds <= detail::VertexRadiosityPass::kFillRounds);

    const std::vector<glm::vec4> filled = fillOnGpu(values, adjacency);
    float largest = 0.0f;
    int unknownMismatch = 0;
    for (std::size_t v = 0; v < values.size(); ++v) {
        unknownMismatch += (filled[v].w > 0.0f) != (expected[v].w > 0.0f) ? 1 : 0;
        largest = std::max(largest, glm::length(glm::vec3(filled[v]) - glm::vec3(expected[v])));
    }
    INFO("largest difference " << largest);
    CHECK(unknownMismatch == 0);
    CHECK(largest <= 1e-5f);
    gl.requireNoErrors();
}

TEST_CASE("the GPU vertex fill leaves islands no map sees unknown", "[gl][mesh][vertex-fill]") {
    test::GlTestScope gl;
    // Two separate spheres in one mesh: only the first has known vertices.
    Mesh first = makeUvSphere(12, 8), second = makeUvSphere(12, 8);
    std::vector<glm::vec3> positions = first.positions();
    std::vector<std::uint32_t> indices = first.indices();
    const auto offset = static_cast<std::uint32_t>(positions.size());
    for (const glm::vec3& p : second.positions()) positions.push_back(p + glm::vec3(3.0f, 0.0f, 0.0f));
    for (std::uint32_t i : second.indices()) indices.push_back(i + offset);
    const Mesh both = Mesh::fromArrays(positions, indices);
    const detail::VertexAdjacency adjacency = detail::buildVertexAdjacency(both);
    std::vector<glm::vec4> values(positions.size(), glm::vec4(0.0f));
    values[0] = glm::vec4(1.0f, 0.5f, 0.25f, 1.0f);
    const std::vector<glm::vec4> filled = fillOnGpu(values, adjacency);
    for (std::size_t v = 0; v < offset; ++v) CHECK(filled[v].w > 0.0f);
    for (std::size_t v = offset; v < positions.size(); ++v) CHECK(filled[v].w == 0.0f);
    CHECK(glm::length(glm::vec3(filled[offset - 1]) - glm::vec3(1.0f, 0.5f, 0.25f)) < 1e-5f);
    gl.requireNoErrors();
}
