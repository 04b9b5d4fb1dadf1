// sss-viewer: interactive viewer for light scattering in meshes and volumes (GLFW + Dear ImGui).
// Run `sss-viewer --help` for the options. Exit codes: 0 ok, 1 runtime failure, 2 bad usage.
#include "present_gl.h"
#include "tf_editor_widget.h"
#include "viewer_options.h"

#include <sss/option_names.h>
#include <sss/scene.h>
#include "viewer_state.h"

#include <sss/glfw_context.h>
#include <sss/hybrid_compositor.h>
#include <sss/materials.h>
#include <sss/sss.h>
#include <sss/transfer_function_editor.h>

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>
#include <imgui_stdlib.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using viewer::UsageError;
using viewer::ViewerOptions;

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Meshes are scaled to a largest side of 1 and centred, like Volume::worldBounds(), so any two
// inputs fit side by side; --scale then says how many millimetres that unit is.
sss::Mesh normalised(const sss::Mesh& mesh) {
    const sss::Bounds b = mesh.bounds();
    const glm::vec3 size = b.size();
    const float largest = std::max({size.x, size.y, size.z, 1e-12f});
    return mesh.transformed(glm::scale(glm::mat4(1.0f), glm::vec3(1.0f / largest)) *
                            glm::translate(glm::mat4(1.0f), -b.center()));
}

constexpr std::array<int, 5> kMapResolutions{128, 256, 512, 1024, 2048};
constexpr std::array<int, 4> kShadowResolutions{256, 512, 1024, 2048};
// The viewer stops path tracing a still scene at this many paths per pixel (noise about 1/64 of one path's).
constexpr int kMaxViewerPaths = 4096;

bool comboInt(const char* label, int& value, const int* options, std::size_t count) {
    bool changed = false;
    if (ImGui::BeginCombo(label, std::to_string(value).c_str())) {
        for (std::size_t i = 0; i < count; ++i) {
            if (ImGui::Selectable(std::to_string(options[i]).c_str(), options[i] == value)) {
                changed = options[i] != value;
                value = options[i];
            }
        }
        ImGui::EndCombo();
    }
    return changed;
}

bool colorEdit(const char* label, glm::vec3& color) {
    float c[3] = {color.r, color.g, color.b};
    if (!ImGui::ColorEdit3(label, c, ImGuiColorEditFlags_Float)) return false;
    color = glm::clamp(glm::vec3(c[0], c[1], c[2]), glm::vec3(0.0f), glm::vec3(1.0f));
    return true;
}

bool dragDvec3(const char* label, glm::dvec3& v, float speed, float lo, float hi, const char* format) {
    float f[3] = {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)};
    if (!ImGui::DragFloat3(label, f, speed, lo, hi, format)) return false;
    v = glm::dvec3(f[0], f[1], f[2]);
    return true;
}

class Viewer {
public:
    Viewer(const ViewerOptions& args, std::unique_ptr<sss::GlfwContext> context)
        : m_args(args), m_dataDir(viewer::dataDirectory(args.input.dataDir)), m_context(std::move(context)) {
        m_gl.emplace();
        m_compositor.emplace(m_hybrid);
        IMGUI_CHECKVERSION();
        ImGui::CreateContext();
        ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the working directory
        ImGui::StyleColorsDark();
        ImGui::GetStyle().WindowRounding = 4.0f;
        ImGui_ImplGlfw_InitForOpenGL(static_cast<GLFWwindow*>(m_context->nativeWindow()), true);
        ImGui_ImplOpenGL3_Init("#version 450");

        m_meshPath = args.input.mesh;
        m_volumePath = args.input.volume;
        m_volumeRaw = args.input.raw;
        m_showUi = !args.hideUi;
        m_meshOptions = args.mesh;
        // Ambient light for the faces the light misses, as sss-render does: on in a Cornell box.
        if (args.cornellBox && m_meshOptions.environment == glm::vec3(0.0f)) m_meshOptions.environment = glm::vec3(0.05f);
        m_volumeOptions = args.volume;
        setVolumeShading(args.volume.shading);
        m_volumeMultiple = args.volume.multipleScattering;
        m_displayTransform = args.display;
        m_hybrid.cornellBox = args.cornellBox;
        m_lightAzimuth = args.lightAzimuth;
        m_lightElevation = args.lightElevation;
        m_lightColor = args.lightColor;
        m_lightIntensity = args.lightIntensity;
        m_material = sss::materialPreset(args.material);
        const auto names = sss::materialPresetNames();
        const auto found = std::find(names.begin(), names.end(), m_material.name);
        m_materialIndex = found == names.end() ? -1 : static_cast<int>(found - names.begin());
    }

    ~Viewer() {
        // GL objects go before the ImGui backend, and both before the context.
        m_compositor.reset();
        m_target.reset();
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
        m_context.reset();
    }

    Viewer(const Viewer&) = delete;
    Viewer& operator=(const Viewer&) = delete;

    /// Shows what the command line named (loaded before the window opened, see run()).
    void setInitialScene(std::optional<sss::Mesh> mesh, std::optional<sss::Volume> volume, sss::TransferFunction tf,
                         const std::string& tfName) {
        if (mesh) m_mesh = m_meshTransform ? *mesh : normalised(*mesh);  // a scene's mesh is sized by the scene
        if (volume) setVolume(std::move(*volume), m_args.input.volume);
        m_tfEditor = sss::TransferFunctionEditor(std::move(tf));
        if (tfName.size() > 5 && tfName.substr(tfName.size() - 5) == ".json") m_tfPath = tfName;
        else m_tfPreset = tfName;
        rebuildScene();
        reframe();
        const sss::SceneCamera& c = m_args.camera;
        m_camera.setYaw(m_args.yawGiven || !m_hybrid.cornellBox ? c.yaw : 14.0f);
        m_camera.setPitch(m_args.pitchGiven || !m_hybrid.cornellBox ? c.pitch : 12.0f);
        m_camera.setFovY(c.fovY);
        m_camera.setProjectionType(c.projection);
        if (c.target && c.distance) {
            m_camera.setTarget(*c.target);
            m_camera.setDistance(*c.distance);
            m_camera.setClipPlanes(*c.distance * 0.01f, *c.distance * 10.0f);
        }
        if (c.zoom != 1.0f) m_camera.zoom(c.zoom);
    }

    /// Opens a scene file's content: its mesh and volume with their placement, options and
    /// materials, its light and camera (run() checked that the viewer can show all of it).
    void setSceneOptions(const sss::SceneDescription& scene) {
        m_hybrid = scene.options;
        if (!scene.meshes.empty()) {
            const sss::SceneMesh& m = scene.meshes.front();
            m_meshPath = m.source;
            m_meshTransform = m.transform;
            m_meshSize = m.size;
            m_meshOptions = m.options;
            m_material = m.material;
            m_blinnPhong = m.baseline;
        }
        if (!scene.volumes.empty()) {
            const sss::SceneVolume& v = scene.volumes.front();
            m_volumePath = v.source;
            m_volumeRaw = v.raw;
            m_volumeTransform = v.transform;
            m_volumeOptions = v.options;
            setVolumeShading(v.options.shading);
            m_volumeMultiple = v.options.multipleScattering;
        }
        if (!scene.lights.empty()) {
            const auto& d = std::get<sss::DirectionalLight>(scene.lights.front());
            const glm::vec3 towardsLight = -glm::normalize(d.direction);
            m_lightElevation = glm::degrees(std::asin(std::clamp(towardsLight.y, -1.0f, 1.0f)));
            m_lightAzimuth = glm::degrees(std::atan2(towardsLight.x, towardsLight.z));
            m_lightColor = d.color;
            m_lightIntensity = d.intensity;
        }
        m_displayTransform = scene.output.display;
    }

    /// The scene shown, as a scene description (mesh and volume as opened, normalised to one
    /// unit, placed as shown; the transfer function inline; the camera where it is).
    sss::SceneDescription describeScene() const {
        sss::SceneDescription scene;
        scene.options = m_hybrid;
        if (m_mesh) {
            sss::SceneMesh m;
            m.source = m_meshPath;
            m.size = m_meshSize;
            m.transform = meshTransform();
            m.options = meshOptions();
            m.options.finishEachPass = false;
            m.material = m_material;
            m.baseline = m_blinnPhong;
            scene.meshes.push_back(m);
        }
        if (m_volume) {
            sss::SceneVolume v;
            v.source = m_volumeLabel;
            v.raw = m_volumeRaw;
            v.valueWindow = m_volume->transferFunctionRange();
            v.transferFunction.points = m_tfEditor.transferFunction().points();
            v.transform = volumeTransform();
            v.options = volumeOptions();
            v.options.finishEachPass = false;
            scene.volumes.push_back(v);
        }
        scene.lights = {light()};
        scene.camera.yaw = m_camera.yaw();
        scene.camera.pitch = m_camera.pitch();
        scene.camera.fovY = m_camera.fovY();
        scene.camera.projection = m_camera.projectionType();
        scene.camera.target = m_camera.target();
        scene.camera.distance = m_camera.distance();
        if (m_target) scene.output.width = m_target->width(), scene.output.height = m_target->height();
        scene.output.antiAliasing = m_args.antiAliasing;
        scene.output.display = m_displayTransform;
        return scene;
    }

    void saveScene(const std::string& path) {
        try {
            sss::saveSceneFile(describeScene(), path);
            showMessage("saved the scene as " + path, false);
            std::printf("wrote %s\n", path.c_str());
        } catch (const std::exception& e) {
            if (m_args.exitAfter > 0) throw;  // batch: a scene that cannot be written is a failure
            showMessage(e.what(), true);
        }
    }

    void setVolumeShading(sss::VolumeShading shading) {
        m_volumeScattering = shading == sss::VolumeShading::Scattering || shading == sss::VolumeShading::ScatteringGradient;
        m_volumeHighlights = shading == sss::VolumeShading::ScatteringGradient;
        m_volumeBaselineGradient = shading != sss::VolumeShading::EmissionAbsorption;
    }

    int run() {
        const int frames = m_args.exitAfter;
        const Clock::time_point start = Clock::now();
        for (int frame = 0; frames == 0 || frame < frames; ++frame) {
            if (m_context->shouldClose()) break;
            if (m_args.timeout > 0.0 && msSince(start) > 1000.0 * m_args.timeout) {
                std::fprintf(stderr, "sss-viewer: --timeout: the window is still open after %g s\n", m_args.timeout);
                dumpState(false);
                return 1;
            }
            const bool last = frames > 0 && frame + 1 == frames;
            drawFrame(last && !m_args.screenshot.empty());
        }
        dumpState(false);
        if (!m_args.saveScene.empty()) saveScene(m_args.saveScene);
        if (m_args.exitAfter > 0) {
            // Batch runs double as tests: a GL error reported through KHR_debug is a failure.
            const sss::DebugMessageCounts counts = m_context->debugMessages();
            if (counts.errors > 0) {
                std::fprintf(stderr, "sss-viewer: %llu GL error(s), the last: %s\n",
                             static_cast<unsigned long long>(counts.errors), m_context->lastDebugError().c_str());
                return 1;
            }
            std::printf("rendered %d frames\n", m_frameIndex);
        }
        return 0;
    }

private:
    // ---- scene -------------------------------------------------------------------------------
    void setVolume(sss::Volume volume, const std::string& label) {
        if (!volume.valueWindow()) volume.setValueWindow(m_args.input.tfRange);  // --tf-range applies to every volume opened
        m_histogram.histogram = sss::TransferFunctionEditor::histogramBars(volume, 128);
        m_histogram.rawRange = volume.transferFunctionRange();
        m_volume = std::move(volume);
        m_volumeLabel = label;
    }

    sss::MeshRenderOptions meshOptions() const {
        sss::MeshRenderOptions o = m_meshOptions;
        o.finishEachPass = m_honestTimings;
        return o;
    }

    sss::VolumeRenderOptions volumeOptions() const {
        sss::VolumeRenderOptions o = m_volumeOptions;
        if (m_volumeScattering)
            o.shading = m_volumeHighlights ? sss::VolumeShading::ScatteringGradient : sss::VolumeShading::Scattering;
        else
            o.shading = m_volumeBaselineGradient ? sss::VolumeShading::Gradient : sss::VolumeShading::EmissionAbsorption;
        o.finishEachPass = m_honestTimings;
        // The path tracer needs the physical model without highlights; elsewhere the box is inert.
        o.multipleScattering = m_volumeMultiple && o.shading == sss::VolumeShading::Scattering &&
                               o.model == sss::VolumeModel::Physical;
        return o;
    }

    bool pathTracing() const { return m_volume && volumeOptions().multipleScattering; }

    sss::Light light() const {
        // The light travels from the direction given by azimuth (around +y) and elevation.
        const float az = glm::radians(m_lightAzimuth), el = glm::radians(m_lightElevation);
        const glm::vec3 towardsLight(std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az));
        if (!m_spotLight) return sss::DirectionalLight{-towardsLight, m_lightColor, m_lightIntensity};
        // A spot from the same direction, two content radii out, aimed at the centre; its
        // intensity is scaled by the distance squared so the centre gets the same irradiance.
        const sss::Bounds content = m_compositor->bounds();
        const float distance = 2.0f * std::max(content.radius(), 0.5f);
        return sss::SpotLight{content.center() + distance * towardsLight, -towardsLight, m_spotCone, m_spotFalloff,
                              m_lightColor, m_lightIntensity * distance * distance};
    }

    // A scene file's placement, else side by side when both are there.
    sss::SceneTransform meshTransform() const {
        return m_meshTransform.value_or(sss::SceneTransform{.translate = glm::vec3(m_volume ? -0.6f : 0.0f, 0.0f, 0.0f)});
    }
    sss::SceneTransform volumeTransform() const {
        return m_volumeTransform.value_or(sss::SceneTransform{.translate = glm::vec3(m_mesh ? 0.6f : 0.0f, 0.0f, 0.0f)});
    }
    glm::mat4 meshModel() const { return meshTransform().matrix(); }
    glm::mat4 volumeModel() const { return volumeTransform().matrix(); }

    void rebuildScene() {
        m_compositor->clear();
        m_compositor->setOptions(m_hybrid);
        if (m_mesh) {
            sss::MeshScatteringRenderer& r = m_compositor->addMesh(*m_mesh, meshModel(), meshOptions());
            r.setScatteringMaterial(m_material);
            r.setMaterial(m_blinnPhong);
        }
        if (m_volume) {
            sss::VolumeScatteringRenderer& r = m_compositor->addVolume(*m_volume, volumeModel(), volumeOptions());
            r.setTransferFunction(m_tfEditor.transferFunction());
        }
        m_uploadedTf = m_tfEditor.transferFunction().revision();
        m_compositor->setLights({light()});
        m_mapFrames = 0;
    }

    void reframe() {
        const sss::Bounds content = m_compositor->bounds();
        if (content.empty()) return;
        // In a Cornell box, show the box (about its bounding sphere; the editor at the bottom takes room).
        const sss::Bounds bounds = m_hybrid.cornellBox ? sss::makeCornellBox(content).bounds : content;
        m_camera.setTarget(glm::vec3(0.0f));
        m_camera.frame(bounds);
        if (m_hybrid.cornellBox) m_camera.setDistance(m_camera.distance() * (tfWindowShown() ? 1.15f : 0.9f));
        m_camera.setClipPlanes(m_camera.distance() * 0.01f, m_camera.distance() * 10.0f);
        // Centre the content in the part of the window the UI leaves free (if there is room).
        if (m_showUi && m_target && static_cast<float>(m_target->width()) > 2.5f * kPanelWidth) {
            const float perPixel = 2.0f * std::tan(glm::radians(m_camera.fovY()) * 0.5f) /
                                   static_cast<float>(m_target->height());
            const float down = tfWindowShown() ? 0.5f * std::min(kTfWindowHeight, 0.5f * static_cast<float>(m_target->height())) : 0.0f;
            m_camera.pan(glm::vec2(-0.5f * panelWidth(), -down) * perPixel);
        }
    }

    // Pushes the UI's settings into the renderers; a bad value shows an error instead of throwing.
    void applyChanges() {
        m_viewChanged |= m_sceneDirty || m_windowDirty || m_meshDirty || m_volumeDirty || m_lightsDirty || m_hybridDirty ||
                         m_uploadedTf != m_tfEditor.transferFunction().revision();
        try {
            if (m_sceneDirty) {
                rebuildScene();
                reframe();
                m_sceneDirty = false;
                m_meshDirty = m_volumeDirty = m_lightsDirty = m_hybridDirty = m_windowDirty = false;
            }
            if (m_windowDirty) {  // the volume again, with its new window; the camera stays
                rebuildScene();
                m_windowDirty = false;
                m_meshDirty = m_volumeDirty = m_lightsDirty = m_hybridDirty = false;
            }
            if (m_hybridDirty) m_compositor->setOptions(m_hybrid);
            if (m_lightsDirty) m_compositor->setLights({light()});
            for (std::size_t i = 0; i < m_compositor->meshCount() && m_meshDirty; ++i) {
                m_compositor->mesh(i).setOptions(meshOptions());
                m_compositor->mesh(i).setScatteringMaterial(m_material);
                m_compositor->mesh(i).setMaterial(m_blinnPhong);
            }
            for (std::size_t i = 0; i < m_compositor->volumeCount(); ++i) {
                if (m_volumeDirty) m_compositor->volume(i).setOptions(volumeOptions());
                if (m_uploadedTf != m_tfEditor.transferFunction().revision())
                    m_compositor->volume(i).setTransferFunction(m_tfEditor.transferFunction());
            }
            if (m_meshDirty || m_lightsDirty || m_hybridDirty) m_mapFrames = 0;
        } catch (const sss::Error& e) {
            showMessage(e.what(), true);
        }
        m_uploadedTf = m_tfEditor.transferFunction().revision();
        m_meshDirty = m_volumeDirty = m_lightsDirty = m_hybridDirty = false;
    }

    // ---- frame -------------------------------------------------------------------------------
    void drawFrame(bool saveScreenshot) {
        const Clock::time_point start = Clock::now();
        m_context->pollEvents();
        const glm::ivec2 fb = m_context->framebufferSize();
        if (fb.x <= 0 || fb.y <= 0) {  // minimised: nothing to draw into
            glfwWaitEventsTimeout(0.1);
            return;
        }
        if (!m_target || m_target->width() != fb.x || m_target->height() != fb.y) m_target.emplace(fb.x, fb.y);
        if (m_frameIndex == 0) reframe();  // the panel offset needs the target's size

        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        m_layout = {};
        handleInput();
        if (m_showUi) {
            drawPanel();
            drawOverlay();
        }
        applyChanges();

        // The scene. While nothing moves and the maps have converged, each frame adds one more
        // sub-pixel-jittered frame to the anti-aliased mean (FrameAccumulator), up to --aa;
        // then the picture is final and the scene is not drawn again.
        const Clock::time_point renderStart = Clock::now();
        const glm::mat4 viewProjection = m_camera.projection(m_target->aspect()) * m_camera.view();
        if (!m_accumulator || m_accumulator->result().width() != fb.x || m_accumulator->result().height() != fb.y)
            m_accumulator.emplace(fb.x, fb.y);
        if (m_viewChanged || viewProjection != m_lastViewProjection || !m_mapsConverged) m_accumulator->reset();
        m_viewChanged = false;
        m_lastViewProjection = viewProjection;
        if (pathTracing()) {
            // The path tracer keeps its own running mean (through pixel centres: sub-pixel
            // offsets would restart it); the accumulator just holds its latest picture.
            if (m_accumulator->frames() == 0 || m_compositor->volume(0).accumulatedSamples() < kMaxViewerPaths) {
                try {
                    m_compositor->render(m_camera, *m_target);
                } catch (const sss::Error& e) {
                    showMessage(e.what(), true);
                    m_target->clear(m_hybrid.background);
                }
                m_accumulator->reset();
                m_accumulator->add(*m_target);
            }
        } else if (m_accumulator->frames() < m_args.antiAliasing) {
            try {
                m_camera.setSubpixelOffset(sss::FrameAccumulator::subpixelOffset(m_accumulator->frames(), fb.x, fb.y));
                m_compositor->render(m_camera, *m_target);
                m_camera.setSubpixelOffset({0.0f, 0.0f});
                m_accumulator->add(*m_target);
            } catch (const sss::Error& e) {
                // Bad settings must not end an interactive session; the message says what failed.
                m_camera.setSubpixelOffset({0.0f, 0.0f});
                showMessage(e.what(), true);
                m_target->clear(m_hybrid.background);
                m_accumulator->reset();
                m_accumulator->add(*m_target);
            }
        }
        if (m_honestTimings) sss::finishGpuWork();
        m_renderMs = msSince(renderStart);
        trackProgress();

        if (saveScreenshot && !m_args.screenshotUi) writeScreenshot(m_args.screenshot, false);
        if (m_screenshotRequested) writeScreenshot(m_screenshotPath, false);

        // The target holds linear radiance; the window shows its display image.
        if (!m_display) m_display.emplace();
        m_display->encode(m_accumulator->result(), m_displayTransform);
        m_gl->present(m_display->framebufferId(), fb.x, fb.y, fb.x, fb.y);
        ImGui::Render();
        m_uiVertices = ImGui::GetDrawData()->TotalVtxCount;
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        if (saveScreenshot && m_args.screenshotUi) writeScreenshot(m_args.screenshot, true);
        m_context->swapBuffers();

        // Mean over the last frames, so the display is readable but follows changes quickly.
        m_frameTimes[static_cast<std::size_t>(m_frameIndex) % m_frameTimes.size()] = msSince(start);
        ++m_frameIndex;
        const std::size_t n = std::min(m_frameTimes.size(), static_cast<std::size_t>(m_frameIndex));
        m_frameMs = 0.0;
        for (std::size_t i = 0; i < n; ++i) m_frameMs += m_frameTimes[i] / static_cast<double>(n);
        dumpState(true);
    }

    // --dump-state: the state after this frame (running) or at exit.
    void dumpState(bool running) {
        if (m_args.dumpState.empty()) return;
        viewer::ViewerState state;
        state.frame = m_frameIndex;
        state.running = running;
        state.window = m_context->framebufferSize();
        state.camera = m_camera;
        state.uiShown = m_showUi;
        state.uiVertices = m_uiVertices;
        state.panel = m_layout.panel;
        state.overlay = m_layout.overlay;
        state.tfWindow = m_layout.tfWindow;
        state.tfCanvas = m_layout.tfCanvas;
        state.editor = &m_tfEditor;
        state.screenshots = m_screenshotsWritten;
        const sss::DebugMessageCounts counts = m_context->debugMessages();
        state.glErrors = counts.errors;
        state.lastGlError = counts.errors > 0 ? m_context->lastDebugError() : std::string();
        viewer::writeViewerState(m_args.dumpState, state);
    }

    void writeScreenshot(const std::string& path, bool withUi) {
        m_screenshotRequested = false;
        try {
            if (withUi) {
                const glm::ivec2 fb = m_context->framebufferSize();
                m_gl->readBackBuffer(fb.x, fb.y).savePng(path);
            } else {
                sss::toDisplay(m_accumulator->result().readColor(), m_displayTransform).savePng(path);
            }
            std::printf("wrote %s\n", path.c_str());
            std::fflush(stdout);
            m_screenshotsWritten.push_back(path);
            showMessage("saved " + path, false);
        } catch (const sss::Error& e) {
            if (m_args.exitAfter > 0) throw;  // batch: a screenshot that cannot be written is a failure
            showMessage(e.what(), true);
        }
    }

    // Counts map frames while the scattering maps accumulate, and notes light-volume rebuilds.
    void trackProgress() {
        bool converged = true;
        for (std::size_t i = 0; i < m_compositor->meshCount(); ++i)
            converged = converged && m_compositor->mesh(i).converged();
        m_mapsConverged = converged || m_meshOptions.shading != sss::MeshShading::Scattering;
        m_mapFrames = m_mapsConverged ? 0 : m_mapFrames + 1;
        std::uint64_t runs = 0;
        double lastMs = 0.0;
        for (std::size_t i = 0; i < m_compositor->volumeCount(); ++i)
            if (const sss::PassStats* p = m_compositor->volume(i).stats().find("light-volume")) {
                runs += p->runs;
                lastMs = p->lastMs;
            }
        if (runs != m_lightVolumeRuns) {
            m_lightVolumeRuns = runs;
            m_lightVolumeBuiltFrame = m_frameIndex;
            m_lightVolumeMs = lastMs;
        }
    }

    void handleInput() {
        ImGuiIO& io = ImGui::GetIO();
        if (!io.WantCaptureKeyboard) {
            if (ImGui::IsKeyPressed(GLFW_KEY_F1, false)) m_showUi = !m_showUi;
            if (ImGui::IsKeyPressed(GLFW_KEY_F, false)) reframe();
        }
        if (ImGui::IsKeyPressed(GLFW_KEY_F12, false)) m_screenshotRequested = true;
        if (io.KeyCtrl && ImGui::IsKeyPressed(GLFW_KEY_Q, false))
            glfwSetWindowShouldClose(static_cast<GLFWwindow*>(m_context->nativeWindow()), GLFW_TRUE);
        if (io.WantCaptureMouse) return;
        const glm::vec2 delta(io.MouseDelta.x, io.MouseDelta.y);
        if (ImGui::IsMouseDragging(ImGuiMouseButton_Left, 0.0f)) m_camera.orbit(-0.3f * delta.x, 0.3f * delta.y);
        if (ImGui::IsMouseDragging(ImGuiMouseButton_Right, 0.0f) ||
            ImGui::IsMouseDragging(ImGuiMouseButton_Middle, 0.0f)) {
            // Scene points under the cursor follow it (at the target's depth).
            const float perPixel = 2.0f * std::tan(glm::radians(m_camera.fovY()) * 0.5f) /
                                   static_cast<float>(std::max(1, m_target->height()));
            m_camera.pan(glm::vec2(-delta.x, delta.y) * perPixel);
        }
        if (io.MouseWheel != 0.0f) m_camera.zoom(std::pow(0.88f, io.MouseWheel));
    }

    void showMessage(std::string text, bool error) {
        if (error && m_args.exitAfter > 0) std::fprintf(stderr, "sss-viewer: %s\n", text.c_str());
        m_message = std::move(text);
        m_messageIsError = error;
        m_messageTime = Clock::now();
    }

    // ---- UI ----------------------------------------------------------------------------------
    static constexpr float kPanelWidth = 390.0f;
    // Narrow windows get a narrower panel, so some of the scene stays visible.
    float panelWidth() const {
        const float width = m_target ? static_cast<float>(m_target->width()) : 1280.0f;
        return std::min(kPanelWidth, std::max(260.0f, 0.45f * width));
    }

    void drawPanel() {
        const ImGuiViewport* vp = ImGui::GetMainViewport();
        ImGui::SetNextWindowPos(vp->WorkPos, ImGuiCond_Always);
        ImGui::SetNextWindowSize(ImVec2(panelWidth(), vp->WorkSize.y), ImGuiCond_Always);
        ImGui::SetNextWindowBgAlpha(0.88f);
        ImGui::Begin("libsss viewer", nullptr,
                     ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
        m_layout.panel = currentWindowRect();
        ImGui::PushItemWidth(-0.38f * panelWidth());
        if (ImGui::CollapsingHeader("Scene", ImGuiTreeNodeFlags_DefaultOpen)) sceneSection();
        if (ImGui::CollapsingHeader("Light and camera", ImGuiTreeNodeFlags_DefaultOpen)) lightSection();
        if (m_mesh && ImGui::CollapsingHeader("Mesh: subsurface scattering", ImGuiTreeNodeFlags_DefaultOpen))
            meshSection();
        if (m_volume && ImGui::CollapsingHeader("Volume: light-volume scattering", ImGuiTreeNodeFlags_DefaultOpen))
            volumeSection();
        if (ImGui::CollapsingHeader("Timings")) timingSection();
        ImGui::PopItemWidth();
        ImGui::End();
        if (m_volume) drawTransferFunctionWindow();
    }

    static constexpr float kTfWindowHeight = 250.0f;
    bool tfWindowShown() const { return m_showUi && m_volume.has_value(); }

    // The editor gets a wide window along the bottom, right of the panel.
    void drawTransferFunctionWindow() {
        const ImGuiViewport* vp = ImGui::GetMainViewport();
        const float left = vp->WorkPos.x + panelWidth() + 8.0f;
        const float width = std::max(200.0f, vp->WorkPos.x + vp->WorkSize.x - 8.0f - left);
        const float height = std::min(kTfWindowHeight, 0.5f * vp->WorkSize.y);
        ImGui::SetNextWindowPos(ImVec2(left, vp->WorkPos.y + vp->WorkSize.y - height - 8.0f), ImGuiCond_Always);
        ImGui::SetNextWindowSize(ImVec2(width, height), ImGuiCond_Always);
        ImGui::SetNextWindowBgAlpha(0.85f);
        ImGui::Begin("Transfer function", nullptr,
                     ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
        m_layout.tfWindow = currentWindowRect();
        transferFunctionSection(height);
        ImGui::End();
    }

    void sceneSection() {
        ImGui::InputText("mesh (.obj)", &m_meshPath);
        if (ImGui::Button("Open mesh")) openMesh();
        ImGui::SameLine();
        ImGui::BeginDisabled(!m_mesh);
        if (ImGui::Button("Remove mesh")) {
            m_mesh.reset();
            m_sceneDirty = true;
        }
        ImGui::EndDisabled();
        ImGui::InputText("volume", &m_volumePath);
        ImGui::InputInt3("dims (0: name)", &m_volumeDims.x);
        ImGui::Checkbox("16-bit voxels", &m_volume16);
        if (ImGui::Button("Open volume")) openVolume();
        ImGui::SameLine();
        ImGui::BeginDisabled(!m_volume);
        if (ImGui::Button("Remove volume")) {
            m_volume.reset();
            m_sceneDirty = true;
        }
        ImGui::EndDisabled();
        ImGui::TextDisabled("procedural: sphere torus slab | blobs shell bucky");
        m_hybridDirty |= ImGui::Checkbox("Cornell box", &m_hybrid.cornellBox);
        ImGui::SameLine();
        if (ImGui::Button("Reframe (F)")) reframe();
        m_hybridDirty |= ImGui::Checkbox("meshes shadow volumes", &m_hybrid.meshShadowsInVolumes);
        m_hybridDirty |= ImGui::Checkbox("meshes shadow meshes", &m_hybrid.meshShadowsOnMeshes);
        m_hybridDirty |= ImGui::Checkbox("volumes shadow meshes", &m_hybrid.volumeShadowsOnMeshes);
        float background[3] = {m_hybrid.background.r, m_hybrid.background.g, m_hybrid.background.b};
        if (ImGui::ColorEdit3("background", background)) {
            m_hybrid.background = glm::vec4(background[0], background[1], background[2], 1.0f);
            m_hybridDirty = true;
        }
        ImGui::InputText("screenshot", &m_screenshotPath);
        ImGui::SameLine();
        if (ImGui::Button("Save (F12)")) m_screenshotRequested = true;
        ImGui::InputText("scene file", &m_scenePath);
        ImGui::SameLine();
        if (ImGui::Button("Save scene")) saveScene(m_scenePath);
    }

    void openMesh() {
        try {
            m_mesh = normalised(viewer::loadSceneMesh(m_meshPath, m_dataDir));
            m_meshSize = 1.0f;
            m_meshTransform.reset();
            m_volumeTransform.reset();
            m_sceneDirty = true;
            showMessage("opened " + m_meshPath, false);
        } catch (const std::exception& e) {  // sss::Error or UsageError: shown, never fatal
            showMessage(e.what(), true);
        }
    }

    void openVolume() {
        try {
            sss::RawLoadOptions overrides;
            if (m_volumeDims.x > 0 && m_volumeDims.y > 0 && m_volumeDims.z > 0) overrides.dims = m_volumeDims;
            if (m_volume16) overrides.type = sss::VoxelType::UInt16;
            setVolume(viewer::loadSceneVolume(m_volumePath, m_dataDir, overrides), m_volumePath);
            m_volumeRaw = overrides;
            m_meshTransform.reset();
            m_volumeTransform.reset();
            m_sceneDirty = true;
            showMessage("opened " + m_volumePath, false);
        } catch (const std::exception& e) {
            showMessage(e.what(), true);
        }
    }

    void lightSection() {
        m_lightsDirty |= ImGui::SliderFloat("light azimuth", &m_lightAzimuth, -180.0f, 180.0f, "%.0f deg");
        m_lightsDirty |= ImGui::SliderFloat("light elevation", &m_lightElevation, -89.0f, 89.0f, "%.0f deg");
        m_lightsDirty |= colorEdit("light colour", m_lightColor);
        m_lightsDirty |= ImGui::SliderFloat("light intensity", &m_lightIntensity, 0.0f, 4.0f, "%.2f");
        m_lightsDirty |= ImGui::Checkbox("spot light", &m_spotLight);
        if (m_spotLight) {
            m_lightsDirty |= ImGui::SliderFloat("cone half-angle", &m_spotCone, 1.0f, 90.0f, "%.0f deg");
            m_lightsDirty |= ImGui::SliderFloat("cone falloff", &m_spotFalloff, 0.0f, 1.0f, "%.2f");
        }
        ImGui::SliderFloat("exposure (stops)", &m_displayTransform.exposure, -8.0f, 8.0f, "%.1f");
        int toneMap = m_displayTransform.toneMap == sss::ToneMap::Filmic ? 1 : 0;
        if (ImGui::Combo("tone mapping", &toneMap, "none (clip)\0filmic\0"))
            m_displayTransform.toneMap = toneMap == 1 ? sss::ToneMap::Filmic : sss::ToneMap::None;
        ImGui::TextDisabled("left drag: orbit, right/middle: pan, wheel: zoom");
    }

    void meshSection() {
        bool scattering = m_meshOptions.shading == sss::MeshShading::Scattering;
        if (ImGui::Checkbox("scattering (off: Blinn-Phong)", &scattering)) {
            m_meshOptions.shading = scattering ? sss::MeshShading::Scattering : sss::MeshShading::BlinnPhong;
            m_meshDirty = true;
        }
        if (!scattering) {
            m_meshDirty |= colorEdit("diffuse", m_blinnPhong.diffuse);
            m_meshDirty |= ImGui::SliderFloat("shininess", &m_blinnPhong.shininess, 1.0f, 200.0f, "%.0f");
            return;
        }
        bool calibrated = m_meshOptions.profile == sss::ScatteringProfile::Calibrated;
        if (ImGui::Checkbox("calibrated profile", &calibrated)) {
            m_meshOptions.profile = calibrated ? sss::ScatteringProfile::Calibrated : sss::ScatteringProfile::Dipole;
            m_meshDirty = true;
        }
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("on: the dipole rescaled to a random walk, plus single scattering\noff: the paper's directional dipole");
        // Where the combine pass reads the radiosity (the CLI's --combine names).
        const std::string combineName(sss::enumName(m_meshOptions.combine));
        if (ImGui::BeginCombo("combine", combineName.c_str())) {
            for (const auto& [value, name] : sss::enumNames<sss::MeshCombine>()) {
                if (ImGui::Selectable(std::string(name).c_str(), value == m_meshOptions.combine)) {
                    m_meshOptions.combine = value;
                    m_meshDirty = true;
                }
            }
            ImGui::EndCombo();
        }
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("auto: vertex-estimate on fine meshes, per-pixel on coarse ones\n"
                              "per-pixel: the K maps at every pixel (the paper's)\nper-vertex: the maps resolved per vertex\n"
                              "vertex-estimate: no maps, the radiosity estimated at each vertex (fine meshes)");
        const std::vector<std::string> names = sss::materialPresetNames();
        const char* current = m_materialIndex >= 0 ? names[static_cast<std::size_t>(m_materialIndex)].c_str()
                                                    : "(custom)";
        if (ImGui::BeginCombo("material", current)) {
            for (std::size_t i = 0; i < names.size(); ++i) {
                if (ImGui::Selectable(names[i].c_str(), static_cast<int>(i) == m_materialIndex)) {
                    m_materialIndex = static_cast<int>(i);
                    m_material = sss::materialPreset(names[i]);
                    m_meshDirty = true;
                }
            }
            ImGui::EndCombo();
        }
        sss::ScatteringMaterial edited = m_material;
        bool changed = dragDvec3("sigma_a (1/mm)", edited.sigmaA, 0.001f, 0.0f, 100.0f, "%.4f");
        changed |= dragDvec3("sigma_s (1/mm)", edited.sigmaS, 0.01f, 0.0f, 1000.0f, "%.3f");
        float eta = static_cast<float>(edited.eta);
        if (ImGui::SliderFloat("eta", &eta, 1.0f, 2.0f, "%.3f")) {
            edited.eta = eta;
            changed = true;
        }
        if (changed) {
            try {
                edited.validate();
                edited.name = "custom";
                m_material = edited;
                m_materialIndex = -1;
                m_meshDirty = true;
            } catch (const sss::Error& e) {
                showMessage(e.what(), true);
            }
        }
        float scale = static_cast<float>(m_meshOptions.millimetresPerUnit);
        if (ImGui::DragFloat("scale (mm/unit)", &scale, 0.5f, 1.0f, 5000.0f, "%.1f",
                             ImGuiSliderFlags_Logarithmic)) {
            m_meshOptions.millimetresPerUnit = std::max(1.0f, scale);
            m_meshDirty = true;
        }
        m_meshDirty |= ImGui::SliderInt("K (map cameras)", &m_meshOptions.cameras, 1, 32);
        m_meshDirty |= ImGui::SliderInt("N (samples)", &m_meshOptions.samples, 1, 256);
        if (comboInt("map resolution", m_meshOptions.mapResolution, kMapResolutions.data(), kMapResolutions.size())) {
            m_meshOptions.lightMapResolution = m_meshOptions.mapResolution;
            m_meshDirty = true;
        }
        m_meshDirty |= ImGui::SliderInt("frames accumulated", &m_meshOptions.accumulationFrames, 1, 64);
        m_meshDirty |= ImGui::SliderFloat("specular", &m_meshOptions.specular, 0.0f, 2.0f, "%.2f");
        m_meshDirty |= ImGui::SliderFloat("environment", &m_meshOptions.environment.x, 0.0f, 0.5f, "%.3f");
        m_meshOptions.environment = glm::vec3(m_meshOptions.environment.x);  // grey: one slider
        if (m_mapsConverged) {
            ImGui::TextColored(ImVec4(0.5f, 0.9f, 0.5f, 1.0f), "scattering maps converged");
        } else {
            const float done = std::min(1.0f, static_cast<float>(m_mapFrames) /
                                                  static_cast<float>(m_meshOptions.accumulationFrames));
            const std::string text = "accumulating maps: frame " + std::to_string(m_mapFrames) + " / " +
                                     std::to_string(m_meshOptions.accumulationFrames);
            ImGui::ProgressBar(done, ImVec2(-1.0f, 0.0f), text.c_str());
        }
    }

    void volumeSection() {
        const auto dims = m_volume->dims();
        ImGui::Text("%s: %dx%dx%d %s", m_volumeLabel.c_str(), dims.x, dims.y, dims.z,
                    sss::voxelTypeName(m_volume->type()));
        m_volumeDirty |= ImGui::Checkbox("scattering", &m_volumeScattering);
        ImGui::SameLine();
        if (m_volumeScattering) {
            m_volumeDirty |= ImGui::Checkbox("+ gradient highlights", &m_volumeHighlights);
        } else {
            int baseline = m_volumeBaselineGradient ? 0 : 1;
            ImGui::SetNextItemWidth(150.0f);
            if (ImGui::Combo("##off", &baseline, "gradient (Phong)\0emission-absorption\0")) {
                m_volumeBaselineGradient = baseline == 0;
                m_volumeDirty = true;
            }
        }
        m_volumeDirty |= ImGui::SliderFloat("ray step (voxels)", &m_volumeOptions.stepSize, 0.25f, 4.0f, "%.2f");
        m_volumeDirty |= ImGui::Checkbox("pre-integrated classification", &m_volumeOptions.preintegration);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("on: each sample integrates the transfer function over the segment since the previous "
                              "one (thin structures between samples show)\noff: the transfer function at the sample "
                              "alone (the thesis)");
        if (m_volumeScattering) {
            m_volumeDirty |= ImGui::SliderFloat("light-volume scale", &m_volumeOptions.lightVolumeScale, 0.1f, 1.0f,
                                                "%.2f");
            // LightVolumeFallback::Reduce lowered it: the asked-for light volume does not fit the GPU.
            const float inUse = m_compositor->volume(0).lightVolumeScaleInUse();
            if (inUse > 0.0f && inUse < m_volumeOptions.lightVolumeScale)
                ImGui::TextColored(ImVec4(1.0f, 0.7f, 0.3f, 1.0f), "does not fit the GPU: using %.3g", inUse);
            m_volumeDirty |= ImGui::SliderFloat("anisotropy g", &m_volumeOptions.anisotropy, -0.9f, 0.9f, "%.2f");
            bool physical = m_volumeOptions.model == sss::VolumeModel::Physical;
            if (ImGui::Checkbox("physical single scattering", &physical)) {
                m_volumeOptions.model = physical ? sss::VolumeModel::Physical : sss::VolumeModel::Paper;
                m_volumeDirty = true;
            }
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip("on: TF colour as albedo x phase function x light (about 4 pi dimmer)\noff: the paper's ambient + diffuse x light-volume colour");
            if (physical && !m_volumeHighlights) {
                m_volumeDirty |= ImGui::Checkbox("multiple scattering (path traced)", &m_volumeMultiple);
                if (ImGui::IsItemHovered())
                    ImGui::SetTooltip("all orders of scattering, path traced on the GPU: one path per pixel and\n"
                                      "frame, accumulated while the camera and the scene stay still");
                if (m_volumeMultiple)
                    ImGui::Text("paths per pixel: %d", m_compositor->volume(0).accumulatedSamples());
            }
        }
        m_volumeDirty |= ImGui::SliderFloat("ambient", &m_volumeOptions.ambient, 0.0f, 1.0f, "%.2f");
        m_volumeDirty |= ImGui::SliderFloat("diffuse", &m_volumeOptions.diffuse, 0.0f, 2.0f, "%.2f");
        if (m_volumeScattering) {
            const bool recent = m_frameIndex - m_lightVolumeBuiltFrame < 3 && m_lightVolumeRuns > 0;
            if (recent)
                ImGui::TextColored(ImVec4(1.0f, 0.75f, 0.3f, 1.0f), "light volume rebuilt (%.1f ms)", m_lightVolumeMs);
            else
                ImGui::TextColored(ImVec4(0.5f, 0.9f, 0.5f, 1.0f), "light volume up to date");
        }
    }

    void transferFunctionSection(float windowHeight) {
        const std::vector<std::string> presets = sss::TransferFunction::presetNames();
        ImGui::SetNextItemWidth(130.0f);
        if (ImGui::BeginCombo("preset", m_tfPreset.empty() ? "(edited)" : m_tfPreset.c_str())) {
            for (const std::string& name : presets)
                if (ImGui::Selectable(name.c_str(), name == m_tfPreset)) {
                    m_tfEditor.setTransferFunction(sss::TransferFunction::preset(name));
                    m_tfPreset = name;
                }
            ImGui::EndCombo();
        }
        ImGui::SameLine();
        ImGui::SetNextItemWidth(std::max(80.0f, ImGui::GetContentRegionAvail().x - 290.0f));
        ImGui::InputText("##json", &m_tfPath);
        ImGui::SameLine();
        if (ImGui::Button("Save JSON")) {
            try {
                m_tfEditor.transferFunction().saveParaViewJson(m_tfPath, "sss-viewer");
                showMessage("saved " + m_tfPath, false);
            } catch (const sss::Error& e) {
                showMessage(e.what(), true);
            }
        }
        ImGui::SameLine();
        if (ImGui::Button("Load JSON")) {
            try {
                m_tfEditor.setTransferFunction(sss::TransferFunction::loadParaViewJson(m_tfPath));
                m_tfPreset.clear();
                showMessage("loaded " + m_tfPath, false);
            } catch (const sss::Error& e) {
                showMessage(e.what(), true);
            }
        }
        ImGui::SameLine();
        ImGui::TextDisabled("(ParaView)");
        valueWindowRow();
        const uint64_t before = m_tfEditor.transferFunction().revision();
        // The canvas takes what is left above the point controls (two rows).
        const float canvasHeight = std::max(60.0f, windowHeight - 5.0f * ImGui::GetFrameHeightWithSpacing() - 20.0f);
        viewer::ScreenRect canvas;
        viewer::transferFunctionEditorWidget(m_tfEditor, m_histogram, canvasHeight, &canvas);
        m_layout.tfCanvas = canvas;
        if (m_tfEditor.transferFunction().revision() != before) m_tfPreset.clear();
    }

    // Window/level of the value window (Volume::setValueWindow, in data units): the TF's domain is
    // level -+ window / 2. Applied when a drag ends, since the volume is uploaded again.
    void valueWindowRow() {
        if (!m_volume) {
            ImGui::TextDisabled("window/level: open a volume");
            return;
        }
        const auto [lo, hi] = m_volume->transferFunctionRange();
        float level = static_cast<float>(0.5 * (lo + hi)), window = static_cast<float>(hi - lo);
        const float speed = std::max(window * 0.002f, 1e-6f);
        bool done = false;
        ImGui::SetNextItemWidth(140.0f);
        ImGui::DragFloat("level", &level, speed, 0.0f, 0.0f, "%.4g");
        done |= ImGui::IsItemDeactivatedAfterEdit();
        const float levelEdited = level;
        ImGui::SameLine();
        ImGui::SetNextItemWidth(140.0f);
        ImGui::DragFloat("window", &window, speed, 0.0f, 0.0f, "%.4g");
        done |= ImGui::IsItemDeactivatedAfterEdit();
        ImGui::SameLine();
        const bool reset = ImGui::Button("data range");
        if (!done && !reset) return;
        try {
            m_volume->setValueWindow(reset ? std::nullopt
                                           : std::optional(std::pair<double, double>(levelEdited - 0.5 * window,
                                                                                     levelEdited + 0.5 * window)));
            m_histogram.histogram = sss::TransferFunctionEditor::histogramBars(*m_volume, 128);
            m_histogram.rawRange = m_volume->transferFunctionRange();
            m_windowDirty = true;
        } catch (const sss::Error& e) {  // a window of width <= 0
            showMessage(e.what(), true);
        }
    }

    // Where the window being built lies (window pixels).
    static viewer::ScreenRect currentWindowRect() {
        const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
        return {pos.x, pos.y, pos.x + size.x, pos.y + size.y};
    }

    void statsTable(const char* owner, const sss::RenderStats& stats) {
        for (const auto& [name, pass] : stats.passes()) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::Text("%s %s", owner, name.c_str());
            ImGui::TableNextColumn();
            ImGui::Text("%.2f", pass.lastMs);
            ImGui::TableNextColumn();
            ImGui::Text("%llu", static_cast<unsigned long long>(pass.runs));
        }
    }

    void timingSection() {
        if (ImGui::Checkbox("wait for the GPU after each pass", &m_honestTimings)) m_meshDirty = m_volumeDirty = true;
        ImGui::TextDisabled(m_honestTimings ? "times below are GPU times"
                                            : "times below are CPU submission times");
        if (ImGui::BeginTable("passes", 3, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp)) {
            ImGui::TableSetupColumn("pass");
            ImGui::TableSetupColumn("last ms");
            ImGui::TableSetupColumn("runs");
            ImGui::TableHeadersRow();
            statsTable("hybrid", m_compositor->stats());
            for (std::size_t i = 0; i < m_compositor->meshCount(); ++i) statsTable("mesh", m_compositor->mesh(i).stats());
            for (std::size_t i = 0; i < m_compositor->volumeCount(); ++i)
                statsTable("volume", m_compositor->volume(i).stats());
            ImGui::EndTable();
        }
    }

    // Frame time, progress and messages, top right.
    void drawOverlay() {
        const ImGuiViewport* vp = ImGui::GetMainViewport();
        ImGui::SetNextWindowPos(ImVec2(vp->WorkPos.x + vp->WorkSize.x - 10.0f, vp->WorkPos.y + 10.0f),
                                ImGuiCond_Always, ImVec2(1.0f, 0.0f));
        ImGui::SetNextWindowBgAlpha(0.6f);
        ImGui::Begin("##overlay", nullptr,
                     ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove |
                         ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                         ImGuiWindowFlags_NoNav);
        m_layout.overlay = currentWindowRect();
        ImGui::Text("frame %.1f ms (%.1f fps), scene %s %.1f ms", m_frameMs,
                    m_frameMs > 0 ? 1000.0 / m_frameMs : 0.0, m_honestTimings ? "(GPU)" : "submit", m_renderMs);
        ImGui::Text("%dx%d, %s", m_target ? m_target->width() : 0, m_target ? m_target->height() : 0,
                    m_context->info().renderer.c_str());
        if (!m_mapsConverged)
            ImGui::TextColored(ImVec4(1.0f, 0.75f, 0.3f, 1.0f), "accumulating scattering maps %d / %d", m_mapFrames,
                               m_meshOptions.accumulationFrames);
        if (m_volume && m_volumeScattering && m_frameIndex - m_lightVolumeBuiltFrame < 3 && m_lightVolumeRuns > 0)
            ImGui::TextColored(ImVec4(1.0f, 0.75f, 0.3f, 1.0f), "light volume rebuilt (%.1f ms)", m_lightVolumeMs);
        if (!m_message.empty() && msSince(m_messageTime) < 8000.0)
            ImGui::TextColored(m_messageIsError ? ImVec4(1.0f, 0.45f, 0.4f, 1.0f) : ImVec4(0.6f, 0.9f, 0.6f, 1.0f),
                               "%s", m_message.c_str());
        ImGui::End();
    }

    // ---- state -------------------------------------------------------------------------------
    ViewerOptions m_args;
    fs::path m_dataDir;
    std::unique_ptr<sss::GlfwContext> m_context;
    std::optional<viewer::PresentGl> m_gl;
    std::optional<sss::HybridCompositor> m_compositor;
    std::optional<sss::RenderTarget> m_target;  // linear radiance
    std::optional<sss::DisplayEncoder> m_display;  // its display image, presented in the window
    std::optional<sss::FrameAccumulator> m_accumulator;  // the anti-aliased mean of m_target's frames
    glm::mat4 m_lastViewProjection{0.0f};
    bool m_viewChanged = true;
    sss::DisplayTransform m_displayTransform;
    sss::Camera m_camera;

    std::optional<sss::Mesh> m_mesh;
    std::optional<sss::Volume> m_volume;
    std::string m_volumeLabel;
    viewer::TfEditorWidgetState m_histogram;

    sss::HybridOptions m_hybrid;
    sss::MeshRenderOptions m_meshOptions;
    sss::BlinnPhongMaterial m_blinnPhong;
    sss::ScatteringMaterial m_material;
    int m_materialIndex = -1;
    sss::VolumeRenderOptions m_volumeOptions;
    bool m_volumeScattering = true, m_volumeHighlights = false, m_volumeBaselineGradient = true;
    bool m_volumeMultiple = false;  // the path tracer, where the options allow it (volumeOptions)
    float m_lightAzimuth = 35.0f, m_lightElevation = 40.0f, m_lightIntensity = 1.0f;
    glm::vec3 m_lightColor{1.0f};
    bool m_spotLight = false;  // the light panel's spot: same direction, placed outside the content
    float m_spotCone = 20.0f, m_spotFalloff = 0.3f;
    sss::TransferFunctionEditor m_tfEditor;
    std::uint64_t m_uploadedTf = 0;
    std::string m_tfPreset, m_tfPath = "transfer-function.json";

    bool m_sceneDirty = false, m_meshDirty = false, m_volumeDirty = false, m_lightsDirty = false,
         m_hybridDirty = false, m_windowDirty = false;
    bool m_showUi = true, m_honestTimings = false, m_screenshotRequested = false;
    std::string m_meshPath, m_volumePath, m_screenshotPath = "sss-viewer.png", m_scenePath = "scene.json";
    sss::RawLoadOptions m_volumeRaw;  // how the volume was opened, for saved scenes
    std::optional<sss::SceneTransform> m_meshTransform, m_volumeTransform;  // from a scene file
    std::optional<float> m_meshSize = 1.0f;  // normalised(), unless a scene file said otherwise
    glm::ivec3 m_volumeDims{0};
    bool m_volume16 = false;

    int m_frameIndex = 0, m_mapFrames = 0, m_lightVolumeBuiltFrame = -100;
    bool m_mapsConverged = true;
    std::uint64_t m_lightVolumeRuns = 0;
    std::array<double, 16> m_frameTimes{};
    double m_frameMs = 0.0, m_renderMs = 0.0, m_lightVolumeMs = 0.0;
    std::string m_message;
    bool m_messageIsError = false;
    Clock::time_point m_messageTime;

    // For --dump-state: where this frame's UI went, and what F12 / Save wrote.
    struct UiLayout {
        std::optional<viewer::ScreenRect> panel, overlay, tfWindow, tfCanvas;
    };
    UiLayout m_layout;
    int m_uiVertices = 0;
    std::vector<std::string> m_screenshotsWritten;
};

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
    if (scene) viewer.setSceneOptions(*scene);
    viewer.setInitialScene(std::move(mesh), std::move(volume), std::move(*tf), tfName);
    return viewer.run();
}

}  // namespace

int main(int argc, char** argv) {
    return examples::runReportingErrors("sss-viewer", [&] { return run(viewer::parseArgs(argc, argv)); });
}
