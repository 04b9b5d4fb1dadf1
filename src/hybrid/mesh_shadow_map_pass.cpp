#include "hybrid/mesh_shadow_map_pass.h"

#include "mesh/light_buffer_pass.h"

#include <algorithm>

namespace sss::detail {

MeshShadowMapPass::MeshShadowMapPass()
    : m_program(gl::Program::link({{GL_VERTEX_SHADER, "hybrid/mesh_shadow_map.vert"},
                                   {GL_FRAGMENT_SHADER, "hybrid/mesh_shadow_map.frag"}})),
      m_framebuffer(gl::Framebuffer::create()) {}

void MeshShadowMapPass::run(const MeshShadowMapInputs& in, MeshShadowMaps& maps) {
    const int size = in.resolution;
    const int layers = std::max<int>(1, static_cast<int>(in.lights.size()));
    if (!maps.depth || maps.depth.size() != glm::ivec3(size, size, layers)) {
        maps.depth = gl::Texture::create2DArray(GL_DEPTH_COMPONENT32F, size, size, layers, "hybrid mesh shadow maps");
        maps.depth.setFilter(GL_NEAREST, GL_NEAREST);
        maps.depth.setWrap(GL_CLAMP_TO_EDGE);
        maps.ids = gl::Texture::create2DArray(GL_R16UI, size, size, layers, "hybrid mesh shadow ids");
        maps.ids.setFilter(GL_NEAREST, GL_NEAREST);
        maps.ids.setWrap(GL_CLAMP_TO_EDGE);
    }
    const glm::vec3 centre = in.receivers.center();
    const float radius = std::max(in.receivers.radius(), 1e-6f);
    // lightViewProjection frames the sphere with 1 % to spare on each side.
    maps.texelWorldSize = 2.02f * radius / static_cast<float>(size);
    maps.worldToClip.clear();

    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glViewport(0, 0, size, size);
    m_program.use();
    for (std::size_t i = 0; i < in.lights.size(); ++i) {
        maps.worldToClip.push_back(lightViewProjection(in.lights[i], centre, radius));
        m_framebuffer.attachLayer(GL_DEPTH_ATTACHMENT, maps.depth, static_cast<int>(i));
        m_framebuffer.attachLayer(GL_COLOR_ATTACHMENT0, maps.ids, static_cast<int>(i));
        m_framebuffer.setDrawBuffers({GL_COLOR_ATTACHMENT0});
        m_framebuffer.checkComplete("hybrid mesh shadow map");
        const float one = 1.0f;
        const GLuint none[4] = {0, 0, 0, 0};
        glClearNamedFramebufferfv(m_framebuffer.id(), GL_DEPTH, 0, &one);
        glClearNamedFramebufferuiv(m_framebuffer.id(), GL_COLOR, 0, none);
        m_framebuffer.bind();
        for (std::size_t c = 0; c < in.casters.size(); ++c) {
            m_program.set("modelToClip", maps.worldToClip.back() * in.casters[c].model);
            m_program.set("meshId", static_cast<unsigned>(c + 1));
            in.casters[c].mesh->draw();
        }
    }
    glBindVertexArray(0);
    glUseProgram(0);
}

}  // namespace sss::detail
