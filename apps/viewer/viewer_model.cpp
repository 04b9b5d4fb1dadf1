#include "viewer_model.h"

#include <sss/error.h>
#include <sss/procedural.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace viewer {
namespace {

// Meshes are scaled to a largest side of 1 and centred, like Volume::worldBounds(), so any two
// inputs fit side by side; --scale then says how many millimetres that unit is.
sss::Mesh normalised(const sss::Mesh& mesh) {
    const sss::Bounds b = mesh.bounds();
    const glm::vec3 size = b.size();
    const float largest = std::max({size.x, size.y, size.z, 1e-12f});
    return mesh.transformed(glm::scale(glm::mat4(1.0f), glm::vec3(1.0f / largest)) *
                            glm::translate(glm::mat4(1.0f), -b.center()));
}

}  // namespace

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

ViewerModel::ViewerModel(const ViewerOptions& options)
    : args(options), dataDir(dataDirectory(options.input.dataDir)) {
    compositor.emplace(hybrid);
    meshPath = options.input.mesh;
    volumePath = options.input.volume;
    volumeRaw = options.input.raw;
    showUi = !options.hideUi;
    meshOptions = options.mesh;
    // Ambient light for the faces the light misses, as sss-render does: on in a Cornell box.
    if (options.cornellBox && meshOptions.environment == glm::vec3(0.0f)) meshOptions.environment = glm::vec3(0.05f);
    volumeOptions = options.volume;
    setVolumeShading(options.volume.shading);
    volumeMultiple = options.volume.multipleScattering;
    displayTransform = options.display;
    hybrid.cornellBox = options.cornellBox;
    lightAzimuth = options.lightAzimuth;
    lightElevation = options.lightElevation;
    lightColor = options.lightColor;
    lightIntensity = options.lightIntensity;
    material = sss::materialPreset(options.material);
    meshTexture = !options.noTexture;
    const auto names = sss::materialPresetNames();
    const auto found = std::find(names.begin(), names.end(), material.name);
    materialIndex = found == names.end() ? -1 : static_cast<int>(found - names.begin());
}

/// Shows what the command line named (loaded before the window opened, see run()).
void ViewerModel::setInitialScene(std::optional<sss::Mesh> initialMesh, std::optional<sss::Volume> initialVolume,
                                  sss::TransferFunction tf, const std::string& tfName) {
    if (initialMesh) mesh = meshTransform ? *initialMesh : normalised(*initialMesh);  // a scene's mesh is sized by the scene
    // From a scene file the volume's source is the scene's (applyScene), not a command-line path.
    if (initialVolume) setVolume(std::move(*initialVolume), args.input.volume.empty() ? volumePath : args.input.volume);
    tfEditor = sss::TransferFunctionEditor(std::move(tf));
    if (tfName.size() > 5 && tfName.substr(tfName.size() - 5) == ".json") tfPath = tfName;
    else tfPreset = tfName;
    rebuildScene();
    reframe();
    const sss::SceneCamera& c = args.camera;
    camera.setYaw(args.yawGiven || !hybrid.cornellBox ? c.yaw : 14.0f);
    camera.setPitch(args.pitchGiven || !hybrid.cornellBox ? c.pitch : 12.0f);
    camera.setFovY(c.fovY);
    camera.setProjectionType(c.projection);
    if (c.target && c.distance) {
        camera.setTarget(*c.target);
        camera.setDistance(*c.distance);
        camera.setClipPlanes(*c.distance * 0.01f, *c.distance * 10.0f);
    }
    if (c.zoom != 1.0f) camera.zoom(c.zoom);
}

/// Opens a scene file's content: its mesh and volume with their placement, options and
/// materials, its light and camera (run() checked that the viewer can show all of it).
void ViewerModel::setSceneOptions(const sss::SceneDescription& scene) {
    hybrid = scene.options;
    if (!scene.meshes.empty()) {
        const sss::SceneMesh& m = scene.meshes.front();
        meshPath = m.source;
        meshTransform = m.transform;
        meshSize = m.size;
        meshOptions = m.options;
        material = m.material;
        meshTexture = m.texture;
        blinnPhong = m.baseline;
    }
    if (!scene.volumes.empty()) {
        const sss::SceneVolume& v = scene.volumes.front();
        volumePath = v.source;
        volumeRaw = v.raw;
        volumeTransform = v.transform;
        volumeOptions = v.options;
        setVolumeShading(v.options.shading);
        volumeMultiple = v.options.multipleScattering;
        volumeClip = v.clip;
    }
    if (!scene.lights.empty()) {
        const auto& d = std::get<sss::DirectionalLight>(scene.lights.front());
        const glm::vec3 towardsLight = -glm::normalize(d.direction);
        lightElevation = glm::degrees(std::asin(std::clamp(towardsLight.y, -1.0f, 1.0f)));
        lightAzimuth = glm::degrees(std::atan2(towardsLight.x, towardsLight.z));
        lightColor = d.color;
        lightIntensity = d.intensity;
    }
    displayTransform = scene.output.display;
}

/// The scene shown, as a scene description (mesh and volume as opened, normalised to one
/// unit, placed as shown; the transfer function inline; the camera where it is).
sss::SceneDescription ViewerModel::describeScene() const {
    sss::SceneDescription scene;
    scene.options = hybrid;
    if (mesh) {
        sss::SceneMesh m;
        m.source = meshPath;
        m.size = meshSize;
        m.transform = placedMeshTransform();
        m.options = renderedMeshOptions();
        m.options.finishEachPass = false;
        m.material = material;
        m.texture = meshTexture;
        m.baseline = blinnPhong;
        scene.meshes.push_back(m);
    }
    if (volume) {
        sss::SceneVolume v;
        v.source = volumeLabel;
        v.raw = volumeRaw;
        v.valueWindow = volume->transferFunctionRange();
        v.transferFunction.points = tfEditor.transferFunction().points();
        v.transform = placedVolumeTransform();
        v.options = renderedVolumeOptions();
        v.options.finishEachPass = false;
        v.clip = volumeClip;
        scene.volumes.push_back(v);
    }
    scene.lights = {light()};
    scene.camera.yaw = camera.yaw();
    scene.camera.pitch = camera.pitch();
    scene.camera.fovY = camera.fovY();
    scene.camera.projection = camera.projectionType();
    scene.camera.target = camera.target();
    scene.camera.distance = camera.distance();
    if (target) scene.output.width = target->width(), scene.output.height = target->height();
    scene.output.antiAliasing = args.antiAliasing;
    scene.output.display = displayTransform;
    return scene;
}

void ViewerModel::saveScene(const std::string& path) {
    try {
        sss::saveSceneFile(describeScene(), path);
        showMessage("saved the scene as " + path, false);
        std::printf("wrote %s\n", path.c_str());
    } catch (const std::exception& e) {
        if (args.exitAfter > 0) throw;  // batch: a scene that cannot be written is a failure
        showMessage(e.what(), true);
    }
}

void ViewerModel::setVolumeShading(sss::VolumeShading shading) {
    volumeScattering = shading == sss::VolumeShading::Scattering || shading == sss::VolumeShading::ScatteringGradient;
    volumeHighlights = shading == sss::VolumeShading::ScatteringGradient;
    volumeBaselineGradient = shading != sss::VolumeShading::EmissionAbsorption;
}

void ViewerModel::setVolume(sss::Volume opened, const std::string& label) {
    if (!opened.valueWindow()) opened.setValueWindow(args.input.tfRange);  // --tf-range applies to every volume opened
    histogram.histogram = sss::TransferFunctionEditor::histogramBars(opened, 128);
    histogram.rawRange = opened.transferFunctionRange();
    volume = std::move(opened);
    volumeLabel = label;
}

void ViewerModel::openMesh() {
    try {
        mesh = normalised(viewer::loadSceneMesh(meshPath, dataDir));
        meshSize = 1.0f;
        meshTransform.reset();
        volumeTransform.reset();
        sceneDirty = true;
        showMessage("opened " + meshPath, false);
    } catch (const std::exception& e) {  // sss::Error or UsageError: shown, never fatal
        showMessage(e.what(), true);
    }
}

void ViewerModel::openVolume() {
    try {
        sss::RawLoadOptions overrides;
        if (volumeDims.x > 0 && volumeDims.y > 0 && volumeDims.z > 0) overrides.dims = volumeDims;
        if (volume16) overrides.type = sss::VoxelType::UInt16;
        setVolume(viewer::loadSceneVolume(volumePath, dataDir, overrides), volumePath);
        volumeRaw = overrides;
        meshTransform.reset();
        volumeTransform.reset();
        sceneDirty = true;
        showMessage("opened " + volumePath, false);
    } catch (const std::exception& e) {
        showMessage(e.what(), true);
    }
}

sss::MeshRenderOptions ViewerModel::renderedMeshOptions() const {
    sss::MeshRenderOptions o = meshOptions;
    o.finishEachPass = honestTimings;
    return o;
}

sss::VolumeRenderOptions ViewerModel::renderedVolumeOptions() const {
    sss::VolumeRenderOptions o = volumeOptions;
    if (volumeScattering)
        o.shading = volumeHighlights ? sss::VolumeShading::ScatteringGradient : sss::VolumeShading::Scattering;
    else
        o.shading = volumeBaselineGradient ? sss::VolumeShading::Gradient : sss::VolumeShading::EmissionAbsorption;
    o.finishEachPass = honestTimings;
    // The path tracer needs the physical model without highlights; elsewhere the box is inert.
    o.multipleScattering = volumeMultiple && o.shading == sss::VolumeShading::Scattering &&
                           o.model == sss::VolumeModel::Physical;
    // The cache adds to the physical model's single scattering; the path tracer has it all.
    o.multipleScatteringCache = volumeOptions.multipleScatteringCache && volumeScattering &&
                                o.model == sss::VolumeModel::Physical && !o.multipleScattering;
    return o;
}

bool ViewerModel::pathTracing() const {
    return volume && renderedVolumeOptions().multipleScattering;
}

bool ViewerModel::volumeRefining() {
    if (!volume || !compositor || compositor->volumeCount() == 0) return false;
    const sss::VolumeRenderOptions o = renderedVolumeOptions();
    if (compositor->volume(0).lightVolumePreviewed()) return true;
    return o.multipleScatteringCache &&
           compositor->volume(0).cachedPhotons() < static_cast<std::uint64_t>(o.cachePhotons);
}

sss::Light ViewerModel::light() const {
    // The light travels from the direction given by azimuth (around +y) and elevation.
    const float az = glm::radians(lightAzimuth), el = glm::radians(lightElevation);
    const glm::vec3 towardsLight(std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az));
    if (!spotLight) return sss::DirectionalLight{-towardsLight, lightColor, lightIntensity};
    // A spot from the same direction, two content radii out, aimed at the centre; its
    // intensity is scaled by the distance squared so the centre gets the same irradiance.
    const sss::Bounds content = compositor->bounds();
    const float distance = 2.0f * std::max(content.radius(), 0.5f);
    return sss::SpotLight{content.center() + distance * towardsLight, -towardsLight, spotCone, spotFalloff,
                          lightColor, lightIntensity * distance * distance};
}

// A scene file's placement, else side by side when both are there.
sss::SceneTransform ViewerModel::placedMeshTransform() const {
    return meshTransform.value_or(sss::SceneTransform{.translate = glm::vec3(volume ? -0.6f : 0.0f, 0.0f, 0.0f)});
}

sss::SceneTransform ViewerModel::placedVolumeTransform() const {
    return volumeTransform.value_or(sss::SceneTransform{.translate = glm::vec3(mesh ? 0.6f : 0.0f, 0.0f, 0.0f)});
}

glm::mat4 ViewerModel::meshModel() const {
    return placedMeshTransform().matrix();
}

glm::mat4 ViewerModel::volumeModel() const {
    return placedVolumeTransform().matrix();
}

void ViewerModel::applyMaterials(sss::MeshScatteringRenderer& r) const {
    if (meshTexture && mesh && mesh->baseColour())
        r.setScatteringMaterial(sss::texturedScattering(material));
    else
        r.setScatteringMaterial(material);
    r.setMaterial(blinnPhong);
}

void ViewerModel::rebuildScene() {
    compositor->clear();
    compositor->setOptions(hybrid);
    if (mesh) {
        sss::MeshScatteringRenderer& r = compositor->addMesh(*mesh, meshModel(), renderedMeshOptions());
        applyMaterials(r);
    }
    if (volume) {
        sss::VolumeScatteringRenderer& r = compositor->addVolume(*volume, volumeModel(), renderedVolumeOptions());
        r.setTransferFunction(tfEditor.transferFunction());
        r.setClip(volumeClip);
    }
    uploadedTf = tfEditor.transferFunction().revision();
    compositor->setLights({light()});
    mapFrames = 0;
}

void ViewerModel::reframe() {
    const sss::Bounds content = compositor->bounds();
    if (content.empty()) return;
    // In a Cornell box, show the box (about its bounding sphere; the editor at the bottom takes room).
    const sss::Bounds bounds = hybrid.cornellBox ? sss::makeCornellBox(content).bounds : content;
    camera.setTarget(glm::vec3(0.0f));
    camera.frame(bounds);
    if (hybrid.cornellBox) camera.setDistance(camera.distance() * (tfWindowShown() ? 1.15f : 0.9f));
    camera.setClipPlanes(camera.distance() * 0.01f, camera.distance() * 10.0f);
    // Centre the content in the part of the window the UI leaves free (if there is room).
    if (showUi && target && static_cast<float>(target->width()) > 2.5f * kPanelWidth) {
        const float perPixel = 2.0f * std::tan(glm::radians(camera.fovY()) * 0.5f) /
                               static_cast<float>(target->height());
        const float down = tfWindowShown() ? 0.5f * std::min(kTfWindowHeight, 0.5f * static_cast<float>(target->height())) : 0.0f;
        camera.pan(glm::vec2(-0.5f * panelWidth(), -down) * perPixel);
    }
}

// Pushes the UI's settings into the renderers; a bad value shows an error instead of throwing.
void ViewerModel::applyChanges() {
    viewChanged |= sceneDirty || windowDirty || meshDirty || volumeDirty || lightsDirty || hybridDirty ||
                     uploadedTf != tfEditor.transferFunction().revision();
    try {
        if (sceneDirty) {
            rebuildScene();
            reframe();
            sceneDirty = false;
            meshDirty = volumeDirty = lightsDirty = hybridDirty = windowDirty = false;
        }
        if (windowDirty) {  // the volume again, with its new window; the camera stays
            rebuildScene();
            windowDirty = false;
            meshDirty = volumeDirty = lightsDirty = hybridDirty = false;
        }
        if (hybridDirty) compositor->setOptions(hybrid);
        if (lightsDirty) compositor->setLights({light()});
        for (std::size_t i = 0; i < compositor->meshCount() && meshDirty; ++i) {
            compositor->mesh(i).setOptions(renderedMeshOptions());
            applyMaterials(compositor->mesh(i));
        }
        for (std::size_t i = 0; i < compositor->volumeCount(); ++i) {
            if (volumeDirty) {
                compositor->volume(i).setOptions(renderedVolumeOptions());
                compositor->volume(i).setClip(volumeClip);
            }
            if (uploadedTf != tfEditor.transferFunction().revision())
                compositor->volume(i).setTransferFunction(tfEditor.transferFunction());
        }
        if (meshDirty || lightsDirty || hybridDirty) mapFrames = 0;
    } catch (const sss::Error& e) {
        showMessage(e.what(), true);
    }
    uploadedTf = tfEditor.transferFunction().revision();
    meshDirty = volumeDirty = lightsDirty = hybridDirty = false;
}

// Counts map frames while the scattering maps accumulate, and notes light-volume rebuilds.
void ViewerModel::trackProgress() {
    bool converged = true;
    for (std::size_t i = 0; i < compositor->meshCount(); ++i)
        converged = converged && compositor->mesh(i).converged();
    mapsConverged = converged || meshOptions.shading != sss::MeshShading::Scattering;
    mapFrames = mapsConverged ? 0 : mapFrames + 1;
    std::uint64_t runs = 0;
    double lastMs = 0.0;
    for (std::size_t i = 0; i < compositor->volumeCount(); ++i) {
        const sss::VolumeScatteringRenderer& volumeRenderer = compositor->volume(i);
        const sss::RenderStats& stats = volumeRenderer.stats();
        runs += stats.runs("light-volume") + stats.runs("light-volume-preview");
        // The build the frame shows: the preview while one is shown.
        if (const sss::PassStats* p = stats.find(volumeRenderer.lightVolumePreviewed() ? "light-volume-preview" : "light-volume"))
            lastMs = p->lastMs;
    }
    if (runs != lightVolumeRuns) {
        lightVolumeRuns = runs;
        lightVolumeBuiltFrame = frameIndex;
        lightVolumeMs = lastMs;
    }
}

void ViewerModel::showMessage(std::string text, bool error) {
    if (error && args.exitAfter > 0) std::fprintf(stderr, "sss-viewer: %s\n", text.c_str());
    message = std::move(text);
    messageIsError = error;
    messageTime = Clock::now();
}

// Narrow windows get a narrower panel, so some of the scene stays visible.
float ViewerModel::panelWidth() const {
    const float width = target ? static_cast<float>(target->width()) : 1280.0f;
    return std::min(kPanelWidth, std::max(260.0f, 0.45f * width));
}

bool ViewerModel::tfWindowShown() const {
    return showUi && volume.has_value();
}

}  // namespace viewer
