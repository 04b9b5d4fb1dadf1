#include "volume/fluence_cache.h"

#include "core/light_geometry.h"
#include "gl/device.h"
#include "lighting/light_uniforms.h"
#include "lighting/texture_units.h"
#include "sss/error.h"
#include "sss/log.h"
#include "volume/clip_uniforms.h"

#include <glm/geometric.hpp>
#include <glm/gtx/component_wise.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <variant>

namespace sss::detail {

namespace {
constexpr int kSlotsPerCell = 23;            // volume/fluence_sums.glsl
constexpr std::int64_t kSlotBytes = 8;       // 64-bit fixed point
// Storage-buffer bindings the sums may be split over (volume/fluence_sums.glsl: 2, 5, 6, 7).
constexpr int kMaxSumsParts = 4;
constexpr GLuint kSumsBindings[kMaxSumsParts] = {2, 5, 6, 7};
constexpr std::int64_t kDirectMomentBytes = 16;  // per cell, m_directMoments
constexpr std::size_t kPhotonStateBytes = 80;
constexpr int kMaxPhotonSlots = 1 << 15;     // photons in flight at once (2.5 MiB of state)
constexpr int kStepsPerDispatch = 1024;      // as the path tracer: under llvmpipe's loop limit
// Fixed-point quanta per unit of a deposit (w s / majorant, at most 1): fine enough that rounding
// is far below the photons' own noise, coarse enough that every add stays in 32 bits.
constexpr float kQuantaPerUnit = 1048576.0f;
// Voxels per cell side at most: the weights' pass loops over a cell's voxels in one invocation,
// which llvmpipe stops after 65535 iterations.
constexpr int kMaxVoxelsPerCell = 32;
// Mip levels of the cache's textures at most (64 cells: 64, 32, 16, 8): the light's angular shape
// is read coarser while few photons have arrived (FluenceCache::poolingLevels).
constexpr int kMaxLevels = 4;
// Photons per finest cell (photons over cells, medium or not) from which a cell's own fluence,
// and its own angular shape, are read unpooled; the default 2^21 photons give 64^3 cells 8. Finer
// grids hold fewer per cell, also once refined (docs/multiple-scattering.md, "Finer cells").
constexpr float kPhotonsForOwnFluence = 8.0f;
constexpr float kPhotonsForOwnShape = 64.0f;
// The narrowest filter of the finest cells' fluence (fluence_denoise.comp), in cells: at 0.35 a
// neighbour's weight is exp(-1 / (2 0.35^2)) = 1.7 %, and at twice it one two cells away.
constexpr float kLeastSigma = 0.35f;
// The widest spatial sigma of that filter: its 5^3 window holds little more.
constexpr float kWidestSigma = 2.2f;

float largestChannel(glm::vec3 c) { return std::max({c.x, c.y, c.z}); }

// Photons in flight at once: kMaxPhotonSlots, or fewer where their states would not fit one
// storage block. A power of two, so that a frame's photons (a power of two at the defaults) share
// the slots evenly and the cache stays the same whatever the slots.
int photonSlotsWithin(std::int64_t storageBlockBytes) {
    int slots = kMaxPhotonSlots;
    const auto bytes = [](int n) { return static_cast<std::int64_t>(n * kPhotonStateBytes); };
    while (slots > 1 && storageBlockBytes > 0 && bytes(slots) > storageBlockBytes) slots /= 2;
    return slots;
}

// One invocation per cell of a grid `cells` wide, in the cache passes' 4^3 workgroups.
void dispatchOverCells(glm::ivec3 cells) {
    glDispatchCompute(static_cast<GLuint>((cells.x + 3) / 4), static_cast<GLuint>((cells.y + 3) / 4),
                      static_cast<GLuint>((cells.z + 3) / 4));
}

// Each of p's samplers on its own unit from firstUnit on, with its texture bound there.
void bindSamplers(const gl::Program& p, int firstUnit,
                  std::initializer_list<std::pair<const char*, const gl::Texture*>> samplers) {
    int unit = firstUnit;
    for (const auto& [name, texture] : samplers) {
        p.set(name, unit);
        texture->bind(static_cast<GLuint>(unit++));
    }
}

// Image units 0..count - 1 left unbound after a pass.
void unbindImages(GLuint count) {
    for (GLuint unit = 0; unit < count; ++unit) glBindImageTexture(unit, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
}

// The light volumes the direct light sums (one per light; none before they exist).
int directLightCount(const FluenceCacheInputs& in) {
    return in.lightVolumes ? static_cast<int>(std::min(in.lightVolumes->size(), in.lights.size())) : 0;
}

// A light as photons leave it, in model space.
struct Emitter {
    glm::vec4 modelVector;  ///< w 0: unit direction towards the light; w 1: position
    glm::vec3 power;        ///< into the box, rgb
    float coneCosine;       ///< point lights: the cone of directions that reach the box
    const Light* light;
};

// Each light's power into the box, in model space: a directional beam through a disk of the
// bounding sphere's radius; a point light's intensity (falloff in world units, so divided by the
// model's mean scale squared) over the cone of directions towards the sphere. Black lights are
// left out.
std::vector<Emitter> emittersOf(const FluenceCacheInputs& in, glm::vec3 centre, float radius) {
    const glm::mat4 worldToModel = glm::inverse(in.model);
    const glm::mat3 worldToModelLinear(worldToModel);
    const float meanScale = std::cbrt(std::abs(glm::determinant(glm::mat3(in.model))));
    std::vector<Emitter> emitters;
    for (const Light& light : in.lights) {
        const glm::vec3 radiance = lightRadiance(light);
        if (!(largestChannel(radiance) > 0.0f)) continue;
        if (const auto* d = std::get_if<DirectionalLight>(&light)) {
            const glm::vec3 towards = glm::normalize(worldToModelLinear * -glm::normalize(d->direction));
            emitters.push_back({glm::vec4(towards, 0.0f), radiance * std::numbers::pi_v<float> * radius * radius, 1.0f,
                                &light});
        } else {
            const glm::vec3 position(worldToModel * glm::vec4(*lightPosition(light), 1.0f));
            const float distance = glm::length(position - centre);
            const float coneCosine =
                distance > radius ? std::sqrt(std::max(0.0f, 1.0f - (radius / distance) * (radius / distance))) : -1.0f;
            const float solidAngle = 2.0f * std::numbers::pi_v<float> * (1.0f - coneCosine);
            emitters.push_back({glm::vec4(position, 1.0f), radiance / (meanScale * meanScale) * solidAngle, coneCosine,
                                &light});
        }
    }
    return emitters;
}
}  // namespace

std::int64_t fluenceCacheCellsPerPart(std::int64_t storageBlockBytes) {
    // Whole groups of 32 cells: each part then starts 32 x 184 = 23 x 256 bytes after the last,
    // a multiple of any GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT (at most 256).
    constexpr std::int64_t kGroup = 32;
    const std::int64_t wrapSafe = std::min<std::int64_t>(storageBlockBytes, std::int64_t{1} << 31);
    return std::max<std::int64_t>(kGroup, wrapSafe / (kSlotsPerCell * kSlotBytes) / kGroup * kGroup);
}

std::int64_t maxFluenceCacheCells(std::int64_t storageBlockBytes) {
    return std::min(kMaxSumsParts * fluenceCacheCellsPerPart(storageBlockBytes),
                    std::min<std::int64_t>(storageBlockBytes, std::int64_t{1} << 31) / kDirectMomentBytes);
}

glm::ivec3 fluenceCacheCells(glm::ivec3 dims, glm::vec3 boxSize, int resolution, std::int64_t maxCells) {
    const float longest = std::max({boxSize.x, boxSize.y, boxSize.z});
    for (;; --resolution) {
        glm::ivec3 cells;
        for (int a = 0; a < 3; ++a)
            cells[a] = std::clamp(static_cast<int>(std::lround(static_cast<float>(resolution) * boxSize[a] / longest)),
                                  (dims[a] + kMaxVoxelsPerCell - 1) / kMaxVoxelsPerCell, dims[a]);
        if (resolution <= 1 || std::int64_t{cells.x} * cells.y * cells.z <= maxCells) return cells;
    }
}

FluenceCache::FluenceCache(VolumeReconstruction reconstruction)
    : m_reconstruction(reconstruction),
      m_denoiseProgram(gl::Program::link({{GL_COMPUTE_SHADER, "volume/fluence_denoise.comp"}})),
      m_finestProgram(gl::Program::link({{GL_COMPUTE_SHADER, "volume/fluence_finest.comp"}})),
      m_viewProgram(gl::Program::link({{GL_COMPUTE_SHADER, "volume/fluence_view.comp"}})) {
    const std::uint32_t zero[2] = {0, 0};
    m_status = gl::Buffer::create(sizeof(zero), zero, GL_DYNAMIC_STORAGE_BIT, "fluence-cache status");
    m_resumable = gl::currentDeviceIsSoftware();
    m_storageBlockBytes = gl::storageBlockLimit();
    m_cellsPerPart = fluenceCacheCellsPerPart(m_storageBlockBytes);
    m_photonSlots = photonSlotsWithin(m_storageBlockBytes);
}

ShaderDefines FluenceCache::defines() const {
    return {{"MAX_LIGHTS", std::to_string(kMaxLights)},
            {"DIRECT_LIGHTS", std::to_string(m_variant.directLights)},
            {"MESH_SHADOWS", m_variant.meshShadows ? "1" : "0"},
            {"BRICK_VOXELS", std::to_string(kBrickVoxels)},
            {"CUBIC_RECONSTRUCTION", cubicReconstructionDefine(m_reconstruction)},
            {"SUMS_PARTS", std::to_string(m_variant.sumsParts)}};
}

const gl::Program& FluenceCache::photonProgram() {
    return gl::linkedOnce(m_photonPrograms, m_variant, "volume/fluence_photons.comp", [&] { return defines(); });
}

const gl::Program& FluenceCache::densityProgram() {
    return gl::linkedOnce(m_densityPrograms, m_variant, "volume/fluence_density.comp", [&] { return defines(); });
}

FluenceCache::ProgramVariant FluenceCache::variantFor(const FluenceCacheInputs& in) const {
    return {directLightCount(in), castsMeshShadows(in.meshShadows, in.lights.size()), sumsParts()};
}

int FluenceCache::sumsParts() const {
    const std::int64_t cells = std::int64_t{m_cells.x} * m_cells.y * m_cells.z;
    return static_cast<int>(std::max<std::int64_t>(1, (cells + m_cellsPerPart - 1) / m_cellsPerPart));
}

const gl::Program& FluenceCache::resolveProgram() {
    return gl::linkedOnce(m_resolvePrograms, sumsParts(), "volume/fluence_resolve.comp",
                          [&] { return ShaderDefines{{"SUMS_PARTS", std::to_string(sumsParts())}}; });
}

void FluenceCache::bindSums() const {
    const int parts = sumsParts();
    const std::int64_t partBytes = m_cellsPerPart * kSlotsPerCell * kSlotBytes;
    for (int k = 0; k < parts; ++k) {
        const std::int64_t offset = k * partBytes;
        const std::int64_t bytes = std::min<std::int64_t>(partBytes, static_cast<std::int64_t>(m_sums.size()) - offset);
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, kSumsBindings[k], m_sums.id(), static_cast<GLintptr>(offset),
                          static_cast<GLsizeiptr>(bytes));
    }
}

void FluenceCache::unbindSums() const {
    for (int k = 0; k < sumsParts(); ++k) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kSumsBindings[k], 0);
}

void FluenceCache::restart(const FluenceCacheInputs& in, glm::ivec3 cells, bool sameDensityInputs) {
    const std::size_t count = static_cast<std::size_t>(cells.x) * cells.y * cells.z;
    if (static_cast<std::int64_t>(count) > maxFluenceCacheCells(m_storageBlockBytes))
        throw Error(ErrorKind::GpuLimit, "multiple-scattering cache: " + std::to_string(count) + " cells exceed the " +
                                             std::to_string(maxFluenceCacheCells(m_storageBlockBytes)) +
                                             " that GL_MAX_SHADER_STORAGE_BLOCK_SIZE (" +
                                             std::to_string(m_storageBlockBytes) + " bytes) allows");
    m_lights = in.lights;
    if (cells != m_cells) {
        sameDensityInputs = false;
        m_sums = gl::Buffer::create(count * kSlotsPerCell * 2 * sizeof(std::uint32_t), nullptr, 0, "fluence-cache sums");
        m_weights = gl::Buffer::create(count * sizeof(float), nullptr, 0, "fluence-cache cell weights");
        m_directMoments = gl::Buffer::create(count * 4 * sizeof(float), nullptr, 0, "fluence-cache direct-light moments");
        m_levels = std::min(kMaxLevels, 1 + static_cast<int>(std::log2(static_cast<float>(glm::compMax(cells)))));
        m_fluence = gl::Texture::create3D(GL_RGBA32F, cells, "fluence cache", m_levels);
        m_fluxRed = gl::Texture::create3D(GL_RGBA32F, cells, "fluence-cache red flux", m_levels);
        m_fluxGreen = gl::Texture::create3D(GL_RGBA32F, cells, "fluence-cache green flux", m_levels);
        m_fluxBlue = gl::Texture::create3D(GL_RGBA32F, cells, "fluence-cache blue flux", m_levels);
        m_secondMoment = gl::Texture::create3D(GL_RGBA32F, cells, "fluence-cache second moment", m_levels);
        m_directSlope = gl::Texture::create3D(GL_RGBA32F, cells, "fluence-cache direct-light slope");
        m_onceMoments = gl::Texture::create3D(GL_RGBA32F, cells, "fluence-cache once-scattered moments", m_levels);
        m_onceTimesDirect =
            gl::Texture::create3D(GL_RGBA32F, cells, "fluence-cache once-scattered direct-light moments", m_levels);
        m_denoised = gl::Texture::create3D(GL_RGBA32F, cells, "fluence-cache filtered fluence");
        m_denoisedSlope = gl::Texture::create3D(GL_RGBA32F, cells, "fluence-cache filtered direct-light slope");
        for (const gl::Texture* t : {&m_fluence, &m_fluxRed, &m_fluxGreen, &m_fluxBlue, &m_secondMoment})
            t->setFilter(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR);
        for (const gl::Texture* t : {&m_onceMoments, &m_onceTimesDirect})
            t->setFilter(GL_NEAREST_MIPMAP_NEAREST, GL_NEAREST);  // texelFetch'd, at one level each
        m_directSlope.setFilter(GL_LINEAR, GL_LINEAR);
        m_cells = cells;
    }
    m_variant = variantFor(in);
    const std::uint32_t zero = 0;
    glClearNamedBufferData(m_sums.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    const float black[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    for (const gl::Texture* t : {&m_fluence, &m_fluxRed, &m_fluxGreen, &m_fluxBlue, &m_secondMoment})
        for (int level = 0; level < m_levels; ++level) glClearTexImage(t->id(), level, GL_RGBA, GL_FLOAT, black);
    glClearTexImage(m_directSlope.id(), 0, GL_RGBA, GL_FLOAT, black);
    m_photons = 0;
    ++m_revision;
    m_cellVolume = glm::compMul(in.volume.box.size()) / static_cast<float>(count);
    m_box = in.volume.box;
    if (!sameDensityInputs) computeWeights(in);
}

void FluenceCache::computeWeights(const FluenceCacheInputs& in) {
    const gl::Program& p = densityProgram();
    setMediumUniforms(p, in);
    const glm::vec3 voxelSize = in.volume.box.size() / glm::vec3(in.volume.dims);
    p.set("voxelVolume", voxelSize.x * voxelSize.y * voxelSize.z);
    p.set("cacheCells", m_cells);
    bindDirectLight(p, in);
    p.set("majorants", 2);
    in.volume.texture.bind(0);
    in.transferFunction.bind(1);
    in.majorants.bind(2);
    m_weights.bindStorage(3);
    m_directMoments.bindStorage(4);
    p.use();
    dispatchOverCells(m_cells);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, 0);
}

std::vector<float> directLightWeights(const std::vector<Light>& lights, const glm::mat4& model, const Bounds& box) {
    const glm::vec3 centre(model * glm::vec4(box.center(), 1.0f));
    std::vector<float> weights;
    for (const Light& light : lights) {
        const glm::vec3 radiance = lightRadiance(light);
        float weight = (radiance.x + radiance.y + radiance.z) / 3.0f;
        if (const auto position = lightPosition(light)) {
            const glm::vec3 offset = *position - centre;
            weight /= std::max(glm::dot(offset, offset), 1e-8f);
        }
        weights.push_back(weight);
    }
    return weights;
}

void FluenceCache::bindDirectLight(const gl::Program& p, const FluenceCacheInputs& in) const {
    const std::vector<float> weights = directLightWeights(in.lights, in.model, in.volume.box);
    if (m_variant.meshShadows) setMeshVisibilityUniforms(p, *in.meshShadows, in.lights);
    for (int i = 0; i < m_variant.directLights; ++i) {
        const std::string index = "[" + std::to_string(i) + "]";
        p.set("lightVolumes" + index, units::kLightVolumes + i);
        (*in.lightVolumes)[static_cast<std::size_t>(i)].bind(static_cast<GLuint>(units::kLightVolumes + i));
        p.set("directLightWeight" + index, weights[static_cast<std::size_t>(i)]);
    }
}

void FluenceCache::setMediumUniforms(const gl::Program& p, const FluenceCacheInputs& in) const {
    const Bounds& box = in.volume.box;
    p.set("volumeTexture", 0);
    p.set("transferFunction", 1);
    p.set("transferFunctionEntries", static_cast<float>(in.transferFunction.size().x));
    p.set("valueScaleOffset", in.volume.valueScaleOffset);
    p.set("boxMin", box.min);
    p.set("boxMax", box.max);
    p.set("voxelLength", in.volume.voxelLength);
    p.set("modelToWorld", in.model);
    setClipUniforms(p, in.clip, in.model, box);
}

void FluenceCache::setUniforms(const FluenceCacheInputs& in) {
    const gl::Program& p = photonProgram();
    const Bounds& box = in.volume.box;
    setMediumUniforms(p, in);
    p.set("majorants", 2);
    p.set("cellSize", box.size() * static_cast<float>(kBrickVoxels) / glm::vec3(in.volume.dims));
    p.set("phaseG", in.anisotropy);
    p.set("maxBounces", in.maxBounces);
    p.set("cacheCells", m_cells);
    p.set("sumsCellsPerPart", static_cast<unsigned>(m_cellsPerPart));
    p.set("depositScale", kQuantaPerUnit);
    const glm::vec3 centre = box.center();
    const float radius = 0.5f * glm::length(box.size());
    p.set("boxCentre", centre);
    p.set("boxRadius", radius);

    const std::vector<Emitter> emitters = emittersOf(in, centre, radius);
    m_powerUnit = 0.0f;
    for (const Emitter& e : emitters) m_powerUnit += largestChannel(e.power);
    float cumulative = 0.0f;
    for (std::size_t k = 0; k < emitters.size(); ++k) {
        const Emitter& e = emitters[k];
        const std::string i = "[" + std::to_string(k) + "]";
        cumulative += largestChannel(e.power) / m_powerUnit;
        p.set("lightModel" + i, e.modelVector);
        p.set("lightWeight" + i, e.power / largestChannel(e.power));
        p.set("lightPick" + i, k + 1 == emitters.size() ? 1.0f : cumulative);
        p.set("lightConeCosine" + i, e.coneCosine);
        p.set("lightShadowLayer" + i, static_cast<int>(e.light - in.lights.data()));
        setSpotConeUniforms(p, static_cast<int>(k), *e.light);
    }
    p.set("lightCount", static_cast<int>(emitters.size()));
}

void FluenceCache::add(const FluenceCacheInputs& in, int photons, std::uint64_t budget) {
    if (photons <= 0 || m_cells.x == 0) return;
    m_variant = variantFor(in);
    setUniforms(in);
    const gl::Program& p = photonProgram();
    const int slots = std::min(photons, m_photonSlots);
    const unsigned perSlot = static_cast<unsigned>((photons + slots - 1) / slots);
    if (m_photonStates.size() < static_cast<std::size_t>(slots) * kPhotonStateBytes)
        m_photonStates = gl::Buffer::create(static_cast<std::size_t>(m_photonSlots) * kPhotonStateBytes, nullptr, 0,
                                            "fluence-cache photon states");
    p.set("invocations", slots);
    p.set("photonsPerInvocation", perSlot);
    p.set("firstPhoton", static_cast<unsigned>(m_photons));
    p.set("stepsPerDispatch", m_resumable ? kStepsPerDispatch : std::numeric_limits<int>::max());
    bindDirectLight(p, in);
    in.volume.texture.bind(0);
    in.transferFunction.bind(1);
    in.majorants.bind(2);
    m_photonStates.bindStorage(0);
    m_status.bindStorage(1);
    bindSums();
    p.use();
    if (m_powerUnit > 0.0f) dispatchPhotons(slots);
    m_photons += static_cast<std::uint64_t>(slots) * perSlot;
    resolve();
    const PoolingLevels levels = poolingLevels(budget);
    const std::optional<int> filteredOn = denoise(levels.fluence);
    if (levels.shape > 0.0f || filteredOn) settle(levels.shape, filteredOn);
    glUseProgram(0);
    for (GLuint b = 0; b < 4; ++b) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, 0);
    unbindSums();
}

void FluenceCache::dispatchPhotons(int invocations) {
    const gl::Program& p = photonProgram();
    const std::uint32_t zero[2] = {0, 0};
    std::uint32_t status[2] = {0, 0};
    m_status.upload(0, sizeof(zero), zero);
    m_lastDispatches = 0;
    for (bool restart = true;; restart = false) {
        p.set("restart", restart ? 1 : 0);
        glDispatchCompute(static_cast<GLuint>((invocations + 63) / 64), 1, 1);
        ++m_lastDispatches;
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        if (!m_resumable) break;
        glGetNamedBufferSubData(m_status.id(), 0, sizeof(status), status);
        if (status[0] == 0) break;
        m_status.upload(0, sizeof(std::uint32_t), zero);
    }
    if (status[1] > 0)
        log(LogLevel::Warning, "FluenceCache: " + std::to_string(status[1]) +
                                   " photons were given up after 2^24 steps each (degenerate rays)");
}

FluenceCache::PoolingLevels FluenceCache::poolingLevels(std::uint64_t budget) const {
    if (m_photons == 0) return {};
    const float photons = static_cast<float>(m_photons);
    const float cells = static_cast<float>(m_cells.x) * static_cast<float>(m_cells.y) * static_cast<float>(m_cells.z);
    // Each level up has 8 times the photons per cell.
    const float forBudget = m_photons < budget ? std::log2(static_cast<float>(budget) / photons) / 3.0f : 0.0f;
    const auto levelHolding = [&](float perCell) {
        return std::max(forBudget, std::log2(perCell * cells / photons) / 3.0f);
    };
    return {levelHolding(kPhotonsForOwnFluence),
            std::min(levelHolding(kPhotonsForOwnShape), static_cast<float>(m_levels - 1))};
}

void FluenceCache::resolve() {
    const gl::Program& p = resolveProgram();
    p.set("cacheCells", m_cells);
    p.set("sumsCellsPerPart", static_cast<unsigned>(m_cellsPerPart));
    p.set("sumsToFluence", m_photons > 0 ? m_powerUnit / (static_cast<float>(m_photons) * kQuantaPerUnit) : 0.0f);
    p.set("cellVolume", m_cellVolume);
    bindSums();
    m_weights.bindStorage(3);
    m_directMoments.bindStorage(4);
    m_fluence.bindImage(0, GL_WRITE_ONLY);
    m_fluxRed.bindImage(1, GL_WRITE_ONLY);
    m_fluxGreen.bindImage(2, GL_WRITE_ONLY);
    m_fluxBlue.bindImage(3, GL_WRITE_ONLY);
    m_secondMoment.bindImage(4, GL_WRITE_ONLY);
    m_onceMoments.bindImage(5, GL_WRITE_ONLY);
    m_onceTimesDirect.bindImage(6, GL_WRITE_ONLY);
    m_directSlope.bindImage(7, GL_WRITE_ONLY);
    p.use();
    dispatchOverCells(m_cells);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);  // read by settle's mipmaps too
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, 0);
    unbindImages(8);
    ++m_revision;
}

std::optional<int> FluenceCache::denoise(float level) {
    // A level up has cells 2^level finest cells wide: the filter reaches about as far. Below
    // kLeastSigma a neighbour's weight is under 2 %: the filter would change nothing.
    if (std::exp2(level) - 1.0f < kLeastSigma) return std::nullopt;
    // Where that is wider than the window, the filter pools a coarser level's cells: their
    // weighted sums are the same estimate pooled (docs/multiple-scattering.md, "Coarser cells
    // pooled where the window cannot reach").
    const float widestInWindow = std::log2(1.0f + kWidestSigma);
    const int gridLevel = std::clamp(static_cast<int>(std::ceil(level - widestInWindow)), 0, m_levels - 1);
    const float sigma = std::exp2(level - static_cast<float>(gridLevel)) - 1.0f;
    // Beyond the coarsest level's window the range terms widen instead, fourfold per level.
    const float beyondWindow = std::max(0.0f, level - static_cast<float>(gridLevel) - widestInWindow);
    if (gridLevel > 0)
        for (const gl::Texture* t : {&m_fluence, &m_onceMoments, &m_onceTimesDirect}) glGenerateTextureMipmap(t->id());
    const gl::Program& p = m_denoiseProgram;
    bindSamplers(p, 0,
                 {{"cacheFluence", &m_fluence}, {"onceMoments", &m_onceMoments}, {"onceTimesDirect", &m_onceTimesDirect}});
    p.set("gridLevel", gridLevel);
    p.set("spatialSigma", std::min(sigma, kWidestSigma));
    p.set("rangeWidening", std::exp2(2.0f * beyondWindow));
    p.set("radius", sigma > 2.0f * kLeastSigma ? 2 : 1);
    m_denoised.bindImage(0, GL_WRITE_ONLY);
    m_denoisedSlope.bindImage(1, GL_WRITE_ONLY);
    p.use();
    dispatchOverCells(m_cells);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    unbindImages(2);
    return gridLevel;
}

void FluenceCache::settle(float level, std::optional<int> filteredOn) {
    // These textures hold weighted sums (premultiplied by the cell's weight), so a level's box
    // filter gives its larger cells' weighted means: the angular shape at `level`. The fluence's
    // mipmaps are fresh where the filter ran on a coarser level.
    if (level > 0.0f) {
        for (const gl::Texture* t : {&m_fluxRed, &m_fluxGreen, &m_fluxBlue, &m_secondMoment})
            glGenerateTextureMipmap(t->id());
        if (filteredOn.value_or(0) == 0) glGenerateTextureMipmap(m_fluence.id());
    }
    const gl::Program& p = m_finestProgram;
    bindSamplers(p, 0,
                 {{"cacheFluence", &m_fluence},
                  {"cacheFluxRed", &m_fluxRed},
                  {"cacheFluxGreen", &m_fluxGreen},
                  {"cacheFluxBlue", &m_fluxBlue},
                  {"cacheSecondMoment", &m_secondMoment},
                  {"denoised", filteredOn ? &m_denoised : &m_fluence},
                  {"denoisedSlope", filteredOn ? &m_denoisedSlope : &m_directSlope}});
    p.set("readLevel", level);
    GLuint unit = 0;
    for (const gl::Texture* t : {&m_fluence, &m_fluxRed, &m_fluxGreen, &m_fluxBlue, &m_secondMoment})
        t->bindImage(unit++, GL_READ_WRITE, 0);
    m_directSlope.bindImage(unit, GL_WRITE_ONLY, 0);
    p.use();
    dispatchOverCells(m_cells);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    unbindImages(6);
}

glm::vec4 modelSpaceViewer(const Camera& camera, const glm::mat4& model) {
    const glm::mat4 worldToModel = glm::inverse(model);
    if (camera.projectionType() == Projection::Orthographic)
        return glm::vec4(glm::normalize(glm::mat3(worldToModel) * -camera.forward()), 0.0f);
    return glm::vec4(glm::vec3(worldToModel * glm::vec4(camera.position(), 1.0f)), 1.0f);
}

void FluenceCache::bindSources(const gl::Program& p, int firstUnit) const {
    bindSamplers(p, firstUnit,
                 {{"cacheFluence", &m_fluence},
                  {"cacheFluxRed", &m_fluxRed},
                  {"cacheFluxGreen", &m_fluxGreen},
                  {"cacheFluxBlue", &m_fluxBlue},
                  {"cacheSecondMoment", &m_secondMoment},
                  {"cacheDirectSlope", &m_directSlope}});
}

bool FluenceCache::viewOutdated(const FluenceViewInputs& in) const {
    return m_viewKey != std::make_pair(in, m_revision);
}

void FluenceCache::evaluateView(const FluenceViewInputs& in) {
    if (m_cells.x == 0) return;
    if (m_towardsViewer.size() != m_cells) {
        m_towardsViewer = gl::Texture::create3D(GL_RGBA32F, m_cells, "fluence cache towards the viewer");
        m_towardsViewerSlope = gl::Texture::create3D(GL_RGBA32F, m_cells, "fluence cache towards the viewer: slope");
        m_towardsViewerCap = gl::Texture::create3D(GL_R32F, m_cells, "fluence cache towards the viewer: cap");
    }
    const gl::Program& p = m_viewProgram;
    bindSources(p, 0);
    p.set("viewer", in.viewer);
    p.set("boxMin", m_box.min);
    p.set("boxMax", m_box.max);
    p.set("phaseG", in.anisotropy);
    m_towardsViewer.bindImage(0, GL_WRITE_ONLY);
    m_towardsViewerSlope.bindImage(1, GL_WRITE_ONLY);
    m_towardsViewerCap.bindImage(2, GL_WRITE_ONLY);
    p.use();
    dispatchOverCells(m_cells);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    glUseProgram(0);
    unbindImages(3);
    m_viewKey = std::make_pair(in, m_revision);
}

}  // namespace sss::detail
