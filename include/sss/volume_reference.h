#pragma once
/// @file
/// CPU reference renderer for volumes, in double precision: the ground truth the GPU ray caster
/// (VolumeScatteringRenderer) and its light volume are measured against with
/// computeErrorMetrics() (sss/image_compare.h).
///
/// THE OPTICAL MODEL (every GPU volume mode implements it; differences are discretisation):
///
/// Geometry (exactly the GPU's). The volume occupies Volume::worldBounds() (a box centred at the
/// origin, largest side 1) in model space, placed in the world by the model matrix M. Pixel
/// (x, y) of a W x H image, row 0 at the top, has its centre at
///   ndc = ((x + 0.5) / W * 2 - 1, 1 - (y + 0.5) / H * 2);
/// its ray runs from unproject(ndc, z = -1) to unproject(ndc, z = +1) through
/// inverse(camera.projection(W / H) * camera.view()), taken to model space by inverse(M), and
/// is clipped to the box (and to [near, far]). All distances are model-space lengths.
///
/// Reconstruction. A voxel's normalised value (what the GPU texture holds) is v / 255 (UInt8),
/// v / 65535 (UInt16), (v + 32768) / 65535 (Int16) or (v - min) / (max - min) over valueRange()
/// (Float32); the field s(p) is the trilinear interpolation of these with voxel i's centre at
/// texture coordinate (i + 0.5) / n and clamp-to-edge outside (GL_LINEAR on the 3D texture);
/// with VolumeReconstruction::CubicBSpline it is their tensor-product cubic B-spline, per axis
/// s = sum over k of B3(x - k) v_k, x = tc n - 0.5, the indices k clamped to the edge.
/// With raw = s * k + m the inverse of that normalisation and (lo, hi) =
/// Volume::transferFunctionRange(), the transfer-function coordinate is
/// x(p) = clamp(s(p) * a + b, 0, 1), a = k / (hi - lo), b = (m - lo) / (hi - lo): for UInt8 with
/// the default range (1, 0). Classification uses the table T = TransferFunction::table(N), linearly
/// interpolated: with f = x * (N - 1), i = min(floor(f), N - 2), C_tf(x), alpha_tf(x) =
/// T[i] + (f - i) * (T[i + 1] - T[i]) (the GPU's texture lookup at u = (f + 0.5) / N).
///
/// Extinction. The TF opacity is defined per reference length D = one voxel (the smallest voxel
/// edge in model units):  sigma_t(p) = -ln(1 - alpha_tf(x(p))) / D.  Where alpha_tf >= 1 - e^-30
/// (in particular alpha_tf = 1), sigma_t * D is capped at kMaxOpticalDepthPerVoxel = 30 (a
/// transmittance of 9.4e-14 per voxel), so the model stays finite; the GPU treats alpha_tf = 1
/// as exactly opaque, which differs from the cap by at most e^-30 per voxel crossed.
///
/// Emitted colour of a point, by mode (k_a = ambient, k_d = diffuse, k_s = specular):
///  - EmissionAbsorption:  C(p) = C_tf.
///  - Gradient: Blinn-Phong as the GPU's shade(): g = central differences of s one voxel apart
///    on each axis (texture-coordinate offsets 1/n, clamp-to-edge) times 0.5 * a (value per
///    voxel); outward normal n = normalize(transpose(inverse(M3)) * (-g * dims / boxSize)),
///    flipped to face v, where v = normalize(Camera::position() - M p) (also for orthographic
///    cameras, as on the GPU); if |outward| <= 1e-12, n = v. lit = k_a C_tf + sum over lights
///    of E * (k_d C_tf max(n.l, 0) + k_s (n.h)^shininess) for n.l > 0, h = normalize(l + v);
///    C(p) = mix(C_tf, lit, smoothstep(0, gradientThreshold, |g|)).
///  - Scattering (single scattering, hard shadows, light-volume chromaticity):
///      C(p) = C_tf * (k_a + k_d * sum over lights of E * c(p) * l(p)),
///    where, along the straight shadow ray from p towards the light (model space; a
///    directional light's direction is taken there by inverse(M)) up to the box exit or, for a
///    point light, the light itself if that is nearer:
///      l(p) = exp(-integral of sigma_t ds)  (the light arriving at p: no self-shadowing term),
///      c(p) solves dc/ds = sigma_t(s) * (C_tf(s) - c) marching from the light towards p, with
///      c = (1, 1, 1) where the light enters the volume (the continuous limit of Ropinski's
///      c_i = (1 - alpha) c_{i-1} + alpha rgb; over a piece of constant sigma_t and C_tf it is
///      exactly that recurrence with alpha = 1 - exp(-sigma_t ds)).
///    E = colour * intensity for a directional light; colour * intensity / max(r^2, 1e-8)
///    for a point light, r the world-space distance from M p to the light (as on the GPU); a
///    spot light's is the point light's times spotConeFactor() at M p.
///  - ScatteringGradient: Scattering plus, per light, l(p) * smoothstep(0, gradientThreshold,
///    |g|) * E * k_s * max(n.h, 0)^shininess where n.l > 0 (n, h as in Gradient).
///
/// Compositing: front to back, premultiplied. The clipped span [t0, t1] of a ray is split into
/// m = ceil((t1 - t0) / h) equal pieces of length h' = (t1 - t0) / m <= h; piece k is sampled
/// at its midpoint with opacity a = 1 - exp(-sigma_t h'):
///   C += (1 - A) a C(p),  A += (1 - A) a.
/// Shadow rays are integrated the same way with step <= shadowStepVoxels voxels. The output is
/// C + (1 - A) * background.rgb, alpha A + (1 - A) * background.a: what the GPU's target holds
/// after clear(background) + render (premultiplied "over").
///
/// Differences to the GPU by construction (they vanish as the GPU's step shrinks): the GPU
/// samples at t0 + (k + 0.5) h while t < t1 with full-step opacity for every sample (so the
/// last piece may be too long or missing by up to h/2), uses float arithmetic and the
/// driver's filtering precision, stops rays at earlyTermination (default 0.99), and, in the
/// scattering modes, reads c and l from a light volume (slice propagation, c blurred over a cone
/// unless chromaticityConeScale models that).

#include "sss/volume_clip.h"
#include "sss/api.h"
#include "sss/camera.h"
#include "sss/image.h"
#include "sss/light.h"
#include "sss/transfer_function.h"
#include "sss/volume.h"
#include "sss/volume_scattering_renderer.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <memory>
#include <vector>

SSS_BEGIN_API

namespace sss {

/// Cap on sigma_t * (one voxel): where alpha_tf is (nearly) 1 the extinction stays finite.
inline constexpr double kMaxOpticalDepthPerVoxel = 30.0;

/// What the reference computes per sample (see the model in this file's documentation).
enum class ReferenceShading { EmissionAbsorption, Gradient, Scattering, ScatteringGradient };

/// Options of the reference renderer. Defaults match VolumeRenderOptions' defaults where they
/// overlap (ambient, diffuse, specular, shininess, gradientThreshold).
struct VolumeReferenceOptions {
    ReferenceShading shading = ReferenceShading::EmissionAbsorption;
    /// Largest distance between view-ray samples, in voxels, >= 1/1024 (default 1/8).
    double stepVoxels = 0.125;
    /// Largest distance between shadow-ray samples (scattering modes), in voxels, >= 1/1024
    /// (default 1/4).
    double shadowStepVoxels = 0.25;
    /// Colour the volume is composited over (what the GPU target is cleared to), finite.
    glm::dvec4 background{0.0};
    /// Rays stop once A reaches this, in (0, 1]; 1 (the default) never stops early.
    double earlyTermination = 1.0;
    double ambient = 0.25;             ///< k_a, finite and >= 0
    double diffuse = 0.85;             ///< k_d, finite and >= 0
    /// Scattering modes: the paper's model (above) or physical single scattering, where
    ///   C(p) = C_tf * sum over lights of E * l(p) * p_HG(anisotropy, -w_l . v)
    /// (no ambient, no chromaticity c; w_l towards the light, v towards the viewer) (default:
    /// Paper, as VolumeRenderOptions::model).
    VolumeModel model = VolumeModel::Paper;
    /// Henyey-Greenstein g, in (-1, 1): the physical model's phase function, and the paper
    /// model's chromaticity cone (chromaticityConeScale).
    double anisotropy = 0.5;
    /// Paper model: how the chromaticity c reaches p. 0 (default): along the straight shadow ray,
    /// as above (the limit of the light volume's cone gather as its slices get thin). s in (0, 1]:
    /// as the light volume at resolution scale s gathers it (Ropinski et al. 2010): at every slice
    /// plane of that light volume the light crosses (the sweep's planes, chosen as the GPU
    /// chooses them), c is read at the crossing and at 8 points on a ring of radius tan(theta) x
    /// the path between two planes, theta the cone half-angle of HG(anisotropy), weighted as on
    /// the GPU. The expectation is estimated with chromaticityWalks random walks per sample, each
    /// drawing one of the 9 points at every plane; the light's intensity l stays a straight ray.
    double chromaticityConeScale = 0.0;
    /// Random walks per sample for chromaticityConeScale > 0, >= 1 (noise ~ 1/sqrt(walks)).
    int chromaticityWalks = 64;
    glm::dvec3 specular{0.3};          ///< k_s, finite and >= 0
    double shininess = 32.0;           ///< Blinn-Phong exponent, finite and > 0
    double gradientThreshold = 0.02;   ///< |g| (value per voxel) of full shading, finite and > 0
    /// Worker threads over image rows; 0 (default) uses std::thread::hardware_concurrency().
    int threads = 0;
    /// Clip planes and crop box, as VolumeScatteringRenderer::setClip (default: none).
    VolumeClip clip{};
    /// The field between voxel centres, as VolumeRenderOptions::reconstruction (default: Trilinear).
    VolumeReconstruction reconstruction = VolumeReconstruction::Trilinear;
};

/// The light arriving at a point from one light (Scattering model).
struct ReferenceLightSample {
    double transmittance = 1.0;      ///< l: exp(-optical depth) along the shadow ray
    glm::dvec3 chromaticity{1.0};    ///< c: the colour the medium gave the light
    /// E: colour * intensity (/ r^2 for point and spot lights, times a spot's spotConeFactor)
    glm::dvec3 radiance{0.0};
};

/// The reference renderer bound to one scene (volume, TF table, placement, lights). Keeps its
/// own copy of everything, so the arguments may go away after construction.
class VolumeReference {
public:
    /// @throws Error InvalidArgument if tfEntries is outside 2..65536, model is not finite or
    ///         not invertible, a light is invalid (validateLight), or an option is invalid
    ///         (the message names it: "VolumeReferenceOptions::stepVoxels must be ...").
    VolumeReference(const Volume& volume, const TransferFunction& tf, int tfEntries, const glm::mat4& model,
                    std::vector<Light> lights, const VolumeReferenceOptions& options = {});
    ~VolumeReference();
    VolumeReference(VolumeReference&&) noexcept;
    VolumeReference& operator=(VolumeReference&&) noexcept;

    /// @throws Error InvalidArgument as the constructor.
    void setOptions(const VolumeReferenceOptions& options);
    const VolumeReferenceOptions& options() const;

    /// Renders width x height pixels (row 0 at the top). @throws Error InvalidArgument unless
    /// 0 < width, height <= 16384.
    Image render(const Camera& camera, int width, int height) const;

    /// TF colour and opacity (C_tf, alpha_tf) at a model-space point, as the light sees the
    /// medium: zero where options().clip cuts the matter and it casts no shadows.
    glm::dvec4 classify(glm::dvec3 modelPoint) const;
    /// sigma_t at a model-space point, per model unit.
    double extinction(glm::dvec3 modelPoint) const;
    /// l, c and E of light `light` at a model-space point inside the box, integrated with
    /// options().shadowStepVoxels. @throws Error InvalidArgument if light is out of range.
    ReferenceLightSample incidentLight(glm::dvec3 modelPoint, std::size_t light) const;
    /// One voxel (the smallest voxel edge) in model units: the opacity reference length D.
    double voxelLength() const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

/// One-call form of VolumeReference(...).render(camera, width, height).
Image renderVolumeReference(const Volume& volume, const TransferFunction& tf, int tfEntries, const glm::mat4& model,
                            const std::vector<Light>& lights, const Camera& camera, int width, int height,
                            const VolumeReferenceOptions& options = {});

/// Result of renderVolumeReferenceConverged.
struct ConvergedReference {
    Image image;                 ///< the last (finest) image
    double stepVoxels = 0;       ///< view step of that image
    double shadowStepVoxels = 0; ///< shadow step of that image
    double lastChange = 0;       ///< relRmse (computeErrorMetrics) between the last two images; +inf after one
    int renders = 0;             ///< images rendered
    bool converged = false;      ///< lastChange < tolerance (else the step hit minStepVoxels)
};

/// Renders with view step startStepVoxels, then halves it (and the shadow step with it, keeping
/// options.shadowStepVoxels / options.stepVoxels) until the relative RMSE between successive
/// images is below tolerance, or the next step would go below minStepVoxels; options'
/// own step fields are ignored. Does not throw when the tolerance is not reached: check
/// `converged`. EmissionAbsorption and Scattering converge to second order (1/16 voxel
/// typically gives 1e-4); the gradient modes only to first order, because the two-sided normal
/// flips where n is perpendicular to v and the shading jumps there: they need minStepVoxels
/// of about 1/512 for 1e-4 (cheap for small test images).
/// @throws Error InvalidArgument as renderVolumeReference, or unless tolerance > 0 and
///         1/1024 <= minStepVoxels <= startStepVoxels (finite).
ConvergedReference renderVolumeReferenceConverged(const Volume& volume, const TransferFunction& tf, int tfEntries,
                                                  const glm::mat4& model, const std::vector<Light>& lights,
                                                  const Camera& camera, int width, int height,
                                                  const VolumeReferenceOptions& options = {}, double tolerance = 1e-4,
                                                  double startStepVoxels = 0.5, double minStepVoxels = 1.0 / 32.0);

}  // namespace sss

SSS_END_API
