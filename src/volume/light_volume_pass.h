#pragma once
// The light volume of Ropinski et al. 2010: per light, an RGBA16F 3D texture holding the
// chromaticity c (rgb) and intensity l (a) of the light arriving at each point, propagated slice
// by slice from the light (shaders/volume/light_propagation.comp). Without the chromaticity
// (the physical model) it holds l alone in R16F, swizzled so that sampling it still returns
// (1, 1, 1, l). View-independent: it is rebuilt only when the volume, transfer function, light,
// model transform or options change.
//
// Ray doubling (LightPropagation::Doubling, shaders/volume/light_doubling.comp) instead joins
// ray segments towards the light that double in length per dispatch.
//
// Sweeps (all along +w of a permuted frame; a light's sweeps advance together, each compute
// dispatch several slices of each, as many as the light's sideways reach per slice allows):
//  - directional light, or point light outside the volume: along the axis the light travels most
//    along (dir_max) and, blended, the second one (dir_blend), with weights proportional to
//    (p1 - p3) and (p2 - p3) of the sorted direction components, which are continuous when the
//    principal axis switches (both 1/2 there) and when the 2nd and 3rd axes swap (weight 0);
//  - point light inside the volume (or on its boundary): six sweeps outward from the light, each
//    owning the voxels the light reaches mostly along its axis.
#include "gl/program.h"
#include "gl/texture.h"
#include "sss/light.h"
#include "sss/volume_clip.h"
#include "sss/volume_scattering_renderer.h"
#include "volume/gpu_volume.h"
#include "volume/light_sweep_plan.h"

#include <glm/mat4x4.hpp>

#include <array>
#include <functional>
#include <map>
#include <numeric>
#include <optional>
#include <vector>

namespace sss::detail {

/// What the light crosses: the data and its transfer-function table and, optionally, the
/// occupancy grid's neighbourhood texture (OccupancyGrid::occupiedNeighbourhoods) for that table.
/// With it, voxels whose path across their slab stays within a brick of empty ones take no medium
/// samples: the light leaves them as it came, so the light volume is the same texel for texel.
struct LightVolumeMedium {
    const GpuVolume& volume;
    const gl::Texture& transferFunction;
    const gl::Texture* occupiedNeighbourhoods = nullptr;
    const VolumeClip* clip = nullptr;  ///< the clip planes and crop box, if any
};

struct LightVolumeSettings {
    float resolutionScale = 1.0f;  ///< light-volume resolution relative to the data, (0, 1]
    float anisotropy = 0.5f;       ///< Henyey-Greenstein g: sets the chromaticity blur cone
    /// false: propagate the intensity l alone and leave the chromaticity c at 1 (white), for
    /// readers that take none (VolumeModel::Physical: grey extinction). The sweep then makes
    /// no cone gather and no colour mixing; l is the same texel for texel at the same
    /// maxSlicesPerDispatch (the measured choice takes more slices for this sweep).
    bool chromaticity = true;
    /// Slices one dispatch advances a sweep at most, or 0 for the measured choice
    /// (VolumeRenderOptions::lightSweepSlices). Each workgroup recomputes the margins its tile's
    /// later slices look up, so fewer dispatches cost more arithmetic; two or more give the same
    /// light volume texel for texel. Fewer are used where the light's sideways reach per slice
    /// leaves no room in shared memory (docs/light-volume-sweep.md).
    int maxSlicesPerDispatch = 0;
    /// The field the medium samples read (VolumeRenderOptions::reconstruction).
    VolumeReconstruction reconstruction = VolumeReconstruction::Trilinear;
    /// Sweep or ray doubling (VolumeRenderOptions::lightPropagation); the eye pass always sweeps.
    LightPropagation propagation = LightPropagation::Sweep;
    /// false: a light outside the volume is swept along its principal axis alone, without the
    /// blended second sweep that keeps the light volume continuous as the light turns past a
    /// diagonal. Half the work under an oblique light, and as close to the blended light volume
    /// as a quarter-scale one is to the full one (4.0-5.5 against 4.2-5.1 % relRMSE from the full
    /// frame, bonsai and engine): a preview's choice (VolumeRenderOptions::lightVolumePreviewScale).
    bool blendSweeps = true;
    /// Each sweep's dispatches in turn (true) or every sweep in each dispatch (false); unset: in
    /// turn on software rasterisers where a sweep runs along x, where that measured faster. The
    /// same light volume texel for texel either way.
    std::optional<bool> sweepsInTurn = std::nullopt;
    /// A sweep along x stores its light at (y, z, x) in a scratch volume, put in place by a last
    /// pass (true), or in the light volume itself (false); unset: row-ordered on software
    /// rasterisers, where an x slice's stores would each touch another cache line. The same
    /// light volume texel for texel either way.
    std::optional<bool> rowOrderedXSweeps = std::nullopt;
    bool operator==(const LightVolumeSettings&) const = default;
};

class LightVolumePass {
public:
    /// `eyePass`: the variant that carries the voxels' scattered light towards the viewer.
    explicit LightVolumePass(bool eyePass = false);
    /// Propagates `light` (world space) through the medium placed by `model` into `output`
    /// (re)allocated at the scaled resolution.
    void run(const LightVolumeMedium& medium, const Light& light, const glm::mat4& model,
             const LightVolumeSettings& settings, gl::Texture& output);
    /// Eye pass: propagates `litColour` (same size as `output`) towards the viewer, i.e. along
    /// `viewDirection` reversed (world space; perspective rays are taken as parallel).
    void runEyePass(const LightVolumeMedium& medium, const gl::Texture& litColour, glm::vec3 viewDirection,
                    const glm::mat4& model, const LightVolumeSettings& settings, gl::Texture& output);

    /// What the sweeps of one light need together.
    struct SweepLayout {
        int sweeps = 0;
        glm::ivec2 largestSlice{1};
        int passes = 0;              ///< dispatches (ray doubling: over both of its grids)
        bool slab = false;           ///< several slices per dispatch through shared memory
        int slicesPerPass = 1;       ///< the most slices a dispatch advances a sweep
        int columnVoxels = 1;        ///< one slice per dispatch: voxels along v per invocation
        int blendedSweep = -1;       ///< the sweep mixed in afterwards, if any
        float blendedWeight = 0.0f;
        /// Each sweep's passes in turn instead of all sweeps in each dispatch (software devices).
        bool sweepsInTurn = false;
        std::vector<int> sweepPasses = {};  ///< each sweep's own dispatches; passes is the largest
        /// The sweep along x that stores its light along rows of a scratch volume, if any.
        int rowOrderedSweep = -1;
        /// Whether a last pass puts the blended or row-ordered sweep's light in place.
        bool assembles() const { return blendedSweep >= 0 || rowOrderedSweep >= 0; }
        /// Compute dispatches in all: the passes and the last.
        int dispatches() const {
            const int inTurn = std::accumulate(sweepPasses.begin(), sweepPasses.end(), 0);
            return (sweepsInTurn ? inTurn : passes) + (assembles() ? 1 : 0);
        }
    };

    /// How the last run or runEyePass laid out its dispatches.
    const SweepLayout& lastLayout() const { return m_lastLayout; }

private:
    void sweep(const LightVolumeMedium& medium, const Light& light, const glm::mat4& model,
               const LightVolumeSettings& settings, gl::Texture& output, glm::vec4 outside);
    /// Runs the sweeps laid out in `p` (all uniforms but the step set) into `output`.
    void propagate(const gl::Program& p, const SweepLayout& layout, const LightVolumeMedium& medium, glm::vec4 outside,
                   gl::Texture& output);
    /// Ray doubling (light_doubling.comp) of `light` (model space) into `output`.
    void doubleRays(const LightVolumeMedium& medium, const Light& light, const glm::mat4& model,
                    const LightVolumeSettings& settings, gl::Texture& output);
    /// Which light_doubling.comp program a level runs.
    struct DoublingVariant {
        bool colourGrid = false;    ///< the half-resolution (c, T) grid, else the T grid
        bool firstLevel = false;    ///< samples the medium (LEVEL0)
        bool last = false;          ///< the T grid's last level: writes the light volume
        bool chromaticity = false;  ///< a colour grid exists (the last level reads it)
        VolumeReconstruction reconstruction = VolumeReconstruction::Trilinear;
        auto operator<=>(const DoublingVariant&) const = default;
    };
    const gl::Program& doublingProgram(const DoublingVariant& variant);
    /// One grid ray doubling runs on: its voxels, its first segment and its levels (at least 1).
    struct DoublingGrid {
        glm::ivec3 dims;
        glm::vec3 voxelSize;
        float segment;
        int levels;
    };
    static DoublingGrid doublingGrid(const Light& light, const Bounds& box, glm::ivec3 dims);
    /// What every level of a doubling reads: the medium, the light (model space) and the box.
    struct DoublingScene {
        const LightVolumeMedium& medium;
        const Light& light;
        const glm::mat4& model;
        const Bounds& box;
    };
    static void setDoublingUniforms(const gl::Program& p, const DoublingScene& scene, const DoublingGrid& grid);
    /// Runs `grid`'s levels, ping-ponging between `levels`; the last writes `lastTarget` if given.
    /// `setLevel` sets a level's own uniforms. Returns the index in `levels` of the last level.
    int runDoublingGrid(const DoublingScene& scene, const DoublingGrid& grid, DoublingVariant variant,
                        std::array<gl::Texture, 2>& levels, gl::Texture* lastTarget,
                        const std::function<void(const gl::Program&, int)>& setLevel);
    /// Puts the blended sweep's share (from `blended`) and the row-ordered sweep's light (from
    /// `rowOrdered`) in `output`, as `layout` says (light_volume_blend.comp).
    void assemble(const SweepLayout& layout, const gl::Texture& blended, const gl::Texture& rowOrdered,
                  const gl::Texture& output);
    /// Which light_propagation.comp program a sweep runs.
    struct PropagationVariant {
        bool chromaticity = true;
        bool slab = false;           ///< several slices per dispatch (SLAB)
        bool paddedLookups = false;  ///< one slice per dispatch, every lookup within the padding
        int columnVoxels = 1;        ///< voxels along v per invocation (COLUMN_VOXELS)
        VolumeReconstruction reconstruction = VolumeReconstruction::Trilinear;
        auto operator<=>(const PropagationVariant&) const = default;
    };
    /// The propagation program for this pass and `variant`, linked on first use.
    const gl::Program& program(const PropagationVariant& variant);
    std::map<PropagationVariant, gl::Program> m_programs;
    std::array<std::optional<gl::Program>, 2> m_assemblePrograms;  // without, with the chromaticity
    std::map<DoublingVariant, gl::Program> m_doublingPrograms;
    bool m_eyePass = false;
    bool m_softwareDevice = false;  // the device's choice of maxSlicesPerDispatch
    gl::Texture m_slices;  // per sweep, ping-pong: light leaving the previous / current dispatch
    SweepLayout m_lastLayout;
};

}  // namespace sss::detail
