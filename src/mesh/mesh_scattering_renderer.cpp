#include "sss/mesh_scattering_renderer.h"

#include "util/format.h"

#include "core/light_geometry.h"
#include "lighting/light_uniforms.h"
#include "frame/pass_timer.h"
#include "mesh/blinn_phong_pass.h"
#include "mesh/combine_choice.h"
#include "mesh/combine_pass.h"
#include "mesh/gpu_mesh.h"
#include "mesh/light_buffer_pass.h"
#include "mesh/near_field.h"
#include "mesh/scattering_map_pass.h"
#include "mesh/renderer_access.h"
#include "mesh/textured_material.h"
#include "mesh/near_field_cache.h"
#include "mesh/vertex_estimate_pass.h"
#include "sss/error.h"
#include "sss/option_table.h"
#include "sss/timing.h"

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cmath>
#include <optional>
#include <string>

namespace sss {
namespace {


// What the light buffer depends on.
struct LightBufferInputs {
    std::uint64_t meshGeneration = 0;
    glm::mat4 model{1.0f};
    std::vector<Light> lights;
    int resolution = 0;
    std::uint64_t texturedMaterial = 0;  // the material's generation when textured (ln gathered)
    bool operator==(const LightBufferInputs&) const = default;
};

// What the profile's constants and the disk sampling depend on: not the lights, so a light change
// skips their plane integrals (about 0.3 s of CPU for the calibrated profile).
struct ProfileInputs {
    std::uint64_t meshGeneration = 0, materialGeneration = 0;
    glm::mat4 model{1.0f};
    double millimetresPerUnit = 0.0;
    float sampleRadius = 0.0f, spread = 0.0f, nearField = 0.0f;
    int lightMapResolution = 0;
    ScatteringProfile profile = ScatteringProfile::Calibrated;
    bool operator==(const ProfileInputs&) const = default;
};

// What the scattering maps depend on (besides the light buffer).
struct ScatteringMapInputs {
    LightBufferInputs lightBuffer;
    std::uint64_t materialGeneration = 0;
    int cameras = 0, samples = 0, resolution = 0;
    double millimetresPerUnit = 0.0;
    float sampleRadius = 0.0f, spread = 0.0f, nearField = 0.0f, nearFieldSpacing = 0.0f;
    ScatteringProfile profile = ScatteringProfile::Calibrated;
    bool vertexEstimate = false;  // MeshCombine::VertexEstimate: per vertex, no maps
    std::uint64_t shadowRevision = 0;  // hybrid scenes: meshes and volumes between lights and mesh
    bool operator==(const ScatteringMapInputs&) const = default;
};


}  // namespace

void validate(const BlinnPhongMaterial& m) {
    auto bad = [](glm::vec3 c) {
        return !(c.x >= 0 && c.y >= 0 && c.z >= 0) || !std::isfinite(c.x + c.y + c.z);
    };
    if (bad(m.diffuse) || bad(m.specular) || bad(m.ambient))
        throw Error(ErrorKind::InvalidArgument, "BlinnPhongMaterial: colours must be finite and >= 0");
    if (!(m.shininess > 0.0f) || !std::isfinite(m.shininess))
        throw Error(ErrorKind::InvalidArgument, "BlinnPhongMaterial", "shininess",
                    "must be finite and > 0, got " + detail::formatNumber(m.shininess));
}

void validate(const MeshRenderOptions& o) {
    static_assert(detail::kMaxScatteringCameras == 32, "the option table says cameras in 1..32");
    validateOptionRanges(o);
}

struct MeshScatteringRenderer::Impl {
    MeshRenderOptions options;
    BlinnPhongMaterial material;
    ScatteringMaterial scatteringMaterial;
    std::optional<TexturedScattering> texturedMaterial;     // replaces scatteringMaterial when set
    std::optional<detail::TexturedMaterialGpu> texturedGpu;  // its textures, once a mesh is set
    std::shared_ptr<const Image8> meshBaseColour;
    bool meshHasTexcoords = false;
    double texcoordDensity = 0.0;  // meanTexelDensity of a 1 x 1 texture, per model unit
    std::uint64_t materialGeneration = 1;
    std::vector<Light> lights{DirectionalLight{}};
    glm::mat4 model{1.0f};
    std::optional<detail::GpuMesh> mesh;
    std::uint64_t meshGeneration = 0;
    RenderStats stats;
    detail::PassTimer passTimer{stats};
    // Passes are built on first use, so a Blinn-Phong-only renderer compiles no scattering shaders.
    std::optional<detail::BlinnPhongPass> blinnPhong;
    std::optional<detail::LightBufferPass> lightBuffer;
    std::optional<detail::ScatteringMapPass> scatteringMaps;
    std::optional<detail::CombinePass> combine;
    std::optional<detail::VertexRadiosityPass> vertexRadiosity;  // built with the mesh's scattering
    std::optional<detail::VertexEstimatePass> vertexEstimate;    // MeshCombine::VertexEstimate
    std::optional<detail::NearFieldCache> nearFieldCache;        // of the mesh; evaluated with nearFieldSpacing
    detail::VertexAdjacency adjacency;  // of the mesh, for the vertex-radiosity pass
    float surfaceEdgeLength = 0.0f;     // of the mesh, in its own units (MeshCombine::Automatic)
    int vertexRadiosityFrames = -1;
    int pointsRadiosityFrames = -1;  // the vertex estimate's frames the near field's points hold (-1: none)
    std::optional<ScatteringMapInputs> vertexRadiosityInputs;
    detail::MapLookupSettings vertexRadiosityLookup;
    detail::ScatteringCameras cameras;
    std::optional<LightBufferInputs> lightBufferInputs;
    std::optional<ScatteringMapInputs> scatteringMapInputs;
    // The lights at the radiance the maps (or the vertex estimate) and the near field's points were
    // accumulated with: a change of radiance alone, alike for every light, keeps them, and the
    // combine scales what they hold (detail::commonRadianceScale).
    std::vector<Light> mapLights;
    std::optional<detail::SurfaceShadows> shadows;  // set by HybridCompositor
    // Derived when ProfileInputs change (the profile's plane integrals are too slow for every frame).
    DipoleConstants dipole;
    detail::ScatteringSampling sampling;
    detail::NearFieldTable nearField;
    std::optional<ProfileInputs> profileInputs;  // what dipole and sampling were derived for
    glm::dvec3 environmentReflectance{0.0};

    // The material the profile, the sampling and the Automatic combine are derived for: a
    // textured material's widest texel, else the uniform material.
    const ScatteringMaterial& profileMaterial() const {
        return texturedGpu ? texturedGpu->widestMaterial() : scatteringMaterial;
    }

    // Uploads the textured material for the current mesh and profile (if it changed).
    void updateTexturedMaterial() {
        if (!texturedMaterial || !mesh) return;
        if (texturedGpu && texturedGpu->profile() == options.profile) return;
        if (!meshHasTexcoords)
            throw Error(ErrorKind::InvalidArgument,
                        "MeshScatteringRenderer: the textured material \"" + texturedMaterial->name +
                            "\" needs texture coordinates, and the mesh has none");
        const std::shared_ptr<const Image8>& image =
            texturedMaterial->reflectance ? texturedMaterial->reflectance : meshBaseColour;
        if (!image)
            throw Error(ErrorKind::InvalidArgument, "MeshScatteringRenderer: the textured material \"" +
                                                        texturedMaterial->name +
                                                        "\" has no reflectance texture and the mesh no base colour");
        texturedGpu.emplace(*texturedMaterial, *image, options.profile);
        ++materialGeneration;
    }

    // The textured material's texture density in world units under the current model transform.
    void updateTexcoordDensity() {
        if (!texturedGpu) return;
        const double scale = std::cbrt(std::abs(glm::determinant(glm::dmat3(glm::dmat4(model)))));
        texturedGpu->setTexcoordDensity(scale > 0.0 ? texcoordDensity / scale : 0.0);
        texturedGpu->prepareSurface(options.millimetresPerUnit);
    }

    // The profile's constants and the disk sampling for the current inputs.
    void deriveProfile() {
        dipole = deriveDipoleConstants(profileMaterial(), options.millimetresPerUnit, options.profile);
        // The widest channel (smallest sigma_tr) sets the spread; sigma_tr = 0 (no absorption)
        // falls back to the reduced extinction, the next shortest length scale.
        double sigma = std::min({dipole.sigmaTr.x, dipole.sigmaTr.y, dipole.sigmaTr.z});
        if (!(sigma > 0.0)) sigma = std::min({dipole.sigmaTPrime.x, dipole.sigmaTPrime.y, dipole.sigmaTPrime.z});
        sampling.sigmaStar = static_cast<float>(sigma / options.spread);
        // The near field falls off over a few diffusion lengths D = 1 / (3 sigma_t'), but the light
        // buffer cannot resolve distances below about a texel: take whichever is wider.
        const auto [centre, worldRadius] = detail::worldSphere(mesh->bounds, model);
        const double texel = 2.0 * worldRadius / options.lightMapResolution;
        const double sigmaT = std::min({dipole.sigmaTPrime.x, dipole.sigmaTPrime.y, dipole.sigmaTPrime.z});
        sampling.sigmaNear = static_cast<float>(std::max(static_cast<double>(sampling.sigmaStar), std::min(sigmaT, 1.0 / texel)));
        sampling.diskRadius = options.sampleRadius > 0.0f ? options.sampleRadius : 3.0f / sampling.sigmaStar;
        if (options.profile == ScatteringProfile::Calibrated) {
            // 3 / sigma* keeps only 95.9 % of ketchup R's profile (head-on): widen the default disk
            // until every channel keeps 99.9 % (the exponential sampling barely changes), then scale
            // each channel by what it still misses, exact for a flat surface lit head-on.
            const glm::dvec3 whole = dipolePlaneIntegral(dipole, 1.0);
            auto keptShare = [&](double radius) {
                const glm::dvec3 kept = dipolePlaneIntegral(dipole, 1.0, radius);
                double share = 1.0;
                for (int c = 0; c < 3; ++c)
                    if (whole[c] > 0.0) share = std::min(share, kept[c] / whole[c]);
                return share;
            };
            if (options.sampleRadius <= 0.0f) {
                for (int i = 0; i < 12 && keptShare(sampling.diskRadius) < 0.999; ++i) sampling.diskRadius *= 1.25f;
                // The exponential sampler must reach the widened disk: without absorption (spectralon,
                // sigma_tr = 0) the disk grows to 43 / sigma*, where exp(-sigma* r) gives rare samples
                // weights of e^40 (sparkles). Keep the edge at three of the sampler's lengths.
                sampling.sigmaStar = std::min(sampling.sigmaStar, 3.0f / sampling.diskRadius);
            }
            const glm::dvec3 kept = dipolePlaneIntegral(dipole, 1.0, sampling.diskRadius);
            for (int c = 0; c < 3; ++c)
                if (kept[c] > 0.0) dipole.profileScale[c] *= whole[c] / kept[c];
        }
        // The near field ends inside the disk: beyond it the profile is what the disk keeps.
        const double edge = surfaceEdgeLength * detail::largestScale(model);
        sampling.nearRadius = detail::nearFieldRadius(options.nearField, edge, edgeToDiffusionLength(), sampling.diskRadius);
        nearField = detail::tabulateNearField(dipole, sampling.nearRadius, edge);
        if (texturedGpu)
            detail::tabulateTexturedNearFieldShare(nearField, texturedGpu->widestMaterial(), options.millimetresPerUnit,
                                                   options.profile);
        environmentReflectance = options.profile == ScatteringProfile::Calibrated
                                     ? profileDiffuseReflectanceUniform(dipole)
                                     : dipoleDiffuseReflectance(dipole);
    }

    void updateProfile() {
        const ProfileInputs inputs{meshGeneration,       materialGeneration, model,
                                   options.millimetresPerUnit, options.sampleRadius, options.spread,
                                   options.nearField,          options.lightMapResolution, options.profile};
        if (profileInputs == inputs) return;
        timed("profile", [&] { deriveProfile(); });  // CPU: the profile's plane integrals
        profileInputs = inputs;
    }

    template <typename Work>
    void timed(const char* pass, Work&& work) {
        passTimer.time(pass, {options.finishEachPass, options.gpuPassTimes}, std::forward<Work>(work));
    }

    double edgeToDiffusionLength() const {
        if (!mesh) return 0.0;
        return detail::edgeToDiffusionLength(surfaceEdgeLength * detail::largestScale(model), profileMaterial(),
                                             options.millimetresPerUnit);
    }

    MeshCombine activeCombine() const {
        if (!mesh) return MeshCombine::PerPixel;
        if (options.combine != MeshCombine::Automatic) return options.combine;
        const double edgeOverRadius = surfaceEdgeLength / std::max(mesh->bounds.radius(), 1e-12f);
        return detail::resolveCombine(options.combine, edgeToDiffusionLength(), options.nearField, edgeOverRadius);
    }

    ScatteringMapInputs currentMapInputs() const {
        return {{meshGeneration, model, detail::withUnitRadiance(lights), options.lightMapResolution,
                 texturedGpu ? materialGeneration : 0},
                materialGeneration,
                options.cameras,
                options.samples,
                options.mapResolution,
                options.millimetresPerUnit,
                options.sampleRadius,
                options.spread,
                options.nearField,
                options.nearFieldSpacing,
                options.profile,
                activeCombine() == MeshCombine::VertexEstimate,
                shadows ? shadows->revision() : 0};
    }

    // Frames accumulated by whichever pass estimates the radiosity (-1: none yet).
    int radiosityFrames() const {
        if (activeCombine() == MeshCombine::VertexEstimate) return vertexEstimate ? vertexEstimate->frames() : -1;
        return scatteringMaps ? scatteringMaps->frames() : -1;
    }

    bool mapsHoldLights() const { return detail::commonRadianceScale(mapLights, lights).has_value(); }

    bool mapsConverged() const {
        return scatteringMapInputs == currentMapInputs() && mapsHoldLights() &&
               radiosityFrames() >= options.accumulationFrames;
    }

    bool usesNearFieldCache() const {
        return activeCombine() == MeshCombine::VertexEstimate && nearField.radius > 0.0f && options.nearFieldSpacing > 0.0f;
    }

    void evaluateNearFieldCache() {
        const float texel = lightBuffer->texelWorld(*mesh, model);
        const float spacing = options.nearFieldSpacing * texel / std::max(detail::largestScale(model), 1e-30f);
        nearFieldCache->evaluate({*mesh, model, mapLights, *lightBuffer, shadows ? &*shadows : nullptr, nearField,
                                  static_cast<float>(profileMaterial().eta), spacing});
    }

    // Passes 1 and 2, each only when something it depends on changed.
    void updateScattering() {
        const ScatteringMapInputs inputs = currentMapInputs();
        if (lightBufferInputs != inputs.lightBuffer) {
            if (!lightBuffer) lightBuffer.emplace();
            timed("light-buffer", [&] {
                lightBuffer->run(*mesh, model, lights, options.lightMapResolution, texturedGpu ? &*texturedGpu : nullptr);
            });
            lightBufferInputs = inputs.lightBuffer;
        }
        if (scatteringMapInputs != inputs || !mapsHoldLights()) {
            mapLights = lights;
            if (inputs.vertexEstimate) {
                if (!vertexEstimate) vertexEstimate.emplace(adjacency.vertexCount());
                vertexEstimate->reset();
            } else {
                if (!scatteringMaps || scatteringMaps->cameras() != options.cameras) scatteringMaps.emplace(options.cameras);
                scatteringMaps->reset(options.mapResolution);
            }
            cameras = detail::makeScatteringCameras(options.cameras, mesh->bounds);
            scatteringMapInputs = inputs;
            updateProfile();
            if (usesNearFieldCache()) {
                timed("near-field", [&] { evaluateNearFieldCache(); });
                pointsRadiosityFrames = -1;
            }
        }
        if (radiosityFrames() >= options.accumulationFrames) return;
        sampling.samplesPerLight = std::max(1, options.samples / std::max<int>(1, static_cast<int>(lights.size())));
        const detail::RadiosityEstimateInputs estimate{mapLights,
                                                       lightBuffer->viewProjections(),
                                                       lightBuffer->positions(),
                                                       lightBuffer->normals(),
                                                       dipole,
                                                       sampling,
                                                       shadows ? &*shadows : nullptr,
                                                       texturedGpu ? &*texturedGpu : nullptr,
                                                       &lightBuffer->logGathered(),
                                                       options.millimetresPerUnit};
        if (inputs.vertexEstimate)
            timed("vertex-estimate", [&] {
                vertexEstimate->accumulate(*mesh, model, estimate, nearField, lightBuffer->texelWorld(*mesh, model));
            });
        else
            timed("scattering-maps", [&] { scatteringMaps->accumulate({*mesh, model, cameras, estimate}); });
    }
};

MeshScatteringRenderer::MeshScatteringRenderer(const MeshRenderOptions& options) {
    validate(options);
    m_impl = std::make_unique<Impl>();
    m_impl->options = options;
}

MeshScatteringRenderer::~MeshScatteringRenderer() = default;
MeshScatteringRenderer::MeshScatteringRenderer(MeshScatteringRenderer&&) noexcept = default;
MeshScatteringRenderer& MeshScatteringRenderer::operator=(MeshScatteringRenderer&&) noexcept = default;

void MeshScatteringRenderer::setMesh(const Mesh& mesh, const glm::mat4& model) {
    if (mesh.triangleCount() == 0)
        throw Error(ErrorKind::InvalidArgument, "MeshScatteringRenderer::setMesh: the mesh has no triangles");
    m_impl->mesh = detail::GpuMesh::upload(mesh);
    m_impl->vertexRadiosity.reset();
    m_impl->vertexEstimate.reset();
    m_impl->nearFieldCache.emplace(mesh);
    m_impl->adjacency = detail::buildVertexAdjacency(mesh);
    m_impl->surfaceEdgeLength = detail::surfaceEdgeLength(mesh);
    ++m_impl->meshGeneration;
    m_impl->model = model;
    m_impl->meshBaseColour = mesh.baseColour();
    m_impl->meshHasTexcoords = !mesh.texcoords().empty();
    m_impl->texcoordDensity = detail::meanTexelDensity(mesh, glm::mat4(1.0f), 1, 1);
    m_impl->texturedGpu.reset();
    m_impl->updateTexturedMaterial();
}

void MeshScatteringRenderer::setModelTransform(const glm::mat4& model) { m_impl->model = model; }

void MeshScatteringRenderer::setMaterial(const BlinnPhongMaterial& material) {
    validate(material);
    m_impl->material = material;
}

void MeshScatteringRenderer::setScatteringMaterial(const ScatteringMaterial& material) {
    material.validate();
    m_impl->scatteringMaterial = material;
    m_impl->texturedMaterial.reset();
    m_impl->texturedGpu.reset();
    ++m_impl->materialGeneration;
}

void MeshScatteringRenderer::setScatteringMaterial(const TexturedScattering& material) {
    material.validate();
    m_impl->texturedMaterial = material;
    m_impl->texturedGpu.reset();
    ++m_impl->materialGeneration;
    m_impl->updateTexturedMaterial();
}

bool MeshScatteringRenderer::converged() const { return m_impl->mapsConverged(); }

void MeshScatteringRenderer::setLights(std::vector<Light> lights) {
    detail::validateLights(lights, "MeshScatteringRenderer::setLights");
    m_impl->lights = std::move(lights);
}

void MeshScatteringRenderer::setOptions(const MeshRenderOptions& options) {
    validate(options);
    m_impl->options = options;
}

const MeshRenderOptions& MeshScatteringRenderer::options() const { return m_impl->options; }
const RenderStats& MeshScatteringRenderer::stats() const { return m_impl->stats; }
MeshCombine MeshScatteringRenderer::activeCombine() const { return m_impl->activeCombine(); }
double MeshScatteringRenderer::edgeToDiffusionLength() const { return m_impl->edgeToDiffusionLength(); }

void MeshScatteringRenderer::render(const Camera& camera, RenderTarget& target) {
    if (!m_impl->mesh)
        throw Error(ErrorKind::InvalidArgument, "MeshScatteringRenderer::render: no mesh set (call setMesh first)");
    Impl& r = *m_impl;
    if (r.options.shading == MeshShading::BlinnPhong) {
        if (!r.blinnPhong) r.blinnPhong.emplace();
        r.timed("blinn-phong", [&] {
            target.bindForDrawing();
            r.blinnPhong->run({*r.mesh, r.model, r.material, r.lights, camera, target.aspect(),
                               r.shadows ? &*r.shadows : nullptr});
        });
        return;
    }
    r.updateTexturedMaterial();
    r.updateTexcoordDensity();
    r.updateScattering();
    if (!r.combine) r.combine.emplace();
    const MeshCombine combine = r.activeCombine();
    const bool vertexEstimate = combine == MeshCombine::VertexEstimate;
    // Bias and shrink are given in texels of the scattering maps; convert with the maps' extent
    // (2 radii across, 3 radii of depth; see makeScatteringCameras).
    const float texels = static_cast<float>(r.options.mapResolution);
    const float radius = std::max(r.mesh->bounds.radius(), 1e-6f) * 1.01f;
    detail::CombineSettings settings;
    settings.eta = static_cast<float>(r.profileMaterial().eta);
    settings.lookup.depthBias = r.options.depthBias * 2.0f / (3.0f * texels);
    settings.lookup.seamShrink = r.options.seamShrink * 2.0f * radius / texels;
    settings.specularStrength = r.options.specular;
    settings.shininess = r.options.shininess;
    settings.environment = r.options.environment * glm::vec3(r.environmentReflectance);
    settings.dipole = r.dipole;
    if (vertexEstimate) settings.nearField = r.nearField;
    if (r.usesNearFieldCache()) settings.nearFieldCache = &*r.nearFieldCache;
    settings.perVertex = combine != MeshCombine::PerPixel;
    settings.material = r.texturedGpu ? &*r.texturedGpu : nullptr;
    settings.millimetresPerUnit = r.options.millimetresPerUnit;
    // The vertices' radiosity follows the maps: once per accumulated frame.
    if (!vertexEstimate && !r.vertexRadiosity) r.vertexRadiosity.emplace(r.adjacency);
    if (!vertexEstimate &&
        (r.vertexRadiosityFrames != r.scatteringMaps->frames() || r.vertexRadiosityInputs != r.scatteringMapInputs ||
         r.vertexRadiosityLookup != settings.lookup)) {
        r.timed("vertex-radiosity", [&] { r.vertexRadiosity->run(*r.mesh, r.cameras, *r.scatteringMaps, settings.lookup); });
        r.vertexRadiosityFrames = r.scatteringMaps->frames();
        r.vertexRadiosityInputs = r.scatteringMapInputs;
        r.vertexRadiosityLookup = settings.lookup;
    }
    // Untextured, the near field's points hold the vertex estimate's radiosity as well.
    if (settings.nearFieldCache && !settings.material && r.pointsRadiosityFrames != r.vertexEstimate->frames()) {
        r.timed("near-field-radiosity", [&] { r.nearFieldCache->addRadiosity(*r.mesh, r.vertexEstimate->radiosity()); });
        r.pointsRadiosityFrames = r.vertexEstimate->frames();
    }
    r.timed("combine", [&] {
        target.bindForDrawing();
        r.combine->run({*r.mesh, r.model, r.cameras, vertexEstimate ? nullptr : &*r.scatteringMaps,
                        vertexEstimate ? r.vertexEstimate->radiosity() : r.vertexRadiosity->radiosity(), r.lights,
                        camera, target.aspect(), *r.lightBuffer, r.shadows ? &*r.shadows : nullptr,
                        vertexEstimate ? r.vertexEstimate->effective() : nullptr,
                        *detail::commonRadianceScale(r.mapLights, r.lights)},
                       settings);
    });
}

namespace detail {

void MeshRendererAccess::setShadows(MeshScatteringRenderer& r, const SurfaceShadows* shadows) {
    if (shadows)
        r.m_impl->shadows = *shadows;
    else
        r.m_impl->shadows.reset();
}

const GpuMesh* MeshRendererAccess::mesh(const MeshScatteringRenderer& r) {
    return r.m_impl->mesh ? &*r.m_impl->mesh : nullptr;
}

const glm::mat4& MeshRendererAccess::model(const MeshScatteringRenderer& r) { return r.m_impl->model; }

}  // namespace detail
}  // namespace sss
