// sss-viewer: interactive viewer for light scattering in meshes and volumes (GLFW + Dear ImGui).
// Run `sss-viewer --help` for the options. Exit codes: 0 ok, 1 runtime failure, 2 bad usage.
//
// Viewer (here) owns the window, the frame loop, input, screenshots and --dump-state;
// ViewerModel (viewer_model.h) the scene and its settings; Panels (viewer_panels.h) the UI.
#include "present_gl.h"
#include "viewer_model.h"
#include "viewer_options.h"
#include "viewer_panels.h"
#include "viewer_state.h"

#include <sss/frame_accumulator.h>
#include <sss/glfw_context.h>
#include <sss/scene.h>
#include <sss/sss.h>

#include <GLFW/glfw3.h>
#include <glm/trigonometric.hpp>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace viewer {
namespace {

// The viewer stops path tracing a still scene at this many paths per pixel (noise about 1/64 of one path's).
constexpr int kMaxViewerPaths = 4096;

class Viewer {
public:
    Viewer(const ViewerOptions& args, std::unique_ptr<sss::GlfwContext> context)
        : m_context(std::move(context)), m_model(args), m_panels(m_model) {
        m_gl.emplace();
        m_model.renderer = m_context->info().renderer;
        IMGUI_CHECKVERSION();
        ImGui::CreateContext();
        ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the working directory
        ImGui::StyleColorsDark();
        ImGui::GetStyle().WindowRounding = 4.0f;
        ImGui_ImplGlfw_InitForOpenGL(static_cast<GLFWwindow*>(m_context->nativeWindow()), true);
        ImGui_ImplOpenGL3_Init("#version 450");
    }

    ~Viewer() {
        // GL objects go before the ImGui backend, and both before the context.
        m_model.compositor.reset();
        m_model.target.reset();
        m_accumulator.reset();
        m_display.reset();
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
        m_context.reset();
    }

    Viewer(const Viewer&) = delete;
    Viewer& operator=(const Viewer&) = delete;

    ViewerModel& model() { return m_model; }
    int run();

private:
    void drawFrame(bool saveScreenshot);
    void renderScene(glm::ivec2 size);
    // --dump-state: the state after this frame (running) or at exit.
    void dumpState(bool running);
    void writeScreenshot(const std::string& path, bool withUi);
    void handleInput();

    std::unique_ptr<sss::GlfwContext> m_context;
    std::optional<PresentGl> m_gl;
    ViewerModel m_model;
    Panels m_panels;
    std::optional<sss::DisplayEncoder> m_display;        // the model's target as a display image
    std::optional<sss::FrameAccumulator> m_accumulator;  // the anti-aliased mean of the target's frames
    glm::mat4 m_lastViewProjection{0.0f};
    std::array<double, 16> m_frameTimes{};
    int m_uiVertices = 0;
    std::vector<std::string> m_screenshotsWritten;  // by F12 / Save, for --dump-state
};

int Viewer::run() {
    const int frames = m_model.args.exitAfter;
    const Clock::time_point start = Clock::now();
    for (int frame = 0; frames == 0 || frame < frames; ++frame) {
        if (m_context->shouldClose()) break;
        if (m_model.args.timeout > 0.0 && msSince(start) > 1000.0 * m_model.args.timeout) {
            std::fprintf(stderr, "sss-viewer: --timeout: the window is still open after %g s\n", m_model.args.timeout);
            dumpState(false);
            return 1;
        }
        const bool last = frames > 0 && frame + 1 == frames;
        drawFrame(last && !m_model.args.screenshot.empty());
    }
    dumpState(false);
    if (!m_model.args.saveScene.empty()) m_model.saveScene(m_model.args.saveScene);
    if (m_model.args.exitAfter > 0) {
        // Batch runs double as tests: a GL error reported through KHR_debug is a failure.
        const sss::DebugMessageCounts counts = m_context->debugMessages();
        if (counts.errors > 0) {
            std::fprintf(stderr, "sss-viewer: %llu GL error(s), the last: %s\n",
                         static_cast<unsigned long long>(counts.errors), m_context->lastDebugError().c_str());
            return 1;
        }
        std::printf("rendered %d frames\n", m_model.frameIndex);
    }
    return 0;
}

void Viewer::drawFrame(bool saveScreenshot) {
    const Clock::time_point start = Clock::now();
    m_context->pollEvents();
    const glm::ivec2 fb = m_context->framebufferSize();
    if (fb.x <= 0 || fb.y <= 0) {  // minimised: nothing to draw into
        glfwWaitEventsTimeout(0.1);
        return;
    }
    if (!m_model.target || m_model.target->width() != fb.x || m_model.target->height() != fb.y) m_model.target.emplace(fb.x, fb.y);
    if (m_model.frameIndex == 0) m_model.reframe();  // the panel offset needs the target's size

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    m_panels.beginFrame();
    handleInput();
    if (m_model.showUi) {
        m_panels.draw();
        m_panels.drawOverlay();
    }
    m_model.applyChanges();

    const Clock::time_point renderStart = Clock::now();
    renderScene(fb);
    if (m_model.honestTimings) sss::finishGpuWork();
    m_model.renderMs = msSince(renderStart);
    m_model.trackProgress();

    if (saveScreenshot && !m_model.args.screenshotUi) writeScreenshot(m_model.args.screenshot, false);
    if (m_model.screenshotRequested) writeScreenshot(m_model.screenshotPath, false);

    // The target holds linear radiance; the window shows its display image.
    if (!m_display) m_display.emplace();
    m_display->encode(m_accumulator->result(), m_model.displayTransform);
    m_gl->present(m_display->framebufferId(), fb.x, fb.y, fb.x, fb.y);
    ImGui::Render();
    m_uiVertices = ImGui::GetDrawData()->TotalVtxCount;
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (saveScreenshot && m_model.args.screenshotUi) writeScreenshot(m_model.args.screenshot, true);
    m_context->swapBuffers();

    // Mean over the last frames, so the display is readable but follows changes quickly.
    m_frameTimes[static_cast<std::size_t>(m_model.frameIndex) % m_frameTimes.size()] = msSince(start);
    ++m_model.frameIndex;
    const std::size_t n = std::min(m_frameTimes.size(), static_cast<std::size_t>(m_model.frameIndex));
    m_model.frameMs = 0.0;
    for (std::size_t i = 0; i < n; ++i) m_model.frameMs += m_frameTimes[i] / static_cast<double>(n);
    dumpState(true);
}

// The scene. While nothing moves and the maps have converged, each frame adds one more
// sub-pixel-jittered frame to the anti-aliased mean (FrameAccumulator), up to --aa; then the
// picture is final and the scene is not drawn again.
void Viewer::renderScene(glm::ivec2 size) {
    const glm::mat4 viewProjection = m_model.camera.projection(m_model.target->aspect()) * m_model.camera.view();
    if (!m_accumulator || m_accumulator->result().width() != size.x || m_accumulator->result().height() != size.y)
        m_accumulator.emplace(size.x, size.y);
    if (m_model.viewChanged || viewProjection != m_lastViewProjection || !m_model.mapsConverged ||
        m_model.volumeRefining())
        m_accumulator->reset();
    m_model.viewChanged = false;
    m_lastViewProjection = viewProjection;
    if (m_model.pathTracing()) {
        // The path tracer keeps its own running mean (through pixel centres: sub-pixel
        // offsets would restart it); the accumulator just holds its latest picture.
        if (m_accumulator->frames() == 0 || m_model.compositor->volume(0).accumulatedSamples() < kMaxViewerPaths) {
            try {
                m_model.compositor->render(m_model.camera, *m_model.target);
            } catch (const sss::Error& e) {
                m_model.showMessage(e.what(), true);
                m_model.target->clear(m_model.hybrid.background);
            }
            m_accumulator->reset();
            m_accumulator->add(*m_model.target);
        }
    } else if (m_accumulator->frames() < m_model.args.antiAliasing) {
        try {
            m_model.camera.setSubpixelOffset(sss::FrameAccumulator::subpixelOffset(m_accumulator->frames(), size.x, size.y));
            m_model.compositor->render(m_model.camera, *m_model.target);
            m_model.camera.setSubpixelOffset({0.0f, 0.0f});
            m_accumulator->add(*m_model.target);
        } catch (const sss::Error& e) {
            // Bad settings must not end an interactive session; the message says what failed.
            m_model.camera.setSubpixelOffset({0.0f, 0.0f});
            m_model.showMessage(e.what(), true);
            m_model.target->clear(m_model.hybrid.background);
            m_accumulator->reset();
            m_accumulator->add(*m_model.target);
        }
    }
}

// --dump-state: the state after this frame (running) or at exit.
void Viewer::dumpState(bool running) {
    if (m_model.args.dumpState.empty()) return;
    ViewerState state;
    state.frame = m_model.frameIndex;
    state.running = running;
    state.window = m_context->framebufferSize();
    state.camera = m_model.camera;
    state.uiShown = m_model.showUi;
    state.uiVertices = m_uiVertices;
    const UiLayout& layout = m_panels.layout();
    state.panel = layout.panel;
    state.overlay = layout.overlay;
    state.tfWindow = layout.tfWindow;
    state.tfCanvas = layout.tfCanvas;
    state.editor = &m_model.tfEditor;
    state.screenshots = m_screenshotsWritten;
    const sss::DebugMessageCounts counts = m_context->debugMessages();
    state.glErrors = counts.errors;
    state.lastGlError = counts.errors > 0 ? m_context->lastDebugError() : std::string();
    writeViewerState(m_model.args.dumpState, state);
}

void Viewer::writeScreenshot(const std::string& path, bool withUi) {
    m_model.screenshotRequested = false;
    try {
        if (withUi) {
            const glm::ivec2 fb = m_context->framebufferSize();
            m_gl->readBackBuffer(fb.x, fb.y).savePng(path);
        } else {
            sss::toDisplay(m_accumulator->result().readColor(), m_model.displayTransform).savePng(path);
        }
        std::printf("wrote %s\n", path.c_str());
        std::fflush(stdout);
        m_screenshotsWritten.push_back(path);
        m_model.showMessage("saved " + path, false);
    } catch (const sss::Error& e) {
        if (m_model.args.exitAfter > 0) throw;  // batch: a screenshot that cannot be written is a failure
        m_model.showMessage(e.what(), true);
    }
}

void Viewer::handleInput() {
    ImGuiIO& io = ImGui::GetIO();
    if (!io.WantCaptureKeyboard) {
        if (ImGui::IsKeyPressed(GLFW_KEY_F1, false)) m_model.showUi = !m_model.showUi;
        if (ImGui::IsKeyPressed(GLFW_KEY_F, false)) m_model.reframe();
    }
    if (ImGui::IsKeyPressed(GLFW_KEY_F12, false)) m_model.screenshotRequested = true;
    if (io.KeyCtrl && ImGui::IsKeyPressed(GLFW_KEY_Q, false))
        glfwSetWindowShouldClose(static_cast<GLFWwindow*>(m_context->nativeWindow()), GLFW_TRUE);
    if (io.WantCaptureMouse) return;
    const glm::vec2 delta(io.MouseDelta.x, io.MouseDelta.y);
    if (ImGui::IsMouseDragging(ImGuiMouseButton_Left, 0.0f)) m_model.camera.orbit(-0.3f * delta.x, 0.3f * delta.y);
    if (ImGui::IsMouseDragging(ImGuiMouseButton_Right, 0.0f) ||
        ImGui::IsMouseDragging(ImGuiMouseButton_Middle, 0.0f)) {
        // Scene points under the cursor follow it (at the target's depth).
        const float perPixel = 2.0f * std::tan(glm::radians(m_model.camera.fovY()) * 0.5f) /
                               static_cast<float>(std::max(1, m_model.target->height()));
        m_model.camera.pan(glm::vec2(-delta.x, delta.y) * perPixel);
    }
    if (io.MouseWheel != 0.0f) m_model.camera.zoom(std::pow(0.88f, io.MouseWheel));
}

bool isJson(const std::string& name) { return name.size() > 5 && name.substr(name.size() - 5) == ".json"; }

int run(ViewerOptions args) {
    // Load and check everything before opening a window, so bad input fails fast and clearly.
    const fs::path dataDir = viewer::dataDirectory(args.input.dataDir);
    const fs::path searchDirs[] = {dataDir};
    std::optional<sss::Mesh> mesh;
    std::optional<sss::Volume> volume;
    std::optional<sss::SceneDescription> scene;
    std::string tfName;
    std::optional<sss::TransferFunction> tf;
    if (!args.input.scene.empty()) {
        scene = sss::loadSceneFile(args.input.scene);
        // The viewer edits one mesh, one volume and one directional light; anything more would be
        // dropped without a word, so it is refused.
        const std::string file = args.input.scene;
        if (scene->meshes.size() > 1 || scene->volumes.size() > 1)
            throw sss::Error(sss::ErrorKind::InvalidArgument,
                             file + ": sss-viewer shows at most one mesh and one volume; this scene has " +
                                 std::to_string(scene->meshes.size()) + " and " + std::to_string(scene->volumes.size()) +
                                 " (render it with sss-render --scene)");
        const bool isosurface = !scene->meshes.empty() && scene->meshes.front().isosurface;
        const bool hidden = !scene->volumes.empty() && !scene->volumes.front().visible;
        if (isosurface || hidden)
            throw sss::Error(sss::ErrorKind::InvalidArgument,
                             file + ": sss-viewer opens mesh files and shows its volume; this scene has " +
                                 (isosurface ? "an isosurface mesh" : "a hidden volume") +
                                 " (render it with sss-render --scene)");
        if (scene->lights.size() > 1 ||
            (scene->lights.size() == 1 && !std::holds_alternative<sss::DirectionalLight>(scene->lights.front())))
            throw sss::Error(sss::ErrorKind::InvalidArgument,
                             file + ": sss-viewer's light is one directional light; this scene has " +
                                 std::to_string(scene->lights.size()) +
                                 " light(s) of other kinds (render it with sss-render --scene)");
        const sss::SceneAssets assets = sss::loadSceneAssets(*scene, searchDirs);
        if (!assets.meshes.empty()) mesh = assets.meshes.front();
        if (!assets.volumes.empty()) {
            volume = assets.volumes.front();
            tf = assets.transferFunctions.front();
            const sss::SceneTransferFunction& t = scene->volumes.front().transferFunction;
            tfName = t.points.empty() ? (t.file.empty() ? t.preset : t.file) : "ramp";
        }
        args.cornellBox = scene->options.cornellBox;
        args.camera = scene->camera;
        args.yawGiven = args.pitchGiven = true;
        args.width = scene->output.width;
        args.height = scene->output.height;
        args.antiAliasing = scene->output.antiAliasing;
    } else {
        if (!args.input.mesh.empty()) mesh = viewer::loadSceneMesh(args.input.mesh, dataDir);
        if (!args.input.volume.empty())
            volume = viewer::loadSceneVolume(args.input.volume, dataDir, args.input.raw);
        sss::materialPreset(args.material);
    }
    if (!tf) {
        tfName = args.input.tf.empty() ? viewer::guessPreset(args.input.volume) : args.input.tf;
        tf = isJson(tfName) ? sss::TransferFunction::loadParaViewJson(tfName, args.input.tfRange)
                            : sss::TransferFunction::preset(tfName);
    }

    auto context = sss::GlfwContext::create({.width = args.width,
                                             .height = args.height,
                                             .title = "sss-viewer",
                                             .visible = true,
                                             .vsync = args.vsync});
    Viewer viewer(args, std::move(context));
    if (scene) viewer.model().setSceneOptions(*scene);
    viewer.model().setInitialScene(std::move(mesh), std::move(volume), std::move(*tf), tfName);
    return viewer.run();
}

}  // namespace
}  // namespace viewer

int main(int argc, char** argv) {
    return examples::runReportingErrors("sss-viewer", [&] { return viewer::run(viewer::parseArgs(argc, argv)); });
}
