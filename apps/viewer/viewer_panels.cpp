#include "viewer_panels.h"

#include <sss/error.h>
#include <sss/option_names.h>

#include <imgui.h>
#include <imgui_stdlib.h>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace viewer {
namespace {

constexpr std::array<int, 5> kMapResolutions{128, 256, 512, 1024, 2048};

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

}  // namespace

void Panels::draw() {
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(vp->WorkPos, ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(m_model.panelWidth(), vp->WorkSize.y), ImGuiCond_Always);
    ImGui::SetNextWindowBgAlpha(0.88f);
    ImGui::Begin("libsss viewer", nullptr,
                 ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    m_layout.panel = currentWindowRect();
    ImGui::PushItemWidth(-0.38f * m_model.panelWidth());
    if (ImGui::CollapsingHeader("Scene", ImGuiTreeNodeFlags_DefaultOpen)) sceneSection();
    if (ImGui::CollapsingHeader("Light and camera", ImGuiTreeNodeFlags_DefaultOpen)) lightSection();
    if (m_model.mesh && ImGui::CollapsingHeader("Mesh: subsurface scattering", ImGuiTreeNodeFlags_DefaultOpen))
        meshSection();
    if (m_model.volume && ImGui::CollapsingHeader("Volume: light-volume scattering", ImGuiTreeNodeFlags_DefaultOpen))
        volumeSection();
    if (m_model.volume && ImGui::CollapsingHeader("Volume: clipping")) clipSection();
    if (ImGui::CollapsingHeader("Timings")) timingSection();
    ImGui::PopItemWidth();
    ImGui::End();
    if (m_model.volume) drawTransferFunctionWindow();
}

// Frame time, progress and messages, top right.
void Panels::drawOverlay() {
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(vp->WorkPos.x + vp->WorkSize.x - 10.0f, vp->WorkPos.y + 10.0f),
                            ImGuiCond_Always, ImVec2(1.0f, 0.0f));
    ImGui::SetNextWindowBgAlpha(0.6f);
    ImGui::Begin("##overlay", nullptr,
                 ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove |
                     ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                     ImGuiWindowFlags_NoNav);
    m_layout.overlay = currentWindowRect();
    ImGui::Text("frame %.1f ms (%.1f fps), scene %s %.1f ms", m_model.frameMs,
                m_model.frameMs > 0 ? 1000.0 / m_model.frameMs : 0.0, m_model.honestTimings ? "(GPU)" : "submit", m_model.renderMs);
    ImGui::Text("%dx%d, %s", m_model.target ? m_model.target->width() : 0, m_model.target ? m_model.target->height() : 0,
                m_model.renderer.c_str());
    if (!m_model.mapsConverged)
        ImGui::TextColored(ImVec4(1.0f, 0.75f, 0.3f, 1.0f), "accumulating scattering maps %d / %d", m_model.mapFrames,
                           m_model.meshOptions.accumulationFrames);
    if (m_model.volume && m_model.volumeScattering && m_model.frameIndex - m_model.lightVolumeBuiltFrame < 3 && m_model.lightVolumeRuns > 0)
        ImGui::TextColored(ImVec4(1.0f, 0.75f, 0.3f, 1.0f), "light volume rebuilt (%.1f ms)", m_model.lightVolumeMs);
    if (!m_model.message.empty() && msSince(m_model.messageTime) < 8000.0)
        ImGui::TextColored(m_model.messageIsError ? ImVec4(1.0f, 0.45f, 0.4f, 1.0f) : ImVec4(0.6f, 0.9f, 0.6f, 1.0f),
                           "%s", m_model.message.c_str());
    ImGui::End();
}

// The editor gets a wide window along the bottom, right of the panel.
void Panels::drawTransferFunctionWindow() {
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    const float left = vp->WorkPos.x + m_model.panelWidth() + 8.0f;
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

void Panels::sceneSection() {
    ImGui::InputText("mesh (.obj)", &m_model.meshPath);
    if (ImGui::Button("Open mesh")) m_model.openMesh();
    ImGui::SameLine();
    ImGui::BeginDisabled(!m_model.mesh);
    if (ImGui::Button("Remove mesh")) {
        m_model.mesh.reset();
        m_model.sceneDirty = true;
    }
    ImGui::EndDisabled();
    ImGui::InputText("volume", &m_model.volumePath);
    ImGui::InputInt3("dims (0: name)", &m_model.volumeDims.x);
    ImGui::Checkbox("16-bit voxels", &m_model.volume16);
    if (ImGui::Button("Open volume")) m_model.openVolume();
    ImGui::SameLine();
    ImGui::BeginDisabled(!m_model.volume);
    if (ImGui::Button("Remove volume")) {
        m_model.volume.reset();
        m_model.sceneDirty = true;
    }
    ImGui::EndDisabled();
    ImGui::TextDisabled("procedural: sphere torus slab | blobs shell bucky");
    m_model.hybridDirty |= ImGui::Checkbox("Cornell box", &m_model.hybrid.cornellBox);
    ImGui::SameLine();
    if (ImGui::Button("Reframe (F)")) m_model.reframe();
    m_model.hybridDirty |= ImGui::Checkbox("meshes shadow volumes", &m_model.hybrid.meshShadowsInVolumes);
    m_model.hybridDirty |= ImGui::Checkbox("meshes shadow meshes", &m_model.hybrid.meshShadowsOnMeshes);
    m_model.hybridDirty |= ImGui::Checkbox("volumes shadow meshes", &m_model.hybrid.volumeShadowsOnMeshes);
    float background[3] = {m_model.hybrid.background.r, m_model.hybrid.background.g, m_model.hybrid.background.b};
    if (ImGui::ColorEdit3("background", background)) {
        m_model.hybrid.background = glm::vec4(background[0], background[1], background[2], 1.0f);
        m_model.hybridDirty = true;
    }
    ImGui::InputText("screenshot", &m_model.screenshotPath);
    ImGui::SameLine();
    if (ImGui::Button("Save (F12)")) m_model.screenshotRequested = true;
    ImGui::InputText("scene file", &m_model.scenePath);
    ImGui::SameLine();
    if (ImGui::Button("Save scene")) m_model.saveScene(m_model.scenePath);
}

void Panels::lightSection() {
    m_model.lightsDirty |= ImGui::SliderFloat("light azimuth", &m_model.lightAzimuth, -180.0f, 180.0f, "%.0f deg");
    m_model.lightsDirty |= ImGui::SliderFloat("light elevation", &m_model.lightElevation, -89.0f, 89.0f, "%.0f deg");
    m_model.lightsDirty |= colorEdit("light colour", m_model.lightColor);
    m_model.lightsDirty |= ImGui::SliderFloat("light intensity", &m_model.lightIntensity, 0.0f, 4.0f, "%.2f");
    m_model.lightsDirty |= ImGui::Checkbox("spot light", &m_model.spotLight);
    if (m_model.spotLight) {
        m_model.lightsDirty |= ImGui::SliderFloat("cone half-angle", &m_model.spotCone, 1.0f, 90.0f, "%.0f deg");
        m_model.lightsDirty |= ImGui::SliderFloat("cone falloff", &m_model.spotFalloff, 0.0f, 1.0f, "%.2f");
    }
    ImGui::SliderFloat("exposure (stops)", &m_model.displayTransform.exposure, -8.0f, 8.0f, "%.1f");
    int toneMap = m_model.displayTransform.toneMap == sss::ToneMap::Filmic ? 1 : 0;
    if (ImGui::Combo("tone mapping", &toneMap, "none (clip)\0filmic\0"))
        m_model.displayTransform.toneMap = toneMap == 1 ? sss::ToneMap::Filmic : sss::ToneMap::None;
    ImGui::TextDisabled("left drag: orbit, right/middle: pan, wheel: zoom");
}

void Panels::meshSection() {
    bool scattering = m_model.meshOptions.shading == sss::MeshShading::Scattering;
    if (ImGui::Checkbox("scattering (off: Blinn-Phong)", &scattering)) {
        m_model.meshOptions.shading = scattering ? sss::MeshShading::Scattering : sss::MeshShading::BlinnPhong;
        m_model.meshDirty = true;
    }
    if (!scattering) {
        m_model.meshDirty |= colorEdit("diffuse", m_model.blinnPhong.diffuse);
        m_model.meshDirty |= ImGui::SliderFloat("shininess", &m_model.blinnPhong.shininess, 1.0f, 200.0f, "%.0f");
        return;
    }
    bool calibrated = m_model.meshOptions.profile == sss::ScatteringProfile::Calibrated;
    if (ImGui::Checkbox("calibrated profile", &calibrated)) {
        m_model.meshOptions.profile = calibrated ? sss::ScatteringProfile::Calibrated : sss::ScatteringProfile::Dipole;
        m_model.meshDirty = true;
    }
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("on: the dipole rescaled to a random walk, plus single scattering\noff: the paper's directional dipole");
    // Where the combine pass reads the radiosity (the CLI's --combine names).
    const std::string combineName(sss::enumName(m_model.meshOptions.combine));
    if (ImGui::BeginCombo("combine", combineName.c_str())) {
        for (const auto& [value, name] : sss::enumNames<sss::MeshCombine>()) {
            if (ImGui::Selectable(std::string(name).c_str(), value == m_model.meshOptions.combine)) {
                m_model.meshOptions.combine = value;
                m_model.meshDirty = true;
            }
        }
        ImGui::EndCombo();
    }
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("auto: vertex-estimate on fine meshes, per-pixel on coarse ones\n"
                          "per-pixel: the K maps at every pixel (the paper's)\nper-vertex: the maps resolved per vertex\n"
                          "vertex-estimate: no maps, the radiosity estimated at each vertex (fine meshes)");
    const std::vector<std::string> names = sss::materialPresetNames();
    const char* current = m_model.materialIndex >= 0 ? names[static_cast<std::size_t>(m_model.materialIndex)].c_str()
                                                : "(custom)";
    if (ImGui::BeginCombo("material", current)) {
        for (std::size_t i = 0; i < names.size(); ++i) {
            if (ImGui::Selectable(names[i].c_str(), static_cast<int>(i) == m_model.materialIndex)) {
                m_model.materialIndex = static_cast<int>(i);
                m_model.material = sss::materialPreset(names[i]);
                m_model.meshDirty = true;
            }
        }
        ImGui::EndCombo();
    }
    if (m_model.mesh && m_model.mesh->baseColour() && ImGui::Checkbox("texture as reflectance", &m_model.meshTexture))
        m_model.meshDirty = true;
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("the mesh's base-colour texture gives each point its reflectance;\n"
                          "the material gives the mean free path and eta");
    sss::ScatteringMaterial edited = m_model.material;
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
            m_model.material = edited;
            m_model.materialIndex = -1;
            m_model.meshDirty = true;
        } catch (const sss::Error& e) {
            m_model.showMessage(e.what(), true);
        }
    }
    float scale = static_cast<float>(m_model.meshOptions.millimetresPerUnit);
    if (ImGui::DragFloat("scale (mm/unit)", &scale, 0.5f, 1.0f, 5000.0f, "%.1f",
                         ImGuiSliderFlags_Logarithmic)) {
        m_model.meshOptions.millimetresPerUnit = std::max(1.0f, scale);
        m_model.meshDirty = true;
    }
    m_model.meshDirty |= ImGui::SliderInt("K (map cameras)", &m_model.meshOptions.cameras, 1, 32);
    m_model.meshDirty |= ImGui::SliderInt("N (samples)", &m_model.meshOptions.samples, 1, 256);
    if (comboInt("map resolution", m_model.meshOptions.mapResolution, kMapResolutions.data(), kMapResolutions.size())) {
        m_model.meshOptions.lightMapResolution = m_model.meshOptions.mapResolution;
        m_model.meshDirty = true;
    }
    m_model.meshDirty |= ImGui::SliderInt("frames accumulated", &m_model.meshOptions.accumulationFrames, 1, 64);
    m_model.meshDirty |= ImGui::SliderFloat("near field (edges)", &m_model.meshOptions.nearField, 0.0f, 4.0f, "%.2f");
    m_model.meshDirty |=
        ImGui::SliderFloat("near field points (texels; 0: per pixel)", &m_model.meshOptions.nearFieldSpacing, 0.0f, 8.0f, "%.1f");
    m_model.meshDirty |= ImGui::SliderFloat("specular", &m_model.meshOptions.specular, 0.0f, 2.0f, "%.2f");
    m_model.meshDirty |= ImGui::SliderFloat("environment", &m_model.meshOptions.environment.x, 0.0f, 0.5f, "%.3f");
    m_model.meshOptions.environment = glm::vec3(m_model.meshOptions.environment.x);  // grey: one slider
    if (m_model.mapsConverged) {
        ImGui::TextColored(ImVec4(0.5f, 0.9f, 0.5f, 1.0f), "scattering maps converged");
    } else {
        const float done = std::min(1.0f, static_cast<float>(m_model.mapFrames) /
                                              static_cast<float>(m_model.meshOptions.accumulationFrames));
        const std::string text = "accumulating maps: frame " + std::to_string(m_model.mapFrames) + " / " +
                                 std::to_string(m_model.meshOptions.accumulationFrames);
        ImGui::ProgressBar(done, ImVec2(-1.0f, 0.0f), text.c_str());
    }
}

// One clip plane through the volume's centre (shifted along its normal) and the crop box.
void Panels::clipSection() {
    sss::VolumeClip& clip = m_model.volumeClip;
    bool changed = false;
    if (clip.cropSpace == sss::CropSpace::Data) {
        static const char* axes[] = {"crop x", "crop y", "crop z"};
        for (int a = 0; a < 3; ++a) {
            changed |= ImGui::DragFloatRange2(axes[a], &clip.cropMin[a], &clip.cropMax[a], 0.005f, 0.0f, 1.0f, "%.3f",
                                              "%.3f", ImGuiSliderFlags_AlwaysClamp);
            clip.cropMax[a] = std::max(clip.cropMax[a], std::min(clip.cropMin[a] + 0.01f, 1.0f));
            clip.cropMin[a] = std::min(clip.cropMin[a], clip.cropMax[a] - 0.01f);
        }
    } else {  // a scene file's world-space box: kept as it is, the reset below removes it
        ImGui::Text("world crop box (%.2f, %.2f, %.2f) to (%.2f, %.2f, %.2f)", clip.cropMin.x, clip.cropMin.y,
                    clip.cropMin.z, clip.cropMax.x, clip.cropMax.y, clip.cropMax.z);
    }
    bool plane = !clip.planes.empty();
    if (ImGui::Checkbox("clip plane", &plane)) {
        clip.planes.clear();
        if (plane) clip.planes.push_back({glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f)});
        clip.planeSpace = sss::CropSpace::World;
        changed = true;
    }
    if (plane && clip.planeSpace == sss::CropSpace::Data) {  // a scene file's: kept, the reset removes them
        ImGui::Text("%zu plane(s) in normalised data coordinates", clip.planes.size());
    } else if (plane) {
        // The normal as azimuth and elevation; the plane through centre + offset * normal.
        sss::ClipPlane& p = clip.planes.front();
        const glm::vec3 n = glm::normalize(p.normal);
        float azimuth = glm::degrees(std::atan2(n.x, n.z)), elevation = glm::degrees(std::asin(std::clamp(n.y, -1.0f, 1.0f)));
        float offset = glm::dot(p.point - glm::vec3(m_model.volumeModel()[3]), n);
        bool moved = ImGui::SliderFloat("plane azimuth", &azimuth, -180.0f, 180.0f, "%.0f deg");
        moved |= ImGui::SliderFloat("plane elevation", &elevation, -90.0f, 90.0f, "%.0f deg");
        moved |= ImGui::SliderFloat("plane offset", &offset, -0.9f, 0.9f, "%.3f");
        if (moved) {
            const float a = glm::radians(azimuth), e = glm::radians(elevation);
            p.normal = glm::vec3(std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a));
            p.point = glm::vec3(m_model.volumeModel()[3]) + offset * p.normal;
            changed = true;
        }
    }
    changed |= ImGui::Checkbox("cut matter casts shadows", &clip.clippedMatterCastsShadows);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("off: the cut face is lit like the inside it exposes\non: the removed matter still shadows it");
    if (ImGui::Button("reset clipping")) {
        clip = {};
        changed = true;
    }
    m_model.volumeDirty |= changed;
}

void Panels::volumeSection() {
    const auto dims = m_model.volume->dims();
    ImGui::Text("%s: %dx%dx%d %s", m_model.volumeLabel.c_str(), dims.x, dims.y, dims.z,
                sss::voxelTypeName(m_model.volume->type()));
    m_model.volumeDirty |= ImGui::Checkbox("scattering", &m_model.volumeScattering);
    ImGui::SameLine();
    if (m_model.volumeScattering) {
        m_model.volumeDirty |= ImGui::Checkbox("+ gradient highlights", &m_model.volumeHighlights);
    } else {
        int baseline = m_model.volumeBaselineGradient ? 0 : 1;
        ImGui::SetNextItemWidth(150.0f);
        if (ImGui::Combo("##off", &baseline, "gradient (Phong)\0emission-absorption\0")) {
            m_model.volumeBaselineGradient = baseline == 0;
            m_model.volumeDirty = true;
        }
    }
    m_model.volumeDirty |= ImGui::SliderFloat("ray step (voxels)", &m_model.volumeOptions.stepSize, 0.25f, 4.0f, "%.2f");
    m_model.volumeDirty |= ImGui::Checkbox("pre-integrated classification", &m_model.volumeOptions.preintegration);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("on: each sample integrates the transfer function over the segment since the previous "
                          "one (thin structures between samples show)\noff: the transfer function at the sample "
                          "alone (the thesis)");
    bool cubic = m_model.volumeOptions.reconstruction == sss::VolumeReconstruction::CubicBSpline;
    if (ImGui::Checkbox("cubic B-spline field", &cubic)) {
        m_model.volumeOptions.reconstruction =
            cubic ? sss::VolumeReconstruction::CubicBSpline : sss::VolumeReconstruction::Trilinear;
        m_model.volumeDirty = true;
    }
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("on: the smooth cubic B-spline between voxels (no terraces on coarse data, about 3x the "
                          "ray-casting cost)\noff: trilinear interpolation");
    if (m_model.volumeScattering) {
        m_model.volumeDirty |= ImGui::SliderFloat("light-volume scale", &m_model.volumeOptions.lightVolumeScale, 0.1f, 1.0f,
                                            "%.2f");
        bool preview = m_model.volumeOptions.lightVolumePreviewScale > 0.0f;
        if (ImGui::Checkbox("preview light edits", &preview)) {
            m_model.volumeOptions.lightVolumePreviewScale = preview ? ViewerOptions::kLightVolumePreviewScale : 0.0f;
            m_model.volumeDirty = true;
        }
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("on: the frame after a light or transfer-function edit draws a light volume at a quarter\n"
                              "of the scale, the next frame the full one (for slow GPUs; off: every frame the full one)");
        // LightVolumeFallback::Reduce lowered it: the asked-for light volume does not fit the GPU.
        const float inUse = m_model.compositor->volume(0).lightVolumeScaleInUse();
        if (inUse > 0.0f && inUse < m_model.volumeOptions.lightVolumeScale)
            ImGui::TextColored(ImVec4(1.0f, 0.7f, 0.3f, 1.0f), "does not fit the GPU: using %.3g", inUse);
        m_model.volumeDirty |= ImGui::SliderFloat("anisotropy g", &m_model.volumeOptions.anisotropy, -0.9f, 0.9f, "%.2f");
        bool physical = m_model.volumeOptions.model == sss::VolumeModel::Physical;
        if (ImGui::Checkbox("physical single scattering", &physical)) {
            m_model.volumeOptions.model = physical ? sss::VolumeModel::Physical : sss::VolumeModel::Paper;
            m_model.volumeDirty = true;
        }
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("on: TF colour as albedo x phase function x light (about 4 pi dimmer)\noff: the paper's ambient + diffuse x light-volume colour");
        if (physical && !m_model.volumeMultiple) {
            m_model.volumeDirty |=
                ImGui::Checkbox("multiple scattering (cache)", &m_model.volumeOptions.multipleScatteringCache);
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip("adds the light scattered more than once, from a view-independent cache that\n"
                                  "photons from the light fill over the next frames; camera moves reuse it");
            if (m_model.volumeOptions.multipleScatteringCache)
                ImGui::Text("cache photons: %llu of %d",
                            static_cast<unsigned long long>(m_model.compositor->volume(0).cachedPhotons()),
                            m_model.volumeOptions.cachePhotons);
        }
        if (physical && !m_model.volumeHighlights) {
            m_model.volumeDirty |= ImGui::Checkbox("multiple scattering (path traced)", &m_model.volumeMultiple);
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip("all orders of scattering, path traced on the GPU: one path per pixel and\n"
                                  "frame, accumulated while the camera and the scene stay still");
            if (m_model.volumeMultiple)
                ImGui::Text("paths per pixel: %d", m_model.compositor->volume(0).accumulatedSamples());
        }
    }
    m_model.volumeDirty |= ImGui::SliderFloat("ambient", &m_model.volumeOptions.ambient, 0.0f, 1.0f, "%.2f");
    m_model.volumeDirty |= ImGui::SliderFloat("diffuse", &m_model.volumeOptions.diffuse, 0.0f, 2.0f, "%.2f");
    if (m_model.volumeScattering) {
        const bool recent = m_model.frameIndex - m_model.lightVolumeBuiltFrame < 3 && m_model.lightVolumeRuns > 0;
        if (recent)
            ImGui::TextColored(ImVec4(1.0f, 0.75f, 0.3f, 1.0f), "light volume %s (%.1f ms)",
                               m_model.compositor->volume(0).lightVolumePreviewed() ? "preview" : "rebuilt",
                               m_model.lightVolumeMs);
        else
            ImGui::TextColored(ImVec4(0.5f, 0.9f, 0.5f, 1.0f), "light volume up to date");
    }
}

void Panels::transferFunctionSection(float windowHeight) {
    const std::vector<std::string> presets = sss::TransferFunction::presetNames();
    ImGui::SetNextItemWidth(130.0f);
    if (ImGui::BeginCombo("preset", m_model.tfPreset.empty() ? "(edited)" : m_model.tfPreset.c_str())) {
        for (const std::string& name : presets)
            if (ImGui::Selectable(name.c_str(), name == m_model.tfPreset)) {
                m_model.tfEditor.setTransferFunction(sss::TransferFunction::preset(name));
                m_model.tfPreset = name;
            }
        ImGui::EndCombo();
    }
    ImGui::SameLine();
    ImGui::SetNextItemWidth(std::max(80.0f, ImGui::GetContentRegionAvail().x - 290.0f));
    ImGui::InputText("##json", &m_model.tfPath);
    ImGui::SameLine();
    if (ImGui::Button("Save JSON")) {
        try {
            m_model.tfEditor.transferFunction().saveParaViewJson(m_model.tfPath, "sss-viewer");
            m_model.showMessage("saved " + m_model.tfPath, false);
        } catch (const sss::Error& e) {
            m_model.showMessage(e.what(), true);
        }
    }
    ImGui::SameLine();
    if (ImGui::Button("Load JSON")) {
        try {
            m_model.tfEditor.setTransferFunction(sss::TransferFunction::loadParaViewJson(m_model.tfPath));
            m_model.tfPreset.clear();
            m_model.showMessage("loaded " + m_model.tfPath, false);
        } catch (const sss::Error& e) {
            m_model.showMessage(e.what(), true);
        }
    }
    ImGui::SameLine();
    ImGui::TextDisabled("(ParaView)");
    valueWindowRow();
    const uint64_t before = m_model.tfEditor.transferFunction().revision();
    // The canvas takes what is left above the point controls (two rows).
    const float canvasHeight = std::max(60.0f, windowHeight - 5.0f * ImGui::GetFrameHeightWithSpacing() - 20.0f);
    ScreenRect canvas;
    transferFunctionEditorWidget(m_model.tfEditor, m_model.histogram, canvasHeight, &canvas);
    m_layout.tfCanvas = canvas;
    if (m_model.tfEditor.transferFunction().revision() != before) m_model.tfPreset.clear();
}

// Window/level of the value window (Volume::setValueWindow, in data units): the TF's domain is
// level -+ window / 2. Applied when a drag ends, since the volume is uploaded again.
void Panels::valueWindowRow() {
    if (!m_model.volume) {
        ImGui::TextDisabled("window/level: open a volume");
        return;
    }
    const auto [lo, hi] = m_model.volume->transferFunctionRange();
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
        m_model.volume->setValueWindow(reset ? std::nullopt
                                       : std::optional(std::pair<double, double>(levelEdited - 0.5 * window,
                                                                                 levelEdited + 0.5 * window)));
        m_model.histogram.histogram = sss::TransferFunctionEditor::histogramBars(*m_model.volume, 128);
        m_model.histogram.rawRange = m_model.volume->transferFunctionRange();
        m_model.windowDirty = true;
    } catch (const sss::Error& e) {  // a window of width <= 0
        m_model.showMessage(e.what(), true);
    }
}

void Panels::timingSection() {
    if (ImGui::Checkbox("wait for the GPU after each pass", &m_model.honestTimings)) m_model.meshDirty = m_model.volumeDirty = true;
    ImGui::TextDisabled(m_model.honestTimings ? "times below are GPU times"
                                        : "times below are CPU submission times");
    if (ImGui::BeginTable("passes", 3, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp)) {
        ImGui::TableSetupColumn("pass");
        ImGui::TableSetupColumn("last ms");
        ImGui::TableSetupColumn("runs");
        ImGui::TableHeadersRow();
        statsTable("hybrid", m_model.compositor->stats());
        for (std::size_t i = 0; i < m_model.compositor->meshCount(); ++i) statsTable("mesh", m_model.compositor->mesh(i).stats());
        for (std::size_t i = 0; i < m_model.compositor->volumeCount(); ++i)
            statsTable("volume", m_model.compositor->volume(i).stats());
        ImGui::EndTable();
    }
}

void Panels::statsTable(const char* owner, const sss::RenderStats& stats) {
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

// Where the window being built lies (window pixels).
ScreenRect Panels::currentWindowRect() {
    const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
    return {pos.x, pos.y, pos.x + size.x, pos.y + size.y};
}

}  // namespace viewer
