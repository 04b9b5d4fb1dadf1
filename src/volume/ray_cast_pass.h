#pragma once
// Single-pass GPU ray casting of a volume with a transfer function (shaders/volume/ray_cast.glsl):
// emission-absorption or gradient-shaded, front to back, early ray termination, opacity
// correction and per-pixel jitter; as fragments over the whole target or as a compute dispatch
// over the volume's screen rectangle.
#include "gl/program.h"
#include "gl/texture.h"
#include "gl/vertex_array.h"
#include "sss/camera.h"
#include "sss/render_target.h"
#include "sss/volume_scattering_renderer.h"
#include "lighting/shadows.h"
#include "volume/empty_space.h"
#include "volume/gpu_volume.h"

#include <vector>

namespace sss::detail {

class FluenceCache;

/// Scattering modes sample light volumes.
bool usesLightVolume(VolumeShading shading);
/// Gradient and ScatteringGradient shade with the data's gradient.
bool usesGradient(VolumeShading shading);
/// Whether the eye pass runs for these options (the paper's model in a light-volume mode).
bool usesEyePass(const VolumeRenderOptions& options);
/// Whether the multiple-scattering cache is built and read for these options.
bool usesScatteringCache(const VolumeRenderOptions& options);

/// Whether the ray caster evaluates the cache's light towards the viewer per sample rather than
/// read the view pass's cells (CacheViewEvaluation; Auto: per sample on software devices where
/// the cache's `cells` outnumber kCacheCellsPerPixel times the target's `pixels`).
bool cacheEvaluatedPerSample(CacheViewEvaluation evaluation, bool softwareDevice, double cells, double pixels);

/// Whether `caster` resolves to the compute ray caster on a software rasteriser or a hardware
/// GPU (gl::currentDeviceIsSoftware()).
bool usesComputeRayCaster(RayCaster caster, bool softwareDevice);

/// Pixels [origin, origin + size) of a viewport.
struct PixelRect {
    glm::ivec2 origin{0};
    glm::ivec2 size{0};
    bool empty() const { return size.x <= 0 || size.y <= 0; }
};

/// The pixels whose centres may see the box `box` under `modelViewProjection`, within a
/// viewport of `viewport` pixels: its projected corners' bounds, a pixel wider on each side; the
/// whole viewport when the box reaches behind the eye.
PixelRect screenRectangle(const glm::mat4& modelViewProjection, const Bounds& box, glm::ivec2 viewport);

/// What one ray-cast draw reads. References stay owned by the renderer.
struct RayCastInputs {
    RenderTarget& target;  ///< drawn over (the fragment caster draws into whatever is bound)
    const GpuVolume& volume;
    const gl::Texture& transferFunction;
    /// A copy of the target's depth, where rays stop; null: the target's own depth texture (the
    /// compute caster, which draws into no framebuffer, reads it directly).
    const gl::Texture* sceneDepth = nullptr;
    const gl::Texture& occupancy;
    const std::vector<gl::Texture>& lightVolumes;  ///< one per light in the scattering modes
    /// Texels towards the light at which samples read the light volumes: options.lightVolumeReach,
    /// scaled down for a preview light volume so that it spans the same voxels.
    float lightVolumeReach = 0.0f;
    const MeshShadowMaps* meshShadows = nullptr;   ///< hybrid scenes: meshes seen from the lights
    const gl::Texture* eyeVolume = nullptr;        ///< the eye pass's result, if it ran
    /// The multiple-scattering cache, if it is on, its light towards this camera evaluated
    /// (FluenceCache::evaluateView) unless the variant evaluates it per sample.
    const FluenceCache* cache = nullptr;
    const gl::Texture* gradientVolume = nullptr;   ///< gradient modes: precomputed gradients, if any
    const gl::Texture* preintegration = nullptr;   ///< the pre-integrated table, if options.preintegration
    const gl::Texture* stepTransferFunction = nullptr;  ///< else the TF corrected for the step (step_classification.h)
    /// The opacity alone of the table that classifies: the TF's entries (R32F), or pre-integrated
    /// the table's layer 0 (R16F, preintegration.h). Where the physical model carries light back
    /// through the data it reads nothing else of them, with a quarter of the channels to filter.
    const gl::Texture* opacityTable = nullptr;
    const glm::mat4& model;
    const std::vector<Light>& lights;
    const VolumeRenderOptions& options;
    const Camera& camera;
    float aspect = 1.0f;
    const VolumeClip* clip = nullptr;  ///< the clip planes and crop box, if any
};

/// Where the gradient modes read gradients: computed per sample from six data fetches, or the
/// gradient volume; with unorm data (8 and 16 bit) its fourth channel also holds the data value,
/// so a gradient-shaded sample reads one texel for both.
enum class GradientSource { OnTheFly, Volume, VolumeWithValues };

/// What a ray-cast program depends on besides the options (RayCastVariant::of).
struct RayCastScene {
    const std::vector<Light>& lights;
    const glm::mat4& model;
    const VolumeClip* clip = nullptr;             ///< null: nothing cut
    const MeshShadowMaps* meshShadows = nullptr;  ///< hybrid scenes: meshes seen from the lights
    GradientSource gradients = GradientSource::OnTheFly;
    bool preintegration = false;
    bool softwareDevice = false;
    /// The multiple-scattering cache's light towards the viewer is evaluated per sample
    /// (cacheEvaluatedPerSample), not read from the view pass's textures.
    bool cachePerSample = false;
};

/// What a ray-cast program is compiled for: every switch the shader takes as a constant. The
/// renderer rebuilds the pass when the variant its options and lights call for changes.
struct RayCastVariant {
    VolumeShading shading = VolumeShading::EmissionAbsorption;
    bool emptySpaceSkipping = true;
    std::size_t lightCount = 0;
    bool eyePass = false;
    GradientSource gradients = GradientSource::OnTheFly;
    bool preintegration = false;
    /// Every light is directional: the shader then finds each light's direction and half vector
    /// once per ray instead of once per sample, and no sample's world position.
    bool directionalLightsOnly = true;
    /// The gradient modes' Blinn-Phong exponent when it is a whole number from 1 to 256: the
    /// shader then raises to it by repeated squaring (exact, and a few multiplications where
    /// pow() costs a logarithm and an exponential per sample); 0: pow() with the uniform.
    int integerShininess = 0;
    /// The gradient modes' normal length is |M g| for a gradient g and M the model's normal
    /// matrix times a diagonal. M^T M is diagonal unless the model shears or scales unequally
    /// along turned axes; where it is, the shader takes |M g|^2 from three products instead of
    /// a matrix.
    bool diagonalGradientMetric = true;
    /// Clip planes or a crop box cut the volume; without, the shader has no clip tests.
    bool clipped = false;
    /// Meshes cast shadows into the volume (hybrid scenes); without, no shadow-map lookups.
    bool meshShadows = false;
    /// Physical single scattering (VolumeModel::Physical in a light-volume mode): grey light.
    bool physicalModel = false;
    /// The compute ray caster (ray_cast.comp) rather than the fragment one (ray_cast.frag).
    bool compute = false;
    /// Samples add what they scatter of the multiple-scattering cache.
    bool scatteringCache = false;
    /// ... evaluated per sample from its six textures (else read from the view pass's three).
    bool cachePerSample = false;
    /// The field between voxel centres (VolumeRenderOptions::reconstruction).
    VolumeReconstruction reconstruction = VolumeReconstruction::Trilinear;

    static RayCastVariant of(const VolumeRenderOptions& options, const RayCastScene& scene);
    bool operator==(const RayCastVariant&) const = default;
};

class RayCastPass {
public:
    explicit RayCastPass(const RayCastVariant& variant);
    const RayCastVariant& variant() const { return m_variant; }
    /// Composites the volume over in.target (bound for drawing).
    void run(const RayCastInputs& in) const;

private:
    /// Sets the uniforms and binds the textures both casters read.
    void bindInputs(const RayCastInputs& in) const;
    void dispatchOverRectangle(const RayCastInputs& in) const;

    RayCastVariant m_variant;
    gl::Program m_program;
    gl::VertexArray m_emptyVertexArray;  // core profile needs a VAO even without attributes
};

}  // namespace sss::detail
