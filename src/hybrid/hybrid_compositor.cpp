#include "sss/hybrid_compositor.h"

#include "core/light_geometry.h"
#include "gl/framebuffer.h"
#include "gl/program.h"
#include "mesh/renderer_access.h"
#include "volume/renderer_access.h"
#include "lighting/light_uniforms.h"
#include "hybrid/mesh_shadow_map_pass.h"
#include "mesh/light_buffer_pass.h"
#include "sss/log.h"
#include "sss/error.h"
#include "sss/option_table.h"
#include "sss/procedural.h"
#include "sss/timing.h"

#include <algorithm>
#include <chrono>
#include <optional>
#include <string>

namespace sss {
namespace {


}  // namespace

void validate(const HybridOptions& o) { validateOptionRanges(o); }

struct HybridCompositor::Impl {
    HybridOptions options;
    std::vector<Light> lights{DirectionalLight{}};
    // unique_ptr: the references addMesh/addVolume return stay valid as more are added.
    std::vector<std::unique_ptr<MeshScatteringRenderer>> meshes;
    std::vector<std::unique_ptr<VolumeScatteringRenderer>> volumes;
    std::vector<std::unique_ptr<MeshScatteringRenderer>> walls;  // Cornell box: white, red, green
    std::optional<Bounds> wallsFor;                              // content bounds the walls were built for
    RenderStats stats;

    // Meshes seen from the lights, for volumes and mesh surfaces (rebuilt when meshes, lights or
    // bounds change).
    detail::MeshShadowMaps meshShadows;
    std::uint64_t sceneRevision = 1;      // bumped by every change the shadow maps depend on
    std::uint64_t shadowMapsRevision = 0; // sceneRevision the maps were drawn for
    std::optional<detail::MeshShadowMapPass> shadowMapPass;
    bool warnedVolumeShadowLimit = false;

    Bounds contentBounds() const {
        Bounds b;
        for (const auto& m : meshes)
            if (const detail::GpuMesh* gpu = detail::MeshRendererAccess::mesh(*m)) {
                const auto [c, r] = detail::worldSphere(gpu->bounds, detail::MeshRendererAccess::model(*m));
                b.extend(c - glm::vec3(r));
                b.extend(c + glm::vec3(r));
            }
        for (const auto& v : volumes) b.extend(detail::VolumeRendererAccess::worldBounds(*v));
        return b;
    }

    void updateWalls() {
        if (!options.cornellBox) {
            walls.clear();
            wallsFor.reset();
            return;
        }
        const Bounds content = contentBounds();
        if (content.empty() || (wallsFor && wallsFor->min == content.min && wallsFor->max == content.max)) return;
        const CornellBox box = makeCornellBox(content);
        walls.clear();
        for (auto [mesh, color] : {std::pair{&box.white, box.whiteColor}, std::pair{&box.red, box.redColor},
                                   std::pair{&box.green, box.greenColor}}) {
            auto wall = std::make_unique<MeshScatteringRenderer>();
            wall->setMesh(*mesh);
            wall->setMaterial({.diffuse = color, .specular = glm::vec3(0.0f), .ambient = glm::vec3(0.03f)});
            walls.push_back(std::move(wall));
        }
        wallsFor = content;
    }

    void updateMeshShadowMaps() {
        if (shadowMapsRevision == sceneRevision && meshShadows.depth) return;
        const auto start = std::chrono::steady_clock::now();
        std::vector<detail::ShadowCaster> casters;
        for (const auto& m : meshes)
            if (const detail::GpuMesh* gpu = detail::MeshRendererAccess::mesh(*m))
                casters.push_back({gpu, detail::MeshRendererAccess::model(*m)});
        if (!shadowMapPass) shadowMapPass.emplace();
        shadowMapPass->run({lights, casters, contentBounds(), options.shadowMapResolution}, meshShadows);
        meshShadows.revision = sceneRevision;
        shadowMapsRevision = sceneRevision;
        stats.record("mesh-shadow-maps",
                     std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }

    // What shadows each mesh and wall: the mesh shadow maps (if on) and every volume's light
    // volumes (if on), as many as fit the texture units.
    void shareShadows(bool useMeshMaps) {
        std::vector<detail::VolumeShadows> volumeShadows;
        if (options.volumeShadowsOnMeshes)
            for (auto& v : volumes)
                if (auto s = detail::VolumeRendererAccess::shadows(*v)) volumeShadows.push_back(*s);
        const std::size_t fit = static_cast<std::size_t>(detail::kMaxVolumeShadowPairs) / std::max<std::size_t>(1, lights.size());
        if (volumeShadows.size() > fit && !warnedVolumeShadowLimit) {
            log(LogLevel::Warning, "hybrid scene: only the first " + std::to_string(fit) + " of " +
                                              std::to_string(volumeShadows.size()) + " volumes shadow meshes with " +
                                              std::to_string(lights.size()) + " lights (at most " +
                                              std::to_string(detail::kMaxVolumeShadowPairs) + " volume-light pairs)");
            warnedVolumeShadowLimit = true;
        }
        for (std::size_t i = 0; i < meshes.size(); ++i) {
            detail::SurfaceShadows shadows;
            shadows.meshes = useMeshMaps ? &meshShadows : nullptr;
            shadows.selfId = static_cast<unsigned>(i + 1);
            shadows.volumes = volumeShadows;
            detail::MeshRendererAccess::setShadows(*meshes[i], &shadows);
        }
        detail::SurfaceShadows wallShadows;
        wallShadows.meshes = useMeshMaps ? &meshShadows : nullptr;
        wallShadows.volumes = volumeShadows;
        for (auto& w : walls) detail::MeshRendererAccess::setShadows(*w, &wallShadows);
    }
};

HybridCompositor::HybridCompositor(const HybridOptions& options) : m_impl(std::make_unique<Impl>()) {
    validate(options);
    m_impl->options = options;
}

HybridCompositor::~HybridCompositor() = default;
HybridCompositor::HybridCompositor(HybridCompositor&&) noexcept = default;
HybridCompositor& HybridCompositor::operator=(HybridCompositor&&) noexcept = default;

MeshScatteringRenderer& HybridCompositor::addMesh(const Mesh& mesh, const glm::mat4& model, const MeshRenderOptions& options) {
    auto renderer = std::make_unique<MeshScatteringRenderer>(options);
    renderer->setMesh(mesh, model);
    renderer->setLights(m_impl->lights);
    m_impl->meshes.push_back(std::move(renderer));
    ++m_impl->sceneRevision;
    return *m_impl->meshes.back();
}

VolumeScatteringRenderer& HybridCompositor::addVolume(const Volume& volume, const glm::mat4& model,
                                                      const VolumeRenderOptions& options) {
    auto renderer = std::make_unique<VolumeScatteringRenderer>(options);
    renderer->setVolume(volume, model);
    renderer->setLights(m_impl->lights);
    m_impl->volumes.push_back(std::move(renderer));
    ++m_impl->sceneRevision;  // the shadow maps' view must hold the new volume too
    return *m_impl->volumes.back();
}

std::size_t HybridCompositor::meshCount() const { return m_impl->meshes.size(); }
std::size_t HybridCompositor::volumeCount() const { return m_impl->volumes.size(); }

MeshScatteringRenderer& HybridCompositor::mesh(std::size_t index) {
    if (index >= m_impl->meshes.size())
        throw Error(ErrorKind::InvalidArgument, "HybridCompositor::mesh: index " + std::to_string(index) +
                                                    " out of range (" + std::to_string(m_impl->meshes.size()) + " meshes)");
    return *m_impl->meshes[index];
}

VolumeScatteringRenderer& HybridCompositor::volume(std::size_t index) {
    if (index >= m_impl->volumes.size())
        throw Error(ErrorKind::InvalidArgument, "HybridCompositor::volume: index " + std::to_string(index) +
                                                    " out of range (" + std::to_string(m_impl->volumes.size()) + " volumes)");
    return *m_impl->volumes[index];
}

void HybridCompositor::setMeshTransform(std::size_t index, const glm::mat4& model) {
    mesh(index).setModelTransform(model);
    ++m_impl->sceneRevision;
}

void HybridCompositor::clear() {
    m_impl->meshes.clear();
    m_impl->volumes.clear();
    ++m_impl->sceneRevision;
}

void HybridCompositor::setLights(std::vector<Light> lights) {
    detail::validateLights(lights, "HybridCompositor::setLights");
    // The shadow maps see where the lights are, not how bright they are.
    if (detail::withUnitRadiance(lights) != detail::withUnitRadiance(m_impl->lights)) ++m_impl->sceneRevision;
    m_impl->lights = std::move(lights);
    for (auto& m : m_impl->meshes) m->setLights(m_impl->lights);
    for (auto& v : m_impl->volumes) v->setLights(m_impl->lights);
    for (auto& w : m_impl->walls) w->setLights(m_impl->lights);
}

const std::vector<Light>& HybridCompositor::lights() const { return m_impl->lights; }

void HybridCompositor::setOptions(const HybridOptions& options) {
    validate(options);
    if (options.shadowMapResolution != m_impl->options.shadowMapResolution) ++m_impl->sceneRevision;
    m_impl->options = options;
}

const HybridOptions& HybridCompositor::options() const { return m_impl->options; }
Bounds HybridCompositor::bounds() const { return m_impl->contentBounds(); }
const RenderStats& HybridCompositor::stats() const { return m_impl->stats; }

void HybridCompositor::render(const Camera& camera, RenderTarget& target) {
    Impl& r = *m_impl;
    r.updateWalls();
    for (auto& w : r.walls) w->setLights(r.lights);

    // 1. Meshes seen from the lights: they shadow the volumes' samples and every mesh surface
    //    (each mesh by the others: see SurfaceShadows::selfId).
    const bool shadowsInVolumes = r.options.meshShadowsInVolumes && !r.volumes.empty();
    const bool shadowsOnMeshes = r.options.meshShadowsOnMeshes && (r.meshes.size() > 1 || !r.walls.empty());
    const bool meshMaps = !r.meshes.empty() && (shadowsInVolumes || shadowsOnMeshes);
    if (meshMaps) r.updateMeshShadowMaps();
    for (auto& v : r.volumes) {
        detail::VolumeRendererAccess::setMeshShadows(*v, shadowsInVolumes && meshMaps ? &r.meshShadows : nullptr);
        detail::VolumeRendererAccess::updateLightVolumes(*v);
    }
    // 2. Every scattering volume tints and dims the light reaching meshes and walls.
    r.shareShadows(shadowsOnMeshes && meshMaps);

    // 3. Opaque surfaces with depth, then volumes back to front, each stopping at that depth.
    if (r.options.clearTarget) target.clear(r.options.background);
    if (!r.walls.empty()) {
        const auto start = std::chrono::steady_clock::now();
        for (auto& w : r.walls) w->render(camera, target);
        r.stats.record("cornell-box",
                       std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
    for (auto& m : r.meshes) m->render(camera, target);
    std::vector<VolumeScatteringRenderer*> order;
    for (auto& v : r.volumes) order.push_back(v.get());
    const glm::vec3 eye = camera.position();
    std::sort(order.begin(), order.end(), [&](VolumeScatteringRenderer* a, VolumeScatteringRenderer* b) {
        return glm::length(detail::VolumeRendererAccess::worldBounds(*a).center() - eye) >
               glm::length(detail::VolumeRendererAccess::worldBounds(*b).center() - eye);
    });
    for (VolumeScatteringRenderer* v : order) v->render(camera, target);
}

}  // namespace sss
