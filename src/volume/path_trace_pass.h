#pragma once
// Progressive GPU volume path tracing (VolumeRenderOptions::multipleScattering,
// shaders/volume/path_trace.comp): each accumulate() adds paths per pixel to running sums of
// (radiance, hit) in an RGBA32F texture; composite() draws their mean over the bound target.
// The estimator and its model are renderVolumePathTraced()'s (sss/volume_path_tracer.h).
// Paths are resumable: each dispatch advances every unfinished path by a bounded number of
// steps, its state kept in a storage buffer, until all have finished (see accumulate()).
#include "gl/buffer.h"
#include "gl/program.h"
#include "gl/texture.h"
#include "gl/vertex_array.h"
#include "sss/camera.h"
#include "sss/light.h"
#include "lighting/shadows.h"
#include "sss/volume_scattering_renderer.h"
#include "volume/empty_space.h"
#include "volume/gpu_volume.h"

#include <glm/mat4x4.hpp>

#include <cstdint>
#include <map>
#include <optional>
#include <vector>

namespace sss::detail {

/// Majorants (sigma_t per model unit, R32F) per kBrickVoxels^3 brick of `grid`, from the
/// largest opacity its trilinear samples can reach (OccupancyGrid::maxOpacity), raised a little
/// so float rounding on the GPU stays below them.
gl::Texture brickMajorants(const OccupancyGrid& grid, float voxelLength);

/// What one accumulate() reads. References stay owned by the renderer.
struct PathTraceInputs {
    const GpuVolume& volume;
    const gl::Texture& transferFunction;
    const gl::Texture& majorants;   ///< brickMajorants()
    const gl::Texture& sceneDepth;  ///< a copy of the target's depth: camera rays stop there
    const glm::mat4& model;
    const std::vector<Light>& lights;
    const VolumeRenderOptions& options;  ///< samplesPerFrame, maxBounces, anisotropy
    const Camera& camera;
    float aspect = 1.0f;
    unsigned firstSample = 0;  ///< paths per pixel already in the sums (keys the random streams)
    const VolumeClip* clip = nullptr;  ///< the clip planes and crop box, if any
    /// Hybrid scenes: the meshes block each light's next-event term (null: no meshes shadow the volume).
    const MeshShadowMaps* meshShadows = nullptr;
};

/// Units (loop iterations) one invocation may spend per dispatch by default. llvmpipe stops every
/// loop of an invocation after 65535 iterations in all, counted per SIMD vector: a vector of L
/// lanes runs at most L times this (path_trace.comp), 8192 for llvmpipe's 8 lanes at 256 bits.
inline constexpr int kPathTraceStepsPerDispatch = 1024;
inline constexpr int kPathTraceMaxStepsPerDispatch = 2048;  ///< the largest allowed (x 16 lanes < 65535)
/// Path states held at once by default (112 bytes each: 28 MiB); larger images are traced in
/// bands of rows.
inline constexpr int kPathTraceMaxPathStates = 1 << 18;

/// How a PathTracePass splits its work. The image does not depend on either bound, only the
/// number of dispatches does (tests make them small).
struct PathTraceBounds {
    /// Steps (tentative collisions, brick crossings, events) per path and dispatch, in
    /// [1, kPathTraceMaxStepsPerDispatch].
    int stepsPerDispatch = kPathTraceStepsPerDispatch;
    /// Paths in flight at once, >= 1: the image is traced in bands of rows with at most this
    /// many pixels (at least one row each).
    int maxPathStates = kPathTraceMaxPathStates;
    /// Resume unfinished paths in further dispatches, reading back the count of unfinished
    /// invocations after each (where the GL caps an invocation's loop iterations: llvmpipe); or
    /// trace every path to its end in one dispatch per band with nothing read back, the counts
    /// of paths given up collected a frame later once a fence says they are there (hardware
    /// GPUs). Unset: resumable on software rasterisers only.
    std::optional<bool> resumable;
};

class PathTracePass {
public:
    /// @throws Error InvalidArgument for bounds out of range.
    explicit PathTracePass(PathTraceBounds bounds = {},
                           VolumeReconstruction reconstruction = VolumeReconstruction::Trilinear);
    VolumeReconstruction reconstruction() const { return m_reconstruction; }
    ~PathTracePass();  // the status fence and mapping
    PathTracePass(const PathTracePass&) = delete;
    PathTracePass& operator=(const PathTracePass&) = delete;
    /// Adds options.samplesPerFrame paths per pixel to `sums` (RGBA32F, the target's size): per
    /// band of rows, one dispatch starts them; resumable passes resume the unfinished ones in
    /// further dispatches until none is left (each waits for a read-back of the count). A path
    /// is given up only after 2^24 steps (a degenerate ray); that is logged as a warning and
    /// counted in abandonedPaths() (a frame later without resuming).
    void accumulate(const PathTraceInputs& in, const gl::Texture& sums);
    /// Draws sums / samples with premultiplied "over" into the bound target, the radiance scaled
    /// per channel (lights whose radiance changed alike since the paths were traced).
    void composite(const gl::Texture& sums, int samples, glm::vec3 radianceScale = glm::vec3(1.0f)) const;

    /// Dispatches the last accumulate() took.
    int lastDispatches() const { return m_lastDispatches; }
    /// Paths given up since construction (0 unless a ray is degenerate).
    std::uint64_t abandonedPaths() const { return m_abandoned; }
    bool resumable() const { return m_resumable; }

private:
    void dispatchBands(const gl::Program& p, glm::ivec2 size, int bandRows);
    /// Without resuming: records the status of a finished earlier frame, never waiting.
    void collectStatus();
    void reportAbandoned(std::uint32_t abandoned);

    /// The tracing program, by whether meshes shadow the lights (linked on first use).
    const gl::Program& traceProgram(bool meshShadows);

    std::map<bool, gl::Program> m_tracePrograms;
    gl::Program m_resolve;
    gl::VertexArray m_emptyVertexArray;  // core profile needs a VAO even without attributes
    PathTraceBounds m_bounds;
    VolumeReconstruction m_reconstruction;
    gl::Buffer m_paths;   // one PathState (path_trace.comp) per pixel of a band
    gl::Buffer m_status;  // (unfinished invocations, abandoned paths)
    bool m_resumable = true;
    // Without resuming: the status copied after each frame into persistently mapped memory, and
    // the fence after which it is there.
    gl::Buffer m_statusCopy;
    const std::uint32_t* m_statusMapped = nullptr;
    GLsync m_statusFence = nullptr;
    int m_lastDispatches = 0;
    std::uint64_t m_abandoned = 0;
};

}  // namespace sss::detail
