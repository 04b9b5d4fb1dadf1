#pragma once
// The multiple-scattering cache (VolumeRenderOptions::multipleScatteringCache): a grid over the
// volume's box holding, per cell, the fluence of the light that has scattered at least once
// (rgb) and its flux vector per channel (the first angular moment), in model space. The ray
// caster adds what a sample scatters of it towards the eye to the light volume's single
// scattering: the radiance taken as a Henyey-Greenstein lobe about the flux with the same first
// moment, convolved with the phase function (docs/multiple-scattering.md). Within a cell, the
// light scattered once is regressed on the direct light (the light volumes), which the eye knows
// at every sample: so a sample in the first mean free path of a lit dense surface reads more of it
// than the cell's mean over its depth.
//
// It is built by photons from the lights (shaders/volume/fluence_photons.comp): the path
// tracer's medium, delta tracking and scattering, with the collision estimator of each cell's
// track length once a photon has scattered. View-independent: camera moves reuse it. It refines
// progressively: each add() traces more photons into the same sums, and the textures are their
// mean so far.
#include "gl/buffer.h"
#include "gl/program.h"
#include "gl/texture.h"
#include "sss/camera.h"
#include "sss/light.h"
#include "sss/volume_clip.h"
#include "lighting/shadows.h"
#include "volume/empty_space.h"
#include "volume/gpu_volume.h"

#include <glm/mat4x4.hpp>

#include <cstdint>
#include <map>
#include <optional>
#include <vector>

namespace sss::detail {

/// What the photons cross and where they come from. References stay owned by the renderer.
struct FluenceCacheInputs {
    const GpuVolume& volume;
    const gl::Texture& transferFunction;
    const gl::Texture& majorants;      ///< brickMajorants() for the current TF
    const glm::mat4& model;
    const std::vector<Light>& lights;
    float anisotropy = 0.5f;           ///< Henyey-Greenstein g
    int maxBounces = 100000;           ///< scatterings in all, the eye's included
    const VolumeClip* clip = nullptr;  ///< cut matter casts no shadows unless the clip says so
    /// One per light, as the eye reads them: the direct light the cells' fluence is regressed on.
    const std::vector<gl::Texture>* lightVolumes = nullptr;
    /// Hybrid scenes: the meshes block each light's way to a photon's first scattering, and the
    /// direct light the fluence is regressed on (null: no meshes shadow the volume).
    const MeshShadowMaps* meshShadows = nullptr;
};

/// What the cache's light towards the eye depends on besides the cache (FluenceCache::evaluateView).
struct FluenceViewInputs {
    glm::vec4 viewer{0.0f};  ///< model space: the eye (w 1, perspective) or the unit direction towards it (w 0)
    float anisotropy = 0.5f; ///< Henyey-Greenstein g
    bool operator==(const FluenceViewInputs&) const = default;
};

/// The viewer of `camera` in the model space of `model`, as FluenceViewInputs::viewer holds it.
glm::vec4 modelSpaceViewer(const Camera& camera, const glm::mat4& model);

/// Each light's weight in the direct light the cache regresses its once-scattered fluence on
/// (shaders/volume/direct_light.glsl): its mean radiance channel, and for point and spot lights
/// the inverse square of their distance from the box's centre (world units).
std::vector<float> directLightWeights(const std::vector<Light>& lights, const glm::mat4& model, const Bounds& box);

/// Cells of the cache along each axis: `resolution` along the box's longest side, the others in
/// proportion, at most one per voxel and at most 32 voxels wide; the resolution lowered until
/// they number at most `maxCells`.
glm::ivec3 fluenceCacheCells(glm::ivec3 dims, glm::vec3 boxSize, int resolution, std::int64_t maxCells);

/// Cells whose photon sums one storage-buffer binding of `storageBlockBytes` holds
/// (gl::storageBlockLimit), and the most cells a cache can have: its sums split over at most four
/// bindings, its other per-cell buffers in one (llvmpipe's 128 MiB: 2.9 million, 142^3).
std::int64_t fluenceCacheCellsPerPart(std::int64_t storageBlockBytes);
std::int64_t maxFluenceCacheCells(std::int64_t storageBlockBytes);

class FluenceCache {
public:
    explicit FluenceCache(VolumeReconstruction reconstruction = VolumeReconstruction::Trilinear);
    VolumeReconstruction reconstruction() const { return m_reconstruction; }
    /// Empties the cache for new inputs, at `cells` cells. Unless `sameDensityInputs` (the
    /// medium, the lights and the light volumes are those of the last restart: only the
    /// scattering changed), it takes each cell's weight and direct-light moments anew.
    void restart(const FluenceCacheInputs& in, glm::ivec3 cells, bool sameDensityInputs);
    /// Traces `photons` more photons into the sums and updates the textures to their mean. Where
    /// the cells hold few photons (before `budget`, or finer grids even at it: poolingLevels),
    /// the finest cells then hold a filtered fluence and direct-light slope and a coarser level's
    /// angular shape (denoise, settle): readers always read the finest cells.
    void add(const FluenceCacheInputs& in, int photons, std::uint64_t budget);

    /// Whether evaluateView(in) would change the textures it fills: the cache or `in` changed.
    bool viewOutdated(const FluenceViewInputs& in) const;
    /// Per cell, what the cache scatters towards the viewer
    /// (shaders/volume/fluence_view.comp): the ray caster reads three textures per sample instead
    /// of six, and none of the lobe's arithmetic. View-dependent: run once per camera move.
    void evaluateView(const FluenceViewInputs& in);
    /// w times the light scattered towards the viewer at the cell's mean direct light (rgb), and
    /// w (RGBA32F).
    const gl::Texture& towardsViewer() const { return m_towardsViewer; }
    /// w times its slope against the direct light (rgb), and w times that mean (RGBA32F).
    const gl::Texture& towardsViewerSlope() const { return m_towardsViewerSlope; }
    /// w times the largest direct light the slope applies to (R32F).
    const gl::Texture& towardsViewerCap() const { return m_towardsViewerCap; }
    /// Binds the cache's six textures to units firstUnit..firstUnit + 5 as p's samplers
    /// cacheFluence, cacheFluxRed, cacheFluxGreen, cacheFluxBlue, cacheSecondMoment and cacheDirectSlope
    /// (shaders/volume/fluence_lobe.glsl evaluates them towards a viewer).
    void bindSources(const gl::Program& p, int firstUnit) const;
    /// The lights of the last restart, at the radiance its photons carry. Where the lights now
    /// differ from them by a common factor per channel (detail::commonRadianceScale), the cache
    /// stays: it goes on tracing for these lights, and the ray caster scales what it reads.
    const std::vector<Light>& lights() const { return m_lights; }
    /// Photons traced since the last restart (those that missed the box included).
    std::uint64_t photons() const { return m_photons; }
    glm::ivec3 cells() const { return m_cells; }
    /// Dispatches the last add() took.
    int lastDispatches() const { return m_lastDispatches; }

private:
    void setUniforms(const FluenceCacheInputs& in);
    void setMediumUniforms(const gl::Program& p, const FluenceCacheInputs& in) const;
    void bindDirectLight(const gl::Program& p, const FluenceCacheInputs& in) const;
    /// What the photon and density programs are compiled for: the number of light volumes (a
    /// compile-time count: shaders/volume/direct_light.glsl) and whether meshes shadow the lights.
    struct ProgramVariant {
        int directLights = 0;
        bool meshShadows = false;
        int sumsParts = 1;  // storage buffers the sums are split over (volume/fluence_sums.glsl)
        auto operator<=>(const ProgramVariant&) const = default;
    };
    ProgramVariant variantFor(const FluenceCacheInputs& in) const;
    /// Storage-buffer bindings the sums of m_cells take, m_cellsPerPart cells each, and their
    /// binding (fluence_photons.comp and fluence_resolve.comp read them so).
    int sumsParts() const;
    void bindSums() const;
    void unbindSums() const;
    const gl::Program& resolveProgram();
    /// The photon and density programs for m_variant, linked on first use.
    const gl::Program& photonProgram();
    const gl::Program& densityProgram();
    ShaderDefines defines() const;
    /// Each cell's integral of the weight s, and the direct light's moments (fluence_density.comp).
    void computeWeights(const FluenceCacheInputs& in);
    void dispatchPhotons(int invocations);
    void resolve();
    /// How far the cells' values are pooled, as mip levels (cells 2^level finest cells wide):
    /// the fluence's filter reaches over about `fluence`'s cells, the angular shape is read at
    /// `shape`. Each is the level whose cells hold about as many photons as the finest will once
    /// the cache holds `budget` (log8(budget / photons)), or more where that leaves a cell fewer
    /// than kPhotonsForOwnFluence or kPhotonsForOwnShape. Both 0 where nothing needs pooling.
    struct PoolingLevels {
        float fluence = 0.0f;
        float shape = 0.0f;
    };
    PoolingLevels poolingLevels(std::uint64_t budget) const;
    /// The finest cells' fluence and direct-light slope, filtered over about `level`'s cells
    /// (fluence_denoise.comp): pooling the finest cells or, where its window cannot reach that
    /// far, a coarser level's. Returns the level pooled, or nothing where the filter would be too
    /// narrow to change them.
    std::optional<int> denoise(float level);
    /// The finest cells' textures for the readers where poolingLevels pools (fluence_finest.comp):
    /// the angular shape of `level`, the filtered fluence and slope if the filter ran (pooling
    /// `filteredOn`'s cells), the cells' own otherwise. Generates the mipmaps it reads.
    void settle(float level, std::optional<int> filteredOn);

    VolumeReconstruction m_reconstruction;
    std::map<ProgramVariant, gl::Program> m_photonPrograms;
    std::map<ProgramVariant, gl::Program> m_densityPrograms;
    ProgramVariant m_variant;     // of the current inputs
    std::map<int, gl::Program> m_resolvePrograms;  // per sumsParts()
    gl::Program m_denoiseProgram;
    gl::Program m_finestProgram;
    gl::Program m_viewProgram;
    glm::ivec3 m_cells{0};
    std::vector<Light> m_lights;
    std::int64_t m_storageBlockBytes = 0;  // gl::storageBlockLimit, asked once
    std::int64_t m_cellsPerPart = 1;       // fluenceCacheCellsPerPart of it
    int m_photonSlots = 1;                 // photons in flight at once, their states within it
    gl::Buffer m_sums;            // 23 slots per cell, 64-bit fixed point (fluence_photons.comp)
    gl::Buffer m_weights;         // per cell, the integral of s over it (fluence_density.comp)
    gl::Buffer m_directMoments;   // per cell, the integrals of s E and s E^2, the largest E (fluence_density.comp)
    gl::Buffer m_photonStates;
    gl::Buffer m_status;
    // Per cell and premultiplied by its mean weight w (readers divide filtered values by the
    // filtered w; texel centres are the cells' centres), model space, all RGBA32F; these four
    // mipmapped (by settle, where it reads a coarser level, and the fluence by denoise, where it
    // runs on one):
    gl::Texture m_fluence;       // rgb fluence, and w (fluence_resolve.comp)
    gl::Texture m_fluxRed;       // the red channel's flux vector, and the second moment's yz
    gl::Texture m_fluxGreen;     // the green channel's, and the largest direct light of the cell's
                                 // voxel centres
    gl::Texture m_fluxBlue;      // the blue channel's
    gl::Texture m_secondMoment;  // the mean channel's traceless xx - 1/3, yy - 1/3, xy, xz
    // The finest cells' slope against the direct light (rgb) and its mean (single level), and
    // the moments it is solved from (the filter pools them, fluence_denoise.comp; their mipmaps
    // are made by denoise where it pools a coarser level).
    gl::Texture m_directSlope;
    gl::Texture m_onceMoments, m_onceTimesDirect;
    gl::Texture m_denoised, m_denoisedSlope;  // the finest cells' fluence and slope, filtered (fluence_denoise.comp)
    std::uint64_t m_photons = 0;
    float m_cellVolume = 1.0f;    // model units^3
    Bounds m_box;                 // the volume's, model space
    float m_powerUnit = 0.0f;     // power a photon of weight 1 carries (see setUniforms)
    bool m_resumable = true;
    int m_lastDispatches = 0;
    int m_levels = 1;             // mip levels of the cache's textures
    std::uint64_t m_revision = 0; // counts the changes of the cache's textures
    gl::Texture m_towardsViewer, m_towardsViewerSlope, m_towardsViewerCap;  // evaluateView's, at its level
    std::optional<std::pair<FluenceViewInputs, std::uint64_t>> m_viewKey;  // and the revision it read
};

}  // namespace sss::detail
