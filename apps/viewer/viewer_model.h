#pragma once
// What sss-viewer shows and how: the scene's inputs and settings as the panels edit them, the
// compositor that draws them, and what the frames measured. The Viewer (sss_viewer.cpp) drives
// it frame by frame; Panels (viewer_panels.h) edits its fields and sets the *Dirty flags, which
// applyChanges() turns into renderer calls.
#include "tf_editor_widget.h"
#include "viewer_options.h"

#include <sss/camera.h>
#include <sss/display.h>
#include <sss/hybrid_compositor.h>
#include <sss/light.h>
#include <sss/materials.h>
#include <sss/render_target.h>
#include <sss/scene.h>
#include <sss/transfer_function_editor.h>

#include <glm/mat4x4.hpp>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace viewer {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point start);

constexpr float kPanelWidth = 390.0f;      // the settings panel, left (narrower in narrow windows)
constexpr float kTfWindowHeight = 250.0f;  // the transfer-function editor, along the bottom

class ViewerModel {
public:
    explicit ViewerModel(const ViewerOptions& options);

    /// Shows what the command line named (loaded before the window opened, see run()).
    void setInitialScene(std::optional<sss::Mesh> initialMesh, std::optional<sss::Volume> initialVolume,
                         sss::TransferFunction tf, const std::string& tfName);
    /// Opens a scene file's content: its mesh and volume with their placement, options and
    /// materials, its light and camera (run() checked that the viewer can show all of it).
    void setSceneOptions(const sss::SceneDescription& scene);
    /// The scene shown, as a scene description (mesh and volume as opened, normalised to one
    /// unit, placed as shown; the transfer function inline; the camera where it is).
    sss::SceneDescription describeScene() const;
    void saveScene(const std::string& path);
    void setVolumeShading(sss::VolumeShading shading);
    void setVolume(sss::Volume opened, const std::string& label);
    void openMesh();
    void openVolume();
    sss::MeshRenderOptions renderedMeshOptions() const;
    sss::VolumeRenderOptions renderedVolumeOptions() const;
    bool pathTracing() const;
    /// The next frame draws the volume better: its light volume is a preview, or its
    /// multiple-scattering cache is on and still taking photons (each frame adds some).
    bool volumeRefining();
    sss::Light light() const;
    // A scene file's placement, else side by side when both are there.
    sss::SceneTransform placedMeshTransform() const;
    sss::SceneTransform placedVolumeTransform() const;
    glm::mat4 meshModel() const;
    glm::mat4 volumeModel() const;
    void rebuildScene();
    // The translucent (textured when the mesh has a base colour and meshTexture) and Blinn-Phong materials.
    void applyMaterials(sss::MeshScatteringRenderer& r) const;
    void reframe();
    // Pushes the UI's settings into the renderers; a bad value shows an error instead of throwing.
    void applyChanges();
    // Counts map frames while the scattering maps accumulate, and notes light-volume rebuilds.
    void trackProgress();
    void showMessage(std::string text, bool error);
    // Narrow windows get a narrower panel, so some of the scene stays visible.
    float panelWidth() const;
    bool tfWindowShown() const;

    // ---- the scene ---------------------------------------------------------------------------
    ViewerOptions args;
    std::filesystem::path dataDir;
    std::optional<sss::HybridCompositor> compositor;
    std::optional<sss::RenderTarget> target;  // linear radiance
    sss::Camera camera;
    sss::DisplayTransform displayTransform;
    std::string renderer;  // the GL renderer's name, for the overlay

    std::optional<sss::Mesh> mesh;
    std::optional<sss::Volume> volume;
    std::string volumeLabel;
    TfEditorWidgetState histogram;

    sss::HybridOptions hybrid;
    sss::MeshRenderOptions meshOptions;
    sss::BlinnPhongMaterial blinnPhong;
    sss::ScatteringMaterial material;
    bool meshTexture = true;  // a mesh's base colour gives the reflectance (--no-texture, checkbox)
    int materialIndex = -1;
    sss::VolumeRenderOptions volumeOptions;
    bool volumeScattering = true, volumeHighlights = false, volumeBaselineGradient = true;
    bool volumeMultiple = false;  // the path tracer, where the options allow it (renderedVolumeOptions)
    sss::VolumeClip volumeClip;   // changed with volumeDirty
    float lightAzimuth = 35.0f, lightElevation = 40.0f, lightIntensity = 1.0f;
    glm::vec3 lightColor{1.0f};
    bool spotLight = false;  // the light panel's spot: same direction, placed outside the content
    float spotCone = 20.0f, spotFalloff = 0.3f;
    sss::TransferFunctionEditor tfEditor;
    std::uint64_t uploadedTf = 0;
    std::string tfPreset, tfPath = "transfer-function.json";

    // ---- what the UI asked for ---------------------------------------------------------------
    bool sceneDirty = false, meshDirty = false, volumeDirty = false, lightsDirty = false, hybridDirty = false,
         windowDirty = false, viewChanged = true;
    bool showUi = true, honestTimings = false, screenshotRequested = false;
    std::string meshPath, volumePath, screenshotPath = "sss-viewer.png", scenePath = "scene.json";
    sss::RawLoadOptions volumeRaw;  // how the volume was opened, for saved scenes
    std::optional<sss::SceneTransform> meshTransform, volumeTransform;  // from a scene file
    std::optional<float> meshSize = 1.0f;  // normalised(), unless a scene file said otherwise
    glm::ivec3 volumeDims{0};
    bool volume16 = false;

    // ---- what the frames measured ------------------------------------------------------------
    int frameIndex = 0, mapFrames = 0, lightVolumeBuiltFrame = -100;
    bool mapsConverged = true;
    std::uint64_t lightVolumeRuns = 0;
    double frameMs = 0.0, renderMs = 0.0, lightVolumeMs = 0.0;
    std::string message;
    bool messageIsError = false;
    Clock::time_point messageTime;
};

}  // namespace viewer
