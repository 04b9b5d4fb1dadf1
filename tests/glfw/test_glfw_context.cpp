// GlfwContext tests. ctest runs "[window]" cases under xvfb-run and "[no-display]" cases with
// DISPLAY unset (see tests/CMakeLists.txt).
#include "support/gl_test.h"

#include "gl/gl.h"

#include <catch2/catch.hpp>
#include <sss/error.h>
#include <sss/glfw_context.h>
#include <sss/mesh_scattering_renderer.h>
#include <sss/procedural.h>
#include <sss/render_target.h>

#include <vector>

using namespace sss;

TEST_CASE("GLFW window context renders and presents a mesh", "[window]") {
    auto context = GlfwContext::create({.width = 160, .height = 90, .title = "sss test", .debug = true});
    REQUIRE(context->info().version.rfind("4.", 0) == 0);
    REQUIRE(context->info().debug);
    const glm::ivec2 size = context->framebufferSize();
    REQUIRE(size.x > 0);
    {
        RenderTarget target(size.x, size.y);
        target.clear({0.1f, 0.1f, 0.12f, 1.0f});
        MeshScatteringRenderer renderer;
        renderer.setMesh(makeUvSphere());
        Camera camera;
        renderer.render(camera, target);
        // Show the offscreen image in the window, as an application would.
        glBlitNamedFramebuffer(target.framebufferId(), 0, 0, 0, size.x, size.y, 0, 0, size.x, size.y,
                               GL_COLOR_BUFFER_BIT, GL_NEAREST);
        std::vector<unsigned char> pixel(4);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
        glReadBuffer(GL_BACK);
        glReadPixels(size.x / 2, size.y / 2, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, pixel.data());
        const Image8 offscreen = target.readColor().toRgba8();
        // The window's framebuffer holds what the renderer drew (the sphere covers the centre).
        CHECK(pixel[0] == offscreen.at(size.x / 2, size.y - 1 - size.y / 2).r);
        CHECK(pixel[0] > 100);
        context->swapBuffers();
        context->pollEvents();
    }
    CHECK(context->debugMessages().errors == 0);
}

TEST_CASE("GLFW without a display fails with a clear error", "[no-display]") {
    try {
        auto context = GlfwContext::create();
        FAIL("a window was created without a display");
    } catch (const Error& e) {
        CHECK(e.kind() == ErrorKind::Gl);
        CHECK_THAT(e.what(), Catch::Contains("display"));
    }
}
