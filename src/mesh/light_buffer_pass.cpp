#include "mesh/light_buffer_pass.h"

#include "core/light_geometry.h"
#include "lighting/light_uniforms.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace sss::detail {
namespace {

// An up vector not parallel to `forward`.
glm::vec3 upFor(glm::vec3 forward) {
    return std::abs(forward.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
}

}  // namespace

std::pair<glm::vec3, float> worldSphere(const Bounds& bounds, const glm::mat4& model) {
    Bounds world;
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner((i & 1) ? bounds.max.x : bounds.min.x, (i & 2) ? bounds.max.y : bounds.min.y,
                               (i & 4) ? bounds.max.z : bounds.min.z);
        world.extend(glm::vec3(model * glm::vec4(corner, 1.0f)));
    }
    return {world.center(), std::max(world.radius(), 1e-6f)};
}

glm::mat4 lightViewProjection(const Light& light, glm::vec3 centre, float radius) {
    if (const auto* d = std::get_if<DirectionalLight>(&light)) {
        const glm::vec3 forward = glm::normalize(d->direction);
        const glm::vec3 eye = centre - forward * (2.0f * radius);
        const glm::mat4 view = glm::lookAt(eye, centre, upFor(forward));
        // Slightly larger than the sphere so silhouette texels are not clipped.
        const float r = radius * 1.01f;
        return glm::ortho(-r, r, -r, r, radius * 0.5f, radius * 3.5f) * view;
    }
    // Point and spot lights alike: the spot's cone only scales what reaches the surface.
    const glm::vec3 position = *lightPosition(light);
    const glm::vec3 toCentre = centre - position;
    const float distance = glm::length(toCentre);
    const glm::vec3 forward = distance > 0.0f ? toCentre / distance : glm::vec3(0, 0, -1);
    // The cone that holds the sphere; a light inside the sphere sees at most 150 degrees of it.
    const float halfAngle = distance > radius * 1.001f ? std::asin(radius / distance) * 1.01f : glm::radians(75.0f);
    const float nearPlane = std::max(distance - radius, radius * 1e-3f);
    const glm::mat4 view = glm::lookAt(position, position + forward, upFor(forward));
    return glm::perspective(2.0f * std::min(halfAngle, glm::radians(75.0f)), 1.0f, nearPlane, distance + radius) * view;
}

namespace {

gl::Program linkLightBufferProgram(bool textured) {
    return gl::Program::link({{GL_VERTEX_SHADER, "mesh/light_buffer.vert"}, {GL_FRAGMENT_SHADER, "mesh/light_buffer.frag"}},
                             texturedMaterialDefines(textured));
}

}  // namespace

LightBufferPass::LightBufferPass() : m_program(linkLightBufferProgram(false)) {}

void LightBufferPass::run(const GpuMesh& mesh, const glm::mat4& model, const std::vector<Light>& lights,
                          int resolution, const TexturedMaterialGpu* material) {
    const int layers = std::max<int>(1, static_cast<int>(lights.size()));
    const bool textured = material != nullptr;
    if (!m_positions || m_positions.size() != glm::ivec3(resolution, resolution, layers) ||
        static_cast<bool>(m_logGathered) != textured) {
        m_positions = gl::Texture::create2DArray(GL_RGBA32F, resolution, resolution, layers, "light buffer positions");
        // Bilinear, so samples land on the surface between texel centres rather than snapping to
        // them; where the four texels are not all covered (w < 1) the sampler skips the sample.
        m_normals = gl::Texture::create2DArray(GL_RGBA16F, resolution, resolution, layers, "light buffer normals");
        m_depth = gl::Texture::create2DArray(GL_DEPTH_COMPONENT32F, resolution, resolution, layers, "light buffer depth");
        m_logGathered = textured ? gl::Texture::create2DArray(GL_RGBA16F, resolution, resolution, layers,
                                                               "light buffer ln gathered")
                                  : gl::Texture();
        m_layers.clear();
        for (int layer = 0; layer < layers; ++layer) {
            gl::Framebuffer& framebuffer = m_layers.emplace_back(gl::Framebuffer::create());
            framebuffer.attachLayer(GL_COLOR_ATTACHMENT0, m_positions, layer);
            framebuffer.attachLayer(GL_COLOR_ATTACHMENT1, m_normals, layer);
            framebuffer.attachLayer(GL_DEPTH_ATTACHMENT, m_depth, layer);
            if (textured) {
                framebuffer.attachLayer(GL_COLOR_ATTACHMENT2, m_logGathered, layer);
                framebuffer.setDrawBuffers({GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2});
            } else {
                framebuffer.setDrawBuffers({GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1});
            }
            framebuffer.checkComplete("light buffer");
        }
    }
    const auto [centre, radius] = worldSphere(mesh.bounds, model);
    if (textured && !m_texturedProgram) m_texturedProgram = linkLightBufferProgram(true);
    const gl::Program& program = textured ? *m_texturedProgram : m_program;
    if (textured) material->bind(program, 1.0);  // ln gathered needs the reflectance and the table only
    program.set("model", model);
    program.set("normalMatrix", glm::mat3(glm::transpose(glm::inverse(model))));
    const float zero[4] = {0, 0, 0, 0};
    const float one = 1.0f;
    m_viewProjections.clear();
    glViewport(0, 0, resolution, resolution);
    for (size_t i = 0; i < m_layers.size(); ++i) {
        const gl::Framebuffer& framebuffer = m_layers[i];
        glClearNamedFramebufferfv(framebuffer.id(), GL_COLOR, 0, zero);
        glClearNamedFramebufferfv(framebuffer.id(), GL_COLOR, 1, zero);
        glClearNamedFramebufferfv(framebuffer.id(), GL_DEPTH, 0, &one);
        if (i >= lights.size()) continue;  // no light: the layer stays empty
        m_viewProjections.push_back(lightViewProjection(lights[i], centre, radius));
        program.set("lightViewProjection", m_viewProjections.back());
        framebuffer.bind();
        mesh.drawOpaque(program);
    }
}

float LightBufferPass::texelWorld(const GpuMesh& mesh, const glm::mat4& model) const {
    // 2 radii over the resolution.
    const auto [centre, radius] = worldSphere(mesh.bounds, model);
    return 2.0f * radius / static_cast<float>(m_positions.size().x);
}

}  // namespace sss::detail
