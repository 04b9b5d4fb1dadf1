#include "mesh/scattering_map_pass.h"

#include "lighting/light_uniforms.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>

#include <cmath>
#include <string>

namespace sss::detail {
namespace {

float radicalInverse(int index, int base) {
    float result = 0.0f, fraction = 1.0f / static_cast<float>(base);
    for (int i = index; i > 0; i /= base, fraction /= static_cast<float>(base))
        result += static_cast<float>(i % base) * fraction;
    return result;
}

gl::Program linkMapProgram(const char* fragment, int cameras, bool textured = false) {
    ShaderDefines defines = texturedMaterialDefines(textured);
    defines.insert(defines.end(), {{"CAMERA_COUNT", std::to_string(cameras)}, {"MAX_LIGHTS", std::to_string(kMaxLights)}});
    return gl::Program::link({{GL_VERTEX_SHADER, "mesh/scattering_map.vert"},
                              {GL_GEOMETRY_SHADER, "mesh/scattering_map.geom"},
                              {GL_FRAGMENT_SHADER, fragment}},
                             defines);
}

}  // namespace

glm::vec3 haltonSphereDirection(int k) {
    const float s = radicalInverse(k + 1, 2), t = radicalInverse(k + 1, 3);
    const float z = 2.0f * t - 1.0f;
    const float ring = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const float phi = 2.0f * 3.14159265f * s;
    return {ring * std::cos(phi), ring * std::sin(phi), z};
}

ScatteringCameras makeScatteringCameras(int count, const Bounds& bounds) {
    ScatteringCameras cameras;
    const glm::vec3 centre = bounds.center();
    const float radius = std::max(bounds.radius(), 1e-6f) * 1.01f;
    for (int k = 0; k < count; ++k) {
        const glm::vec3 axis = haltonSphereDirection(k);
        const glm::vec3 up = std::abs(axis.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
        const glm::mat4 view = glm::lookAt(centre + axis * (2.0f * radius), centre, up);
        cameras.viewProjection.push_back(glm::ortho(-radius, radius, -radius, radius, radius * 0.5f, radius * 3.5f) * view);
        cameras.axis.push_back(axis);
    }
    return cameras;
}

ScatteringMapPass::ScatteringMapPass(int cameras)
    : m_cameras(cameras),
      m_depthProgram(linkMapProgram("mesh/depth_only.frag", cameras)),
      m_program(linkMapProgram("mesh/scattering_map.frag", cameras)) {}

void ScatteringMapPass::reset(int resolution) {
    if (!m_maps || m_maps.size() != glm::ivec3(resolution, resolution, m_cameras)) {
        m_maps = gl::Texture::create2DArray(GL_RGBA32F, resolution, resolution, m_cameras, "scattering maps");
        m_depth = gl::Texture::create2DArray(GL_DEPTH_COMPONENT32F, resolution, resolution, m_cameras, "scattering map depth");
        m_depth.setFilter(GL_NEAREST, GL_NEAREST);
        m_framebuffer = gl::Framebuffer::create();
        m_framebuffer.attach(GL_COLOR_ATTACHMENT0, m_maps);
        m_framebuffer.attach(GL_DEPTH_ATTACHMENT, m_depth);
        m_framebuffer.checkComplete("scattering maps");
    }
    m_frames = 0;
}

void ScatteringMapPass::accumulate(const ScatteringMapPassInputs& in) {
    const glm::mat4& model = in.model;
    const glm::mat3 normalMatrix = glm::mat3(glm::transpose(glm::inverse(model)));
    if (in.estimate.material && !m_texturedProgram)
        m_texturedProgram = linkMapProgram("mesh/scattering_map.frag", m_cameras, true);
    const gl::Program& program = in.estimate.material ? *m_texturedProgram : m_program;
    for (const gl::Program* p : {static_cast<const gl::Program*>(&m_depthProgram), &program}) {
        p->set("model", model);
        p->set("normalMatrix", normalMatrix);
        for (int k = 0; k < m_cameras; ++k)
            p->set("cameraViewProjection[" + std::to_string(k) + "]", in.cameras.viewProjection[static_cast<size_t>(k)]);
    }
    const int resolution = m_maps.size().x;
    m_framebuffer.bind();
    glViewport(0, 0, resolution, resolution);
    glDisable(GL_CULL_FACE);
    glEnable(GL_DEPTH_TEST);
    if (m_frames == 0) {
        // The nearest surface per texel never changes while the maps accumulate: find it once,
        // then let every frame shade exactly those fragments (depth test EQUAL, additive blend).
        const float zero[4] = {0, 0, 0, 0};
        const float one = 1.0f;
        glClearNamedFramebufferfv(m_framebuffer.id(), GL_COLOR, 0, zero);
        glClearNamedFramebufferfv(m_framebuffer.id(), GL_DEPTH, 0, &one);
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glDepthMask(GL_TRUE);
        glDepthFunc(GL_LESS);
        m_depthProgram.use();
        in.mesh.draw();
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    }

    setRadiosityEstimateUniforms(program, in.estimate, static_cast<unsigned>(m_frames));
    glDepthMask(GL_FALSE);
    glDepthFunc(GL_EQUAL);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    program.use();
    in.mesh.draw();
    glDisable(GL_BLEND);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glBindVertexArray(0);
    glUseProgram(0);
    ++m_frames;
}

}  // namespace sss::detail
