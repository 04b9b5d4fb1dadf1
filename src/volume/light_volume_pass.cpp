#include "volume/light_volume_pass.h"

#include "core/light_geometry.h"
#include "gl/device.h"
#include "lighting/texture_units.h"
#include "volume/clip_uniforms.h"
#include "volume/empty_space.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>

namespace sss::detail {
namespace {

constexpr int kMaxSweeps = 6;        // MAX_SWEEPS in light_propagation.comp
// Slabs (light_propagation.comp, SLAB 1): slice texels per workgroup and side, and the tile with
// its halos. 1024 invocations hold the 64^2 slab, four texels each, in 32 KiB of shared memory
// (what GL guarantees). Measured on an H100 (docs/light-volume-sweep.md): a 16-texel tile with
// one texel per invocation, or 256 invocations, left the slabs 1.3-3x slower than one slice per
// dispatch.
constexpr int kSweepTile = 32;
constexpr int kSweepSlabSide = 64;
// Texels of outsideLight around every slice of the slice texture: where a sweep's lookups reach
// no farther, one slice per dispatch reads them without testing each tap against the slice's
// edges (those tests were an eighth of the paper model's sweep on llvmpipe).
constexpr int kSlicePadding = 4;
// Voxels along v each invocation propagates under a directional light on a software rasteriser,
// sharing their lookups' rows (light_propagation.comp, COLUMN_VOXELS); measured on llvmpipe
// (bonsai, interleaved): the sweep 1.07x faster with 4, 1.15x with 8, 1.2x with 16. One on
// hardware GPUs, which need the invocations (a 256^2 slice in columns of 16 is 4096 of them).
constexpr int kSoftwareColumnVoxels = 16;

const char* flag(bool on) { return on ? "1" : "0"; }

// What bounds how far a voxel's previous-slice lookups reach.
struct LookupGeometry {
    const Light& light;      // model space
    glm::vec3 voxelCentreMin, voxelCentreMax;  // model space
    float coneTangent;       // 0 without the chromaticity cone
};

// The farthest, in slice texels along u or v, that any voxel's lookups into the previous slice
// reach from the voxel: the light's sideways shift between slices, plus the cone's ring radius
// and one texel of its bilinear taps, or two texels of the Catmull-Rom lookup's footprint.
// nullopt where some voxel's light runs (nearly) along the slice. Both terms are largest at a
// corner of the box of voxel centres (a perspective map of a box is convex), so the corners bound
// a point light's sweep.
std::optional<int> lookupReach(const LookupGeometry& g, int u, int v, const LightSweep& sweep, glm::vec3 s) {
    std::vector<glm::vec3> directions;
    if (const auto* d = std::get_if<DirectionalLight>(&g.light)) {
        directions.push_back(d->direction);
    } else {
        if (sweep.pyramid) return std::nullopt;
        for (int corner = 0; corner < 8; ++corner) {
            const glm::vec3 c(corner & 1 ? g.voxelCentreMax.x : g.voxelCentreMin.x,
                              corner & 2 ? g.voxelCentreMax.y : g.voxelCentreMin.y,
                              corner & 4 ? g.voxelCentreMax.z : g.voxelCentreMin.z);
            directions.push_back(c - *lightPosition(g.light));
        }
    }
    glm::vec2 shift(0.0f), ring(0.0f);
    for (const glm::vec3& x : directions) {
        const glm::vec3 d(x[u], x[v], sweep.reversed ? -x[sweep.axis] : x[sweep.axis]);
        const float length = glm::length(d);
        if (!(length > 0.0f) || d.z <= 1e-3f * length) return std::nullopt;
        const glm::vec2 sideways = glm::abs(glm::vec2(d)) / d.z;  // per unit of w
        shift = glm::max(shift, sideways * s.z / glm::vec2(s));
        ring = glm::max(ring, g.coneTangent * (length / d.z) * s.z / glm::vec2(s));
    }
    const glm::vec2 reach = glm::max(shift + ring, shift + 1.0f);
    const float farthest = std::max(reach.x, reach.y) + 1e-3f;  // CPU and GPU round apart
    if (farthest > static_cast<float>(kSweepSlabSide)) return std::nullopt;
    return static_cast<int>(std::floor(farthest)) + 1;
}

// How many slices a dispatch advances a sweep, and the halo each slice needs around a tile.
struct SweepSlab {
    int slices = 1;
    int halo = 0;
};

// Whether every voxel's Catmull-Rom lookup into the previous slice stays within the slice
// texture's padding (the cone's ring taps are filtered, with outsideLight as the border).
bool lookupsWithinPadding(const std::vector<LightSweep>& sweeps, const LookupGeometry& lookups, glm::vec3 voxelSize) {
    const LookupGeometry centreOnly{lookups.light, lookups.voxelCentreMin, lookups.voxelCentreMax, 0.0f};
    return std::all_of(sweeps.begin(), sweeps.end(), [&](const LightSweep& sweep) {
        const int u = (sweep.axis + 1) % 3, v = (sweep.axis + 2) % 3;
        const std::optional<int> reach =
            lookupReach(centreOnly, u, v, sweep, glm::vec3(voxelSize[u], voxelSize[v], voxelSize[sweep.axis]));
        return reach && *reach <= kSlicePadding;
    });
}

// The slabs of `sweeps` (light_propagation.comp's SLAB 1), or none where a sweep's reach is
// unbounded (a light inside the volume, light along a slice) or no more than one slice per
// dispatch is asked for: then one dispatch per slice, the lookups filtered from the slice texture.
std::vector<SweepSlab> planSlabs(const std::vector<LightSweep>& sweeps, const LookupGeometry& lookups,
                                 glm::vec3 voxelSize, int maxSlices) {
    if (maxSlices < 2) return {};
    const int room = (kSweepSlabSide - kSweepTile) / 2;  // halo texels per side, summed over slices
    std::vector<SweepSlab> slabs;
    for (const LightSweep& sweep : sweeps) {
        const int u = (sweep.axis + 1) % 3, v = (sweep.axis + 2) % 3;
        const std::optional<int> reach =
            lookupReach(lookups, u, v, sweep, glm::vec3(voxelSize[u], voxelSize[v], voxelSize[sweep.axis]));
        if (!reach || *reach > room) return {};
        slabs.push_back({std::min(room / *reach, maxSlices), *reach});
    }
    return slabs;
}

// Sets each sweep's frame (light_propagation.comp): u and v across a slice, w along the sweep
// (towards -axis if reversed), and how many slices each dispatch advances it.
LightVolumePass::SweepLayout setSweepFrames(const gl::Program& p, const std::vector<LightSweep>& sweeps, glm::ivec3 dims,
                                            glm::vec3 voxelSize, const std::vector<SweepSlab>& slabs,
                                            bool rowOrderXSweeps) {
    if (sweeps.size() > static_cast<size_t>(kMaxSweeps)) throw std::logic_error("light volume: too many sweeps");
    LightVolumePass::SweepLayout layout;
    layout.sweeps = static_cast<int>(sweeps.size());
    layout.slab = !slabs.empty();
    for (int s = 0; s < static_cast<int>(sweeps.size()); ++s) {
        const LightSweep& sweep = sweeps[static_cast<size_t>(s)];
        const int u = (sweep.axis + 1) % 3, v = (sweep.axis + 2) % 3;
        const glm::vec3 sweepVoxelSize(voxelSize[u], voxelSize[v], voxelSize[sweep.axis]);
        const SweepSlab slab = layout.slab ? slabs[static_cast<size_t>(s)] : SweepSlab{};
        glm::ivec3 origin(0), stepU(0), stepV(0), stepW(0);
        stepU[u] = 1;
        stepV[v] = 1;
        stepW[sweep.axis] = sweep.reversed ? -1 : 1;
        origin[sweep.axis] = sweep.reversed ? dims[sweep.axis] - 1 : 0;
        glm::mat3 dataToSweep(0.0f);  // column = data axis, row = sweep axis
        dataToSweep[u][0] = 1.0f;
        dataToSweep[v][1] = 1.0f;
        dataToSweep[sweep.axis][2] = sweep.reversed ? -1.0f : 1.0f;
        const std::string i = "[" + std::to_string(s) + "]";
        p.set("sliceDims" + i, glm::ivec3(dims[u], dims[v], dims[sweep.axis]));
        p.set("firstSlice" + i, sweep.firstSlice);
        p.set("voxelOrigin" + i, origin);
        p.set("voxelStepU" + i, stepU);
        p.set("voxelStepV" + i, stepV);
        p.set("voxelStepW" + i, stepW);
        p.set("dataToSweep" + i, dataToSweep);
        p.set("sweepVoxelSize" + i, sweepVoxelSize);
        p.set("slabSlices" + i, slab.slices);
        p.set("slabHalo" + i, slab.halo);
        // The second of two blended sweeps goes to its own volume, mixed in once both are done.
        const bool blended = !sweep.pyramid && s > 0;
        if (blended) {
            layout.blendedSweep = s;
            layout.blendedWeight = sweep.weight;
        }
        p.set("blended" + i, blended ? 1 : 0);
        // A pyramid's sweeps share the light volume voxel by voxel: they store in place.
        const bool rowOrdered = rowOrderXSweeps && sweep.axis == 0 && !sweep.pyramid;
        if (rowOrdered) layout.rowOrderedSweep = s;
        p.set("rowOrdered" + i, rowOrdered ? 1 : 0);
        p.set("pyramidMask" + i, sweep.pyramid ? 1 : 0);
        layout.largestSlice = glm::max(layout.largestSlice, glm::ivec2(dims[u], dims[v]));
        const int steps = dims[sweep.axis] - sweep.firstSlice;
        layout.sweepPasses.push_back((steps + slab.slices - 1) / slab.slices);
        layout.passes = std::max(layout.passes, layout.sweepPasses.back());
        layout.slicesPerPass = std::max(layout.slicesPerPass, slab.slices);
    }
    return layout;
}

// Slices per dispatch when the settings leave it to the device, measured side by side
// (sss-bench --table light-sweep, docs/light-volume-sweep.md). On an H100 four slices made the
// intensity-only sweep 1.16-1.19x faster; the chromaticity cone's wider halos made every slab
// slower than one slice. On llvmpipe the recomputed margins cost more than the dispatches save.
int deviceSlicesPerDispatch(bool softwareDevice, bool chromaticity) {
    return softwareDevice || chromaticity ? 1 : 4;
}

// The medium both propagations sample (transfer_function.glsl, clip.glsl,
// empty_neighbourhood.glsl): its textures on units 0, 1 and 3, and its uniforms.
void bindMedium(const LightVolumeMedium& medium) {
    medium.volume.texture.bind(0);
    medium.transferFunction.bind(1);
    // Unit 3 always holds a 3D texture, so the sampler validates with skipping off as well.
    (medium.occupiedNeighbourhoods ? *medium.occupiedNeighbourhoods : medium.volume.texture).bind(3);
}

void setMediumUniforms(const gl::Program& p, const LightVolumeMedium& medium, const glm::mat4& model) {
    const GpuVolume& volume = medium.volume;
    p.set("volumeTexture", 0);
    p.set("transferFunction", 1);
    p.set("occupiedNeighbourhoods", 3);
    p.set("transferFunctionEntries", static_cast<float>(medium.transferFunction.size().x));
    p.set("valueScaleOffset", volume.valueScaleOffset);
    p.set("referenceLength", volume.voxelLength);
    p.set("skipEmpty", medium.occupiedNeighbourhoods ? 1 : 0);
    p.set("dataDims", volume.dims);
    p.set("brickVoxels", kBrickVoxels);
    p.set("textureToBrick", textureToBrick(volume.dims));
    setClipUniforms(p, medium.clip, model, volume.box);
}

// The light, in the volume's model space.
void setLightUniforms(const gl::Program& p, const Light& light) {
    if (const auto* d = std::get_if<DirectionalLight>(&light)) {
        p.set("isPointLight", 0);
        p.set("lightDirection", d->direction);
    } else {
        p.set("isPointLight", 1);
        p.set("lightPosition", *lightPosition(light));
    }
}

bool usesRayDoubling(LightPropagation propagation, bool softwareDevice) {
    if (propagation != LightPropagation::Auto) return propagation == LightPropagation::Doubling;
    return !softwareDevice;
}

// Ray doubling's first segment: the path between two slices of the axis the light travels most
// along (in voxels), so a directional light's far ends all lie on slice planes and each level's
// lookups interpolate within a slice, as the sweep's; a point light outside the box, as seen from
// its centre, the same (its rays are nearly parallel); a point light inside, the shortest voxel
// edge.
float firstSegmentLength(const Light& light, const Bounds& box, glm::vec3 voxelSize) {
    glm::vec3 direction(0.0f);
    if (const auto* d = std::get_if<DirectionalLight>(&light)) {
        direction = d->direction;
    } else {
        const glm::vec3 position = *lightPosition(light);
        if (glm::all(glm::greaterThanEqual(position, box.min)) && glm::all(glm::lessThanEqual(position, box.max)))
            return std::min({voxelSize.x, voxelSize.y, voxelSize.z});
        direction = glm::normalize(position - box.center());
    }
    const glm::vec3 perVoxel = glm::abs(direction) / voxelSize;
    const int axis = perVoxel.x >= perVoxel.y && perVoxel.x >= perVoxel.z ? 0 : (perVoxel.y >= perVoxel.z ? 1 : 2);
    return voxelSize[axis] / std::abs(direction[axis]);
}

}  // namespace

LightVolumePass::DoublingGrid LightVolumePass::doublingGrid(const Light& light, const Bounds& box, glm::ivec3 dims) {
    const glm::vec3 voxelSize = box.size() / glm::vec3(dims);
    const float segment = firstSegmentLength(light, box, voxelSize);
    // Levels until a segment spans the box's diagonal: every path to the light inside the box.
    // At least one, so the last level (which writes the light volume) follows the first.
    const int levels = std::max(1, static_cast<int>(std::ceil(std::log2(glm::length(box.size()) / segment) - 1e-4f)));
    return {dims, voxelSize, segment, levels};
}

void LightVolumePass::setDoublingUniforms(const gl::Program& p, const DoublingScene& scene, const DoublingGrid& grid) {
    p.set("nextLevel", 0);  // image unit
    p.set("gridDims", grid.dims);
    p.set("voxelSize", grid.voxelSize);
    p.set("boxMin", scene.box.min);
    p.set("boxSize", scene.box.size());
    p.set("segmentLength", grid.segment);
    setLightUniforms(p, scene.light);
    setMediumUniforms(p, scene.medium, scene.model);
}

LightVolumePass::LightVolumePass(bool eyePass) : m_eyePass(eyePass), m_softwareDevice(gl::currentDeviceIsSoftware()) {}

const gl::Program& LightVolumePass::program(const PropagationVariant& v) {
    return gl::linkedOnce(m_programs, v, "volume/light_propagation.comp", [&] {
        return ShaderDefines{{"EYE_PASS", flag(m_eyePass)},
                             {"CHROMATICITY", flag(v.chromaticity)},
                             {"SLAB", flag(v.slab)},
                             {"PADDED_LOOKUPS", flag(v.paddedLookups)},
                             {"COLUMN_VOXELS", std::to_string(v.columnVoxels)},
                             {"CUBIC_RECONSTRUCTION", cubicReconstructionDefine(v.reconstruction)},
                             {"TILE", std::to_string(kSweepTile)},
                             {"SLAB_SIDE", std::to_string(kSweepSlabSide)},
                             {"SLICE_PADDING", std::to_string(kSlicePadding)}};
    });
}

void LightVolumePass::run(const LightVolumeMedium& medium, const Light& light, const glm::mat4& model,
                          const LightVolumeSettings& settings, gl::Texture& output) {
    sweep(medium, light, model, settings, output, glm::vec4(1.0f));
}

void LightVolumePass::runEyePass(const LightVolumeMedium& medium, const gl::Texture& litColour,
                                 glm::vec3 viewDirection, const glm::mat4& model, const LightVolumeSettings& settings,
                                 gl::Texture& output) {
    litColour.bind(units::kLitColour);
    // Light travelling towards the viewer; nothing enters from behind the volume.
    sweep(medium, DirectionalLight{.direction = -viewDirection}, model, settings, output,
          glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
}

void LightVolumePass::sweep(const LightVolumeMedium& medium, const Light& worldLight, const glm::mat4& model,
                            const LightVolumeSettings& settings, gl::Texture& output, glm::vec4 outside) {
    const GpuVolume& volume = medium.volume;
    const glm::ivec3 dims = lightVolumeDims(volume.dims, settings.resolutionScale);
    // The eye pass carries colour whatever the settings say.
    const bool chromaticity = settings.chromaticity || m_eyePass;
    const GLenum format = chromaticity ? GL_RGBA16F : GL_R16F;
    if (!output || output.size() != dims || output.internalFormat() != format) {
        output = gl::Texture::create3D(format, dims, m_eyePass ? "eye-pass volume" : "light volume");
        // Without the chromaticity the volume keeps l alone, a quarter of the memory and of the
        // texels a sample filters; every reader still samples (c, l), with c white.
        if (!chromaticity) output.setSwizzle(GL_ONE, GL_ONE, GL_ONE, GL_RED);
    }
    // The light in the volume's model space, where the propagation works. The volume holds what
    // the medium lets through from the light's position; a spot light's cone scales the light
    // where it is shaded (lights.glsl), so here it propagates like a point light.
    const glm::mat4 toModel = glm::inverse(model);
    Light light = worldLight;
    if (auto* d = std::get_if<DirectionalLight>(&light))
        d->direction = glm::normalize(glm::mat3(toModel) * glm::normalize(d->direction));
    else
        light = PointLight{.position = glm::vec3(toModel * glm::vec4(*lightPosition(worldLight), 1.0f))};

    if (!m_eyePass && usesRayDoubling(settings.propagation, m_softwareDevice)) {
        doubleRays(medium, light, model, settings, output);
        return;
    }
    std::vector<LightSweep> sweeps = planLightSweeps(light, volume.box, dims);
    if (!settings.blendSweeps && sweeps.size() == 2 && !sweeps[0].pyramid) {
        sweeps.resize(1);  // the principal axis's
        sweeps[0].weight = 1.0f;
    }
    const ChromaticityCone cone = chromaticityCone(settings.anisotropy);
    const glm::vec3 voxelSize = volume.box.size() / glm::vec3(dims);
    const LookupGeometry lookups{light, volume.box.min + 0.5f * voxelSize, volume.box.max - 0.5f * voxelSize,
                                 chromaticity ? cone.tangent : 0.0f};
    const int maxSlices = settings.maxSlicesPerDispatch > 0 ? settings.maxSlicesPerDispatch
                                                             : deviceSlicesPerDispatch(m_softwareDevice, chromaticity);
    const std::vector<SweepSlab> slabs = planSlabs(sweeps, lookups, voxelSize, maxSlices);
    const bool paddedLookups = slabs.empty() && lookupsWithinPadding(sweeps, lookups, voxelSize);
    const bool columns = paddedLookups && m_softwareDevice && std::holds_alternative<DirectionalLight>(light);
    const PropagationVariant variant{.chromaticity = chromaticity,
                                     .slab = !slabs.empty(),
                                     .paddedLookups = paddedLookups,
                                     .columnVoxels = columns ? kSoftwareColumnVoxels : 1,
                                     .reconstruction = settings.reconstruction};

    const gl::Program& p = program(variant);
    if (m_eyePass) p.set("litColour", units::kLitColour);
    p.set("lightVolume", 0);   // image unit
    p.set("lightVolumeDims", dims);
    p.set("voxelSize", voxelSize);
    p.set("boxMin", volume.box.min);
    setLightUniforms(p, light);
    p.set("coneTangent", cone.tangent);
    p.set("coneWeights", glm::vec2(cone.centreWeight, cone.ringWeight));
    setMediumUniforms(p, medium, model);

    // On llvmpipe the volume's rows run along x, so each voxel of an x slice is another cache line:
    // an x sweep's stores took 1.15 of its 2.2 s on the bonsai (a y sweep's 0.17 of 1.0 s), and
    // beside another sweep in the same dispatch the two sweeps' slices evicted each other (lit
    // from (-0.6, -0.7, -0.4): 5.3 s, in turn 3.6 s). So on software rasterisers an x sweep stores
    // along rows and, where one runs, the sweeps run in turn; y and z sweeps ran as fast together,
    // and on hardware GPUs each dispatch's launch costs more (docs/light-volume-sweep.md).
    const bool alongX = std::any_of(sweeps.begin(), sweeps.end(), [](const LightSweep& s) { return s.axis == 0; });
    const bool rowOrderXSweeps = settings.rowOrderedXSweeps.value_or(m_softwareDevice);
    SweepLayout layout = setSweepFrames(p, sweeps, dims, voxelSize, slabs, rowOrderXSweeps);
    layout.columnVoxels = variant.columnVoxels;
    layout.sweepsInTurn = layout.sweeps > 1 && settings.sweepsInTurn.value_or(m_softwareDevice && alongX);
    m_lastLayout = layout;
    propagate(p, layout, medium, outside, output);
    glUseProgram(0);
}

const gl::Program& LightVolumePass::doublingProgram(const DoublingVariant& v) {
    return gl::linkedOnce(m_doublingPrograms, v, "volume/light_doubling.comp", [&] {
        return ShaderDefines{{"GRID_COLOUR", flag(v.colourGrid)},
                             {"LEVEL0", flag(v.firstLevel)},
                             {"LAST", flag(v.last)},
                             {"CHROMATICITY", flag(v.chromaticity)},
                             {"CUBIC_RECONSTRUCTION", cubicReconstructionDefine(v.reconstruction)}};
    });
}

void LightVolumePass::doubleRays(const LightVolumeMedium& medium, const Light& light, const glm::mat4& model,
                                 const LightVolumeSettings& settings, gl::Texture& output) {
    const GpuVolume& volume = medium.volume;
    bindMedium(medium);
    const DoublingScene scene{medium, light, model, volume.box};
    DoublingVariant variant{.chromaticity = settings.chromaticity, .reconstruction = settings.reconstruction};
    int dispatches = 0;
    // The paper model's colour first, at half resolution: the last level of the light reads it.
    gl::Texture colour;
    if (settings.chromaticity) {
        const DoublingGrid grid = doublingGrid(light, volume.box, glm::max(glm::ivec3(1), (output.size() + 1) / 2));
        const ChromaticityCone cone = chromaticityCone(settings.anisotropy);
        // The sweep blurs a slice's colour only where the cone's ring is half a texel or wider.
        const float minVoxel = std::min({grid.voxelSize.x, grid.voxelSize.y, grid.voxelSize.z});
        const float ring = cone.tangent * grid.segment;
        variant.colourGrid = true;
        const auto setCone = [&](const gl::Program& p, int level) {
            p.set("coneWeights", glm::vec2(cone.centreWeight, cone.ringWeight));
            p.set("ringRadius", ring >= 0.5f * minVoxel ? ring * std::sqrt(std::exp2(static_cast<float>(level - 1))) : 0.0f);
        };
        std::array<gl::Texture, 2> levels{gl::Texture::create3D(GL_RGBA16F, grid.dims, "light doubling colour"),
                                          gl::Texture::create3D(GL_RGBA16F, grid.dims, "light doubling colour")};
        colour = std::move(levels[runDoublingGrid(scene, grid, variant, levels, nullptr, setCone)]);
        dispatches += grid.levels + 1;
        variant.colourGrid = false;
    }
    if (colour) colour.bind(4);
    const DoublingGrid grid = doublingGrid(light, volume.box, output.size());
    std::array<gl::Texture, 2> levels{gl::Texture::create3D(GL_R16F, grid.dims, "light doubling transmittance"),
                                      gl::Texture::create3D(GL_R16F, grid.dims, "light doubling transmittance")};
    runDoublingGrid(scene, grid, variant, levels, &output, nullptr);
    dispatches += grid.levels + 1;
    m_lastLayout = SweepLayout{.passes = dispatches};
}

int LightVolumePass::runDoublingGrid(const DoublingScene& scene, const DoublingGrid& grid, DoublingVariant variant,
                                     std::array<gl::Texture, 2>& levels, gl::Texture* lastTarget,
                                     const std::function<void(const gl::Program&, int)>& setLevel) {
    const gl::Program* configured = nullptr;  // the program whose grid uniforms are set
    for (int level = 0; level <= grid.levels; ++level) {
        variant.firstLevel = level == 0;
        variant.last = lastTarget && level == grid.levels;
        const gl::Program& p = doublingProgram(variant);
        if (&p != configured) {
            setDoublingUniforms(p, scene, grid);
            p.set("level", 2);
            p.set("colourGrid", 4);
            configured = &p;
        }
        if (level > 0) {
            p.set("span", grid.segment * std::exp2(static_cast<float>(level - 1)));
            if (setLevel) setLevel(p, level);
            levels[static_cast<size_t>((level - 1) % 2)].bind(2);
        }
        (variant.last ? *lastTarget : levels[static_cast<size_t>(level % 2)]).bindImage(0, GL_WRITE_ONLY);
        const glm::ivec3 group = p.workGroupSize();
        p.use();
        glDispatchCompute(static_cast<GLuint>((grid.dims.x + group.x - 1) / group.x),
                          static_cast<GLuint>((grid.dims.y + group.y - 1) / group.y), static_cast<GLuint>(grid.dims.z));
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    }
    return grid.levels % 2;
}

void LightVolumePass::propagate(const gl::Program& p, const SweepLayout& layout, const LightVolumeMedium& medium,
                                glm::vec4 outside, gl::Texture& output) {
    const glm::ivec3 dims = output.size();
    const glm::ivec2 largestSlice = layout.largestSlice;
    const glm::ivec2 paddedSlice = largestSlice + 2 * kSlicePadding;
    const int count = layout.sweeps;
    const int blendedSweep = layout.blendedSweep;
    // Grown, never shrunk: lights of different kinds (2 or 6 sweeps) share one array.
    if (!m_slices || glm::ivec2(m_slices.size()) != paddedSlice || m_slices.size().z < 2 * count) {
        m_slices = gl::Texture::create2DArray(GL_RGBA16F, paddedSlice.x, paddedSlice.y, 2 * count, "light volume slices");
        m_slices.setWrap(GL_CLAMP_TO_BORDER);  // what enters from outside the volume (SLAB 0)
    }
    if (!layout.slab) {
        // One slice per dispatch reads each sweep's first slice from the texture, and filters
        // beyond a slice's edge: the unlit value, cleared and as the border. The slabs take
        // outsideLight there instead.
        m_slices.setBorderColor(outside);
        const float unlit[4] = {outside.r, outside.g, outside.b, outside.a};
        glClearTexImage(m_slices.id(), 0, GL_RGBA, GL_FLOAT, unlit);
    }
    // Scratch for this rebuild only, so the memory a renderer holds between light changes stays
    // one light volume per light.
    gl::Texture blended, rowOrdered;
    if (blendedSweep >= 0 && blendedSweep != layout.rowOrderedSweep)
        blended = gl::Texture::create3D(output.internalFormat(), dims, "blended light sweep");
    if (layout.rowOrderedSweep >= 0)
        rowOrdered =
            gl::Texture::create3D(output.internalFormat(), glm::ivec3(dims.y, dims.z, dims.x), "row-ordered light sweep");
    p.set("previousSlices", 2);
    p.set("currentSlices", 1);
    p.set("blendedVolume", 2);  // image units
    p.set("rowOrderedVolume", 3);
    p.set("outsideLight", outside);
    p.set("slicesTextureSize", glm::vec2(paddedSlice));

    bindMedium(medium);
    m_slices.bind(2);
    output.bindImage(0, GL_WRITE_ONLY);
    m_slices.bindImage(1, GL_WRITE_ONLY);
    (blended ? blended : output).bindImage(2, GL_WRITE_ONLY);  // units a program declares hold a volume
    (rowOrdered ? rowOrdered : output).bindImage(3, GL_WRITE_ONLY);
    p.use();
    const glm::ivec2 tile =
        layout.slab ? glm::ivec2(kSweepTile) : glm::ivec2(p.workGroupSize()) * glm::ivec2(1, layout.columnVoxels);
    const auto groupsX = static_cast<GLuint>((largestSlice.x + tile.x - 1) / tile.x);
    const auto groupsY = static_cast<GLuint>((largestSlice.y + tile.y - 1) / tile.y);
    // In turn, each sweep runs its own passes only (a light inside the volume: the slices beyond it).
    const int sweepsPerDispatch = layout.sweepsInTurn ? 1 : count;
    for (int first = 0; first < count; first += sweepsPerDispatch) {
        p.set("firstSweep", first);
        const int passes = layout.sweepsInTurn ? layout.sweepPasses[static_cast<size_t>(first)] : layout.passes;
        for (int pass = 0; pass < passes; ++pass) {
            p.set("pass", pass);
            glDispatchCompute(groupsX, groupsY, static_cast<GLuint>(sweepsPerDispatch));
            // The next pass reads this one's slices; the ray caster samples the volume afterwards.
            glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
        }
    }
    if (layout.assembles()) assemble(layout, blended, rowOrdered, output);
}

void LightVolumePass::assemble(const SweepLayout& layout, const gl::Texture& blended, const gl::Texture& rowOrdered,
                               const gl::Texture& output) {
    const bool chromaticity = output.internalFormat() == GL_RGBA16F;
    std::optional<gl::Program>& linked = m_assemblePrograms[chromaticity ? 1 : 0];
    if (!linked)
        linked = gl::Program::link({{GL_COMPUTE_SHADER, "volume/light_volume_blend.comp"}},
                                   ShaderDefines{{"CHROMATICITY", flag(chromaticity)}});
    const gl::Program& p = *linked;
    const glm::ivec3 dims = output.size();
    const bool mainRowOrdered = layout.rowOrderedSweep == 0;
    const bool blendedRowOrdered = layout.blendedSweep >= 0 && layout.rowOrderedSweep == layout.blendedSweep;
    p.set("lightVolume", 0);
    p.set("blendedVolume", 1);
    p.set("rowOrderedVolume", 2);
    p.set("dims", dims);
    p.set("mainRowOrdered", mainRowOrdered ? 1 : 0);
    p.set("blendedRowOrdered", blendedRowOrdered ? 1 : 0);
    p.set("weight", layout.blendedSweep >= 0 ? layout.blendedWeight : 0.0f);
    output.bindImage(0, GL_READ_WRITE);
    (blended ? blended : output).bindImage(1, GL_READ_ONLY);
    (rowOrdered ? rowOrdered : output).bindImage(2, GL_READ_ONLY);
    p.use();
    const glm::ivec3 group = p.workGroupSize();
    glDispatchCompute(static_cast<GLuint>((dims.x + group.x - 1) / group.x),
                      static_cast<GLuint>((dims.y + group.y - 1) / group.y), static_cast<GLuint>(dims.z));
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

}  // namespace sss::detail
