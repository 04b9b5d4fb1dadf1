// Rendering into a host application's context and framebuffer (sss/host_frame.h, HostContext):
// the host's depth stops libsss's volume rays, libsss's meshes hide what the host draws
// afterwards, and the host's GL state is what it was.
#include "support/gl_test.h"
#include "support/scenes.h"

#include "gl/gl.h"

#include <sss/sss.h>

#include <EGL/egl.h>
#include <catch2/catch.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <array>
#include <string>

using namespace sss;

namespace {

constexpr int kWidth = 96, kHeight = 64;
const glm::u8vec4 kBackground{20, 30, 40, 255};
const glm::vec4 kBackgroundF = glm::vec4(kBackground) / 255.0f;

// The host's own framebuffer: RGBA8 colour and a DEPTH24_STENCIL8 renderbuffer, as windows have.
struct HostFramebufferObjects {
    GLuint framebuffer = 0, color = 0, depth = 0;
    HostFramebufferObjects() {
        glCreateFramebuffers(1, &framebuffer);
        glCreateRenderbuffers(1, &color);
        glCreateRenderbuffers(1, &depth);
        glNamedRenderbufferStorage(color, GL_RGBA8, kWidth, kHeight);
        glNamedRenderbufferStorage(depth, GL_DEPTH24_STENCIL8, kWidth, kHeight);
        glNamedFramebufferRenderbuffer(framebuffer, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color);
        glNamedFramebufferRenderbuffer(framebuffer, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depth);
    }
    ~HostFramebufferObjects() {
        glDeleteFramebuffers(1, &framebuffer);
        glDeleteRenderbuffers(1, &color);
        glDeleteRenderbuffers(1, &depth);
    }
    HostFramebuffer rectangle() const { return {.framebuffer = framebuffer, .width = kWidth, .height = kHeight}; }
    // Colour everywhere, depth 1 everywhere, then `depth` and `color` inside the scissor box.
    void clear(glm::ivec4 box, float boxDepth, glm::vec4 boxColor) const {
        const float one = 1.0f;
        glClearNamedFramebufferfv(framebuffer, GL_COLOR, 0, &kBackgroundF[0]);
        glClearNamedFramebufferfv(framebuffer, GL_DEPTH, 0, &one);
        glEnable(GL_SCISSOR_TEST);
        glScissor(box.x, box.y, box.z, box.w);
        glClearNamedFramebufferfv(framebuffer, GL_COLOR, 0, &boxColor[0]);
        glClearNamedFramebufferfv(framebuffer, GL_DEPTH, 0, &boxDepth);
        glDisable(GL_SCISSOR_TEST);
    }
    glm::u8vec4 pixel(int x, int y) const {
        glm::u8vec4 p;
        glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
        glReadPixels(x, y, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, &p[0]);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
        return p;
    }
};

// A host draw: one flat-coloured fullscreen triangle at window depth `depth`, depth-tested.
struct HostFlatProgram {
    GLuint program = 0, vertexArray = 0;
    HostFlatProgram() {
        const char* vertex = "#version 450 core\nuniform float z;\nvoid main() {\n"
                             "  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2) * 2.0 - 1.0;\n"
                             "  gl_Position = vec4(p, z, 1.0);\n}\n";
        const char* fragment = "#version 450 core\nuniform vec4 color;\nout vec4 outColor;\n"
                               "void main() { outColor = color; }\n";
        program = glCreateProgram();
        for (auto [type, text] : {std::pair{GL_VERTEX_SHADER, vertex}, std::pair{GL_FRAGMENT_SHADER, fragment}}) {
            const GLuint shader = glCreateShader(type);
            glShaderSource(shader, 1, &text, nullptr);
            glCompileShader(shader);
            glAttachShader(program, shader);
            glDeleteShader(shader);
        }
        glLinkProgram(program);
        GLint linked = GL_FALSE;
        glGetProgramiv(program, GL_LINK_STATUS, &linked);
        REQUIRE(linked == GL_TRUE);
        glCreateVertexArrays(1, &vertexArray);
    }
    ~HostFlatProgram() {
        glDeleteProgram(program);
        glDeleteVertexArrays(1, &vertexArray);
    }
    void draw(GLuint framebuffer, float windowDepth, glm::vec4 color) const {
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
        glViewport(0, 0, kWidth, kHeight);
        glEnable(GL_DEPTH_TEST);
        glUseProgram(program);
        glUniform1f(glGetUniformLocation(program, "z"), windowDepth * 2.0f - 1.0f);
        glUniform4fv(glGetUniformLocation(program, "color"), 1, &color[0]);
        glBindVertexArray(vertexArray);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glBindVertexArray(0);
        glUseProgram(0);
        glDisable(GL_DEPTH_TEST);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }
};

Camera hostCamera() {
    Camera camera;
    camera.setDistance(3.0f);
    return camera;
}

// Window depth of the point `fraction` of the way from the camera's target to its eye.
float windowDepthTowardsEye(const Camera& camera, float fraction) {
    const glm::vec3 p = camera.target() + (camera.position() - camera.target()) * fraction;
    const glm::vec4 clip = camera.projection(float(kWidth) / float(kHeight)) * camera.view() * glm::vec4(p, 1.0f);
    return 0.5f * clip.z / clip.w + 0.5f;
}

}  // namespace

TEST_CASE("host depth stops volume rays: a host box in front of the volume keeps its pixels", "[gl][host]") {
    test::GlTestScope gl;
    HybridCompositor scene({.clearTarget = false});
    scene.addVolume(makeBlobsVolume(32), glm::mat4(1.0f), {.shading = VolumeShading::EmissionAbsorption})
        .setTransferFunction(test::blobsTransferFunction());
    const Camera camera = hostCamera();
    HostFramebufferObjects host;
    const glm::ivec4 box(0, 0, kWidth / 2, kHeight);  // the left half, half-way to the eye
    const glm::u8vec4 boxColor(200, 60, 30, 255);

    // Pixels that differ from the host's own, in the box and beside it.
    auto changes = [&](bool depth) {
        host.clear(box, windowDepthTowardsEye(camera, 0.5f), glm::vec4(boxColor) / 255.0f);
        HostTarget target;
        {
            HostFramebuffer rectangle = host.rectangle();
            rectangle.depth = depth;
            HostTarget::Frame frame = target.begin(rectangle);
            scene.render(camera, frame.target());
            frame.present();
        }
        glm::ivec2 changed(0);
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                const glm::u8vec4 p = host.pixel(x, y);
                if (x < box.z)
                    changed.x += p != boxColor;
                else
                    changed.y += p != kBackground;
            }
        return changed;
    };
    const glm::ivec2 honoured = changes(true), overlay = changes(false);
    INFO("changed in the box and beside it: " << honoured.x << ", " << honoured.y << "; as an overlay "
                                              << overlay.x << ", " << overlay.y);
    CHECK(honoured.x == 0);
    CHECK(honoured.y > 40);  // the volume is there: rays that the box does not stop draw it
    CHECK(overlay.x > 40);   // and without the host's depth the box would not hide it
    gl.requireNoErrors();
}

TEST_CASE("libsss meshes hide host geometry drawn after them, and only where they are", "[gl][host]") {
    test::GlTestScope gl;
    HybridCompositor scene({.clearTarget = false});
    scene.addMesh(makeUvSphere(24, 24, 0.5f), glm::mat4(1.0f), {.shading = MeshShading::BlinnPhong});
    const Camera camera = hostCamera();
    HostFramebufferObjects host;
    host.clear({0, 0, 0, 0}, 1.0f, kBackgroundF);
    HostTarget target;
    {
        HostTarget::Frame frame = target.begin(host.rectangle());
        scene.render(camera, frame.target());
        frame.present();
    }
    const glm::u8vec4 sphere = host.pixel(kWidth / 2, kHeight / 2);
    CHECK(sphere != kBackground);
    // The host's plane through the sphere's centre: the sphere's front half is nearer.
    const glm::u8vec4 late(10, 220, 40, 255);
    HostFlatProgram flat;
    flat.draw(host.framebuffer, windowDepthTowardsEye(camera, 0.0f), glm::vec4(late) / 255.0f);
    CHECK(host.pixel(kWidth / 2, kHeight / 2) == sphere);
    CHECK(host.pixel(2, 2) == late);
    CHECK(host.pixel(kWidth - 3, kHeight - 3) == late);
    gl.requireNoErrors();
}

TEST_CASE("a host frame leaves the host's GL state as it found it (GlStateGuard)", "[gl][host][state]") {
    test::GlTestScope gl;
    HybridCompositor scene({.clearTarget = false});
    scene.addMesh(makeTorus(), glm::mat4(1.0f), {.shading = MeshShading::BlinnPhong});
    scene.addVolume(makeBlobsVolume(24), glm::translate(glm::mat4(1.0f), {0.5f, 0.0f, 0.0f}),
                    {.shading = VolumeShading::Scattering})
        .setTransferFunction(test::blobsTransferFunction());
    HostFramebufferObjects host;
    host.clear({0, 0, 0, 0}, 1.0f, kBackgroundF);
    HostFlatProgram flat;
    GLuint texture = 0, buffer = 0, sampler = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &texture);
    glTextureStorage2D(texture, 1, GL_RGBA8, 4, 4);
    glCreateBuffers(1, &buffer);
    glNamedBufferStorage(buffer, 256, nullptr, 0);
    glCreateSamplers(1, &sampler);

    // A host's state, as unlike libsss's as it gets.
    glUseProgram(flat.program);
    glBindVertexArray(flat.vertexArray);
    glBindFramebuffer(GL_FRAMEBUFFER, host.framebuffer);
    glViewport(3, 4, 50, 40);
    glEnable(GL_SCISSOR_TEST);
    glScissor(1, 2, 30, 20);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_COLOR, GL_DST_ALPHA, GL_ZERO, GL_ONE);
    glBlendEquation(GL_MAX);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_FRONT);
    glFrontFace(GL_CW);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glDepthMask(GL_FALSE);
    glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
    glActiveTexture(GL_TEXTURE5);
    glBindTextureUnit(3, texture);
    glBindSampler(3, sampler);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, buffer);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);

    HostTarget target;
    {
        HostTarget::Frame frame = target.begin(host.rectangle());
        scene.render(hostCamera(), frame.target());
        frame.present();
    }
    auto integer = [](GLenum name) {
        GLint v = 0;
        glGetIntegerv(name, &v);
        return v;
    };
    CHECK(integer(GL_CURRENT_PROGRAM) == GLint(flat.program));
    CHECK(integer(GL_VERTEX_ARRAY_BINDING) == GLint(flat.vertexArray));
    CHECK(integer(GL_DRAW_FRAMEBUFFER_BINDING) == GLint(host.framebuffer));
    std::array<GLint, 4> viewport{}, scissor{};
    glGetIntegerv(GL_VIEWPORT, viewport.data());
    glGetIntegerv(GL_SCISSOR_BOX, scissor.data());
    CHECK(viewport == std::array<GLint, 4>{3, 4, 50, 40});
    CHECK(scissor == std::array<GLint, 4>{1, 2, 30, 20});
    CHECK(glIsEnabled(GL_SCISSOR_TEST));
    CHECK(glIsEnabled(GL_BLEND));
    CHECK(integer(GL_BLEND_SRC_RGB) == GL_SRC_COLOR);
    CHECK(integer(GL_BLEND_DST_RGB) == GL_DST_ALPHA);
    CHECK(integer(GL_BLEND_EQUATION_RGB) == GL_MAX);
    CHECK(glIsEnabled(GL_CULL_FACE));
    CHECK(integer(GL_CULL_FACE_MODE) == GL_FRONT);
    CHECK(integer(GL_FRONT_FACE) == GL_CW);
    CHECK(glIsEnabled(GL_DEPTH_TEST));
    CHECK(integer(GL_DEPTH_FUNC) == GL_GREATER);
    GLboolean depthMask = GL_TRUE;
    glGetBooleanv(GL_DEPTH_WRITEMASK, &depthMask);
    CHECK(depthMask == GL_FALSE);
    std::array<GLboolean, 4> colorMask{};
    glGetBooleanv(GL_COLOR_WRITEMASK, colorMask.data());
    CHECK(colorMask == std::array<GLboolean, 4>{GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE});
    CHECK(integer(GL_ACTIVE_TEXTURE) == GL_TEXTURE5);
    glActiveTexture(GL_TEXTURE3);
    CHECK(integer(GL_TEXTURE_BINDING_2D) == GLint(texture));
    CHECK(integer(GL_SAMPLER_BINDING) == GLint(sampler));
    GLint storage = 0;
    glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, 1, &storage);
    CHECK(storage == GLint(buffer));
    CHECK(integer(GL_PACK_ALIGNMENT) == 1);

    // Back to the state the other tests expect.
    glUseProgram(0);
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ZERO);
    glBlendEquation(GL_FUNC_ADD);
    glDisable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
    glDisable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glActiveTexture(GL_TEXTURE0);
    glBindTextureUnit(3, 0);
    glBindSampler(3, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, 0);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glDeleteTextures(1, &texture);
    glDeleteBuffers(1, &buffer);
    glDeleteSamplers(1, &sampler);
    gl.requireNoErrors();
}

TEST_CASE("HostTarget refuses a bad host framebuffer, naming the field", "[gl][host]") {
    test::GlTestScope gl;
    HostTarget target;
    CHECK_THROWS_WITH(target.begin({.framebuffer = 0, .width = 0, .height = 10}),
                      Catch::Contains("HostFramebuffer: width and height must be in [1, 16384], got 0x10"));
    CHECK_THROWS_WITH(target.begin({.framebuffer = 4242, .width = 8, .height = 8}),
                      Catch::Contains("HostFramebuffer::framebuffer: 4242 is not a framebuffer"));
    gl.requireNoErrors();
}

TEST_CASE("HostContext adopts the current context and refuses when none is current", "[gl][host]") {
    test::GlTestScope gl;
    {
        auto adopted = HostContext::adopt({.getProcAddress = eglGetProcAddress, .name = "test host"});
        CHECK(adopted->info().renderer == gl.context().info().renderer);
        CHECK(adopted->info().backend == "test host");
        CHECK_FALSE(adopted->info().debug);  // the host's debug callback (here the test's) stays
    }
    CHECK_THROWS_WITH(HostContext::adopt({}), Catch::Contains("HostContextOptions::getProcAddress is required"));
    const EGLDisplay display = eglGetCurrentDisplay();
    const EGLContext context = eglGetCurrentContext();
    const EGLSurface draw = eglGetCurrentSurface(EGL_DRAW), read = eglGetCurrentSurface(EGL_READ);
    REQUIRE(eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT));
    CHECK_THROWS_WITH(HostContext::adopt({.getProcAddress = eglGetProcAddress}),
                      Catch::Contains("no OpenGL context is current"));
    REQUIRE(eglMakeCurrent(display, draw, read, context));
    gl.requireNoErrors();
}
