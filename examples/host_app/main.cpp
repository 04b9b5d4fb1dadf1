// host_app: a plain GLFW program with its own shaders, a floor and two boxes, that draws a
// libsss volume and a translucent libsss mesh into its own window, in the same frame and depth.
//
//   host_app [--size WxH] [--frames N] [--screenshot FILE.png] [--check] [--no-depth]
//            [--bench N]
//
// --check compares pixels with the host drawing alone: the box in front of the volume keeps
// its pixels (host depth stops the rays), and where the libsss mesh is in front of the box drawn
// after libsss, the mesh stays (libsss depth hides it). --no-depth draws libsss as an overlay
// (HostFramebuffer::depth off), which --check must reject. --bench N times N frames drawn this
// way against libsss rendering into its own target, side by side.
#include "host_gl.h"

#include <sss/sss.h>

#include <GLFW/glfw3.h>
#include <glm/gtc/matrix_transform.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>

namespace {

struct Options {
    int width = 640, height = 400, frames = 3, bench = 0;
    bool check = false, depth = true;
    std::string screenshot;
};

Options parse(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw std::runtime_error(a + ": a value is missing");
            return argv[++i];
        };
        if (a == "--size") {
            if (std::sscanf(value().c_str(), "%dx%d", &o.width, &o.height) != 2 || o.width < 16 || o.height < 16)
                throw std::runtime_error("--size: expected WxH of at least 16x16");
        } else if (a == "--frames") {
            o.frames = std::max(1, std::atoi(value().c_str()));
        } else if (a == "--bench") {
            o.bench = std::max(1, std::atoi(value().c_str()));
        } else if (a == "--screenshot") {
            o.screenshot = value();
        } else if (a == "--check") {
            o.check = true;
        } else if (a == "--no-depth") {
            o.depth = false;
        } else if (a == "--help") {
            std::puts("usage: host_app [--size WxH] [--frames N] [--screenshot FILE.png] [--check] [--no-depth] [--bench N]");
            std::exit(0);
        } else {
            throw std::runtime_error("unknown option " + a);
        }
    }
    return o;
}

// Where things are: the volume behind box A, the translucent mesh in front of box B.
const glm::vec3 kVolumeCentre(-0.55f, 0.1f, -0.4f), kBoxA(-0.55f, -0.05f, 0.7f), kBoxAHalf(0.2f);
const glm::vec3 kMeshCentre(0.55f, 0.05f, 0.45f), kBoxB(0.55f, 0.05f, -0.3f), kBoxBHalf(0.45f, 0.45f, 0.2f);
constexpr float kVolumeScale = 1.2f;

sss::HybridCompositor makeScene() {
    sss::HybridCompositor scene({.clearTarget = false});  // draws over the host's depth (HostTarget)
    const glm::mat4 volumeModel = glm::scale(glm::translate(glm::mat4(1.0f), kVolumeCentre), glm::vec3(kVolumeScale));
    sss::VolumeRenderOptions volume;
    volume.shading = sss::VolumeShading::Scattering;
    scene.addVolume(sss::makeBlobsVolume(48), volumeModel, volume)
        .setTransferFunction(sss::TransferFunction({{0.05f, {0.95f, 0.75f, 0.45f}, 0.0f},
                                                    {0.3f, {0.95f, 0.6f, 0.35f}, 0.8f},
                                                    {1.0f, {1.0f, 0.9f, 0.8f}, 1.0f}}));
    const glm::mat4 meshModel = glm::rotate(glm::translate(glm::mat4(1.0f), kMeshCentre), 1.1f, {1.0f, 0.0f, 0.0f});
    sss::MeshRenderOptions mesh;
    mesh.shading = sss::MeshShading::Scattering;
    mesh.millimetresPerUnit = 40.0;
    scene.addMesh(sss::makeTorus(0.32f, 0.13f), meshModel, mesh).setScatteringMaterial(sss::materialPreset("skin1"));
    scene.setLights({sss::DirectionalLight{.direction = {-0.4f, -1.0f, -0.6f}, .intensity = 3.0f}});
    return scene;
}

sss::Camera makeCamera() {
    sss::Camera camera;
    camera.setDistance(3.2f);
    camera.setYaw(0.0f);
    camera.setPitch(12.0f);
    return camera;
}

class HostApp {
public:
    HostApp(const Options& options, GLFWwindow* window)
        : m_options(options), m_window(window), m_gl(host::Gl::load()), m_flat(m_gl),
          m_context(sss::HostContext::adopt({.getProcAddress = glfwGetProcAddress, .name = "host_app GLFW window"})),
          m_scene(makeScene()), m_camera(makeCamera()) {
        glfwGetFramebufferSize(window, &m_width, &m_height);
        m_viewProjection = m_camera.projection(float(m_width) / float(m_height)) * m_camera.view();
    }

    // One frame: the host's opaque geometry, libsss in the host's framebuffer, then box B.
    void drawFrame(bool withLibsss) {
        m_gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
        m_gl.Viewport(0, 0, m_width, m_height);
        m_gl.ClearColor(0.55f, 0.62f, 0.7f, 1.0f);
        m_gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        m_gl.Enable(GL_DEPTH_TEST);
        m_flat.drawFloor(m_viewProjection, -0.6f, 2.0f, {0.5f, 0.5f, 0.45f, 1.0f});
        m_flat.drawBox(m_viewProjection, kBoxA, kBoxAHalf, {0.85f, 0.25f, 0.2f, 1.0f});
        if (withLibsss) {
            sss::HostTarget::Frame frame =
                m_libsss.begin({.framebuffer = 0, .width = m_width, .height = m_height, .depth = m_options.depth});
            m_scene.render(m_camera, frame.target());
            frame.present();
        }
        m_flat.drawBox(m_viewProjection, kBoxB, kBoxBHalf, {0.2f, 0.45f, 0.85f, 1.0f});
        m_gl.Disable(GL_DEPTH_TEST);
    }

    // The same scene through libsss's own target, blitted into the window: the baseline.
    void drawOwnTarget() {
        if (!m_own) m_own.emplace(m_width, m_height);
        m_own->clear({0.55f, 0.62f, 0.7f, 1.0f});
        m_scene.render(m_camera, *m_own);
        m_encoder.encode(*m_own);
        m_gl.BlitNamedFramebuffer(m_encoder.framebufferId(), 0, 0, 0, m_width, m_height, 0, 0, m_width, m_height,
                                  GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }

    sss::Image8 readWindow() const {
        sss::Image8 image(m_width, m_height);
        m_gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
        m_gl.ReadBuffer(GL_BACK);
        m_gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
        m_gl.ReadPixels(0, 0, m_width, m_height, GL_RGBA, GL_UNSIGNED_BYTE, image.data().data());
        m_gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
        return image.flippedVertically();
    }

    // The pixel (top row first) that a world point projects to.
    glm::ivec2 pixelOf(glm::vec3 p) const {
        const glm::vec4 clip = m_viewProjection * glm::vec4(p, 1.0f);
        const glm::vec2 ndc = glm::vec2(clip) / clip.w;
        return {int((ndc.x * 0.5f + 0.5f) * float(m_width)), int((0.5f - ndc.y * 0.5f) * float(m_height))};
    }

    // A rectangle of pixels (x0, y0, x1, y1; top row first) inside the projection of a box's
    // face towards the camera, 2 pixels in from its edges (inner) or around it (outer).
    glm::ivec4 frontFace(glm::vec3 centre, glm::vec3 half, bool inner = true) const {
        const glm::ivec2 topLeft = pixelOf(centre + glm::vec3(-half.x, half.y, half.z));
        const glm::ivec2 topRight = pixelOf(centre + glm::vec3(half.x, half.y, half.z));
        const glm::ivec2 bottomLeft = pixelOf(centre + glm::vec3(-half.x, -half.y, half.z));
        const glm::ivec2 bottomRight = pixelOf(centre + glm::vec3(half.x, -half.y, half.z));
        const auto pick = [inner](int a, int b, bool low) { return (low == inner) ? std::max(a, b) : std::min(a, b); };
        glm::ivec4 r(pick(topLeft.x, bottomLeft.x, true), pick(topLeft.y, topRight.y, true),
                     pick(topRight.x, bottomRight.x, false), pick(bottomLeft.y, bottomRight.y, false));
        if (inner) r += glm::ivec4(2, 2, -2, -2);
        return glm::clamp(r, glm::ivec4(0), glm::ivec4(m_width - 1, m_height - 1, m_width - 1, m_height - 1));
    }

    int check();
    void bench();
    void run();

private:
    const Options& m_options;
    GLFWwindow* m_window;
    host::Gl m_gl;
    host::FlatRenderer m_flat;
    std::unique_ptr<sss::HostContext> m_context;
    sss::HybridCompositor m_scene;
    sss::Camera m_camera;
    sss::HostTarget m_libsss;
    std::optional<sss::RenderTarget> m_own;
    sss::DisplayEncoder m_encoder;
    int m_width = 0, m_height = 0;
    glm::mat4 m_viewProjection{1.0f};
};

// Pixels where the frame with libsss differs from the host's frame alone, inside `rect`
// (x0, y0, x1, y1) and outside `except`.
int differing(const sss::Image8& a, const sss::Image8& b, glm::ivec4 rect, glm::ivec4 except = glm::ivec4(-1)) {
    int count = 0;
    for (int y = rect.y; y <= rect.w; ++y)
        for (int x = rect.x; x <= rect.z; ++x) {
            const bool excepted = x >= except.x && x <= except.z && y >= except.y && y <= except.w;
            if (!excepted && a.at(x, y) != b.at(x, y)) ++count;
        }
    return count;
}

int HostApp::check() {
    drawFrame(false);
    const sss::Image8 hostOnly = readWindow();
    drawFrame(true);
    const sss::Image8 both = readWindow();
    const glm::ivec4 boxA = frontFace(kBoxA, kBoxAHalf), boxB = frontFace(kBoxB, kBoxBHalf);
    const glm::vec3 volumeHalf(0.5f * kVolumeScale);
    const glm::ivec4 volume = frontFace(kVolumeCentre, volumeHalf, false);
    struct Probe {
        const char* what;
        int changed;
        bool expectChanged;
    };
    const Probe probes[] = {
        {"the host's box A in front of the libsss volume keeps its pixels", differing(hostOnly, both, boxA), false},
        {"the libsss volume shows beside box A", differing(hostOnly, both, volume, boxA), true},
        {"the libsss mesh hides the host's box B drawn after it", differing(hostOnly, both, boxB), true},
    };
    int failures = 0;
    for (const Probe& p : probes) {
        const bool ok = (p.changed > 20) == p.expectChanged && (p.expectChanged || p.changed == 0);
        failures += ok ? 0 : 1;
        std::printf("%s: %s (%d pixels differ from the host's frame alone)\n", ok ? "ok" : "FAILED", p.what, p.changed);
    }
    return failures == 0 ? 0 : 1;
}

void HostApp::bench() {
    auto time = [&](auto&& frame) {
        frame();  // warm: maps, light volumes, programs
        m_gl.Finish();
        const auto start = std::chrono::steady_clock::now();
        for (int i = 0; i < m_options.bench; ++i) frame();
        m_gl.Finish();
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() /
               m_options.bench;
    };
    // Scattering maps and light volumes first: the timed frames are fixed frames.
    for (int i = 0; i < 12; ++i) drawFrame(true);
    m_gl.Finish();
    for (int round = 0; round < 3; ++round) {  // alternate, so drift hits both
        const double own = time([&] { drawOwnTarget(); });
        const double hosted = time([&] { drawFrame(true); });
        std::printf("bench round %d: own target + blit %.2f ms, host framebuffer %.2f ms, ratio %.3f\n", round, own,
                    hosted, hosted / own);
    }
}

void HostApp::run() {
    for (int i = 0; i < m_options.frames; ++i) {
        drawFrame(true);
        if (i + 1 == m_options.frames && !m_options.screenshot.empty()) {
            readWindow().savePng(m_options.screenshot);  // savePng: component io
            std::printf("wrote %s\n", m_options.screenshot.c_str());
        }
        glfwSwapBuffers(m_window);
        glfwPollEvents();
    }
}

}  // namespace

int main(int argc, char** argv) {
    try {
        const Options options = parse(argc, argv);
        if (!glfwInit()) throw std::runtime_error("cannot initialise GLFW (is there a display?)");
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
        glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
        glfwWindowHint(GLFW_DEPTH_BITS, 24);
        GLFWwindow* window = glfwCreateWindow(options.width, options.height, "libsss in a host application", nullptr, nullptr);
        if (!window) throw std::runtime_error("cannot create a GL 4.5 core window");
        glfwMakeContextCurrent(window);
        int status = 0;
        {
            HostApp app(options, window);
            if (options.check) status = app.check();
            if (options.bench > 0) app.bench();
            if (!options.check && options.bench == 0) app.run();
        }  // libsss objects go before the host's context
        glfwDestroyWindow(window);
        glfwTerminate();
        return status;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "host_app: %s\n", e.what());
        return 1;
    }
}
