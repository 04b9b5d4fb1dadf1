#pragma once
/// @file
/// Physical ground truth for light scattering in volumes: a Monte Carlo path tracer, in double
/// precision, for the volume of sss/volume_reference.h treated as a participating medium
/// (single and multiple scattering, no diffusion or light-volume approximation): what the
/// reference's "Scattering" model and the GPU's light volume approximate, to measure them by.
///
/// THE MODEL (renderVolumePathTraced()):
///
/// Scene. Geometry, camera rays, reconstruction, classification and extinction are exactly
/// those of VolumeReference (sss/volume_reference.h): the box Volume::worldBounds() placed by
/// the model matrix M; pixel (x, y) has its ray through ndc = ((x + 0.5) / W * 2 - 1,
/// 1 - (y + 0.5) / H * 2) (or, with jitterPixels, through a uniformly random point of the
/// pixel), unprojected, taken to model space and clipped to the box and to [near, far];
/// sigma_t(p) = -ln(1 - alpha_tf(x(p))) / D with the kMaxOpticalDepthPerVoxel cap, D one voxel.
/// All transport happens in model space: lengths, directions and the phase function there.
/// The medium is the box; outside it there is vacuum, and nothing reflects at its faces.
///
/// Medium. Extinction sigma_t(p) (grey: the same for R, G and B); single-scattering albedo
/// a(p) = clamp(C_tf(x(p)), 0, 1) per channel, so sigma_s = a sigma_t and sigma_a =
/// (1 - a) sigma_t; Henyey-Greenstein phase function of mean cosine g (|g| < 1e-3 exactly
/// isotropic, 1 / (4 pi)). No emission, no ambient term, no gradient shading.
///
/// Light. Directional, point and spot lights (sss/light.h), as the reference: a directional
/// light is a collimated beam of irradiance E = colour * intensity normal to it, travelling
/// along inverse(M) * direction (normalised) in model space; a point light gives E = colour *
/// intensity / max(r^2, 1e-8), r the world-space distance from M p to the light, from the
/// light's model-space position; a spot light is a point light times its spotConeFactor() at
/// M p. Lights are not seen directly and do not shine on the box's faces: the only light is
/// what the medium scatters. The background is black (or
/// options.background composited behind, see below); there is no environment light.
///
/// What is rendered: the radiance L reaching the eye along each pixel's ray after scattering
/// one or more times (MultipleScattering) or exactly once (SingleScattering) in the box:
///   L = sum over n >= 1 of L_n,
///   L_1 = integral over the ray of T(0, t) sigma_s(t) sum over lights of p_HG(l . d) E T_l(t) dt,
/// where d is the ray direction (away from the eye), l the unit direction towards the light,
/// T(0, t) the transmittance along the ray from the eye side and T_l the transmittance from
/// the point to the light (the box exit, or the point light if that is nearer); L_n, n >= 2,
/// the same with the light scattered n - 1 times more before. p_HG(l . d) is the phase function
/// at the angle between the light's propagation (-l) and the radiance's (-d).
///
/// Relation to the reference's Scattering mode: with ambient 0, diffuse 1 and a TF whose
/// colour is white (C_tf = 1, so c(p) = 1), VolumeReference computes exactly
///   L_ref = integral of T(0, t) sigma_t(t) E T_l(t) dt
/// (its compositing is the discretised form), the single-scattering radiance of an albedo-1
/// medium with the phase function replaced by 1: L_1 = L_ref / (4 pi) for g = 0. The reference
/// has no phase function, and its c(p) is a chromaticity where the path tracer multiplies by
/// the albedo at the scattering point only (light crossing a coloured region on the way in is
/// attenuated by the grey sigma_t, not tinted).
///
/// THE ESTIMATOR (adjoint paths from the eye; one path carries all three channels):
///  - Free paths by delta (Woodcock) tracking against a majorant grid: the box is divided into
///    majorantGridResolution cells along each axis (at most one per voxel), each with the
///    largest sigma_t that the reconstruction can take in it (the TF's largest opacity
///    over the range of the voxels its interpolation reads, times 1 + 1e-6). The path's
///    ray walks the cells in order (3D DDA); a unit exponential optical depth is spent at each
///    cell's majorant; where it runs out a tentative collision is made, real with probability
///    sigma_t(p) / majorant, otherwise the path goes on unchanged (a null collision: the
///    distribution of the first real collision is exactly T(0, t) sigma_t(t)). Empty cells
///    (majorant 0) cost nothing.
///  - Next-event estimation at every real collision, to every light: the term
///      w * a(p) * p_HG(l . d) * E * T_l
///    with T_l by ratio tracking through the same grid (the product of 1 - sigma_t / majorant
///    over the tentative collisions to the light: an unbiased estimate of the transmittance);
///    once that product falls below 1/8 it is continued with probability (product * 8), at
///    1/8 (Russian roulette: unbiased, and dense or opaque regions end it quickly).
///  - The path scatters: throughput w (RGB, 1 at the eye) is multiplied by a(p) (the
///    extinction is grey, so one path with RGB weights is unbiased for all three channels),
///    and a new direction is drawn from Henyey-Greenstein around d (sampling the phase
///    function exactly, so no further weight). From rouletteStartBounce scatterings on,
///    Russian roulette on the throughput: the path goes on with probability q =
///    min(1, max channel of w), at w / q. A path that would scatter for the
///    (maxBounces + 1)-th time ends (counted in truncatedPaths: the only bias).
///    SingleScattering stops after the first collision's next-event term. With the same seed,
///    both modes draw the same random numbers up to that term, so a SingleScattering image
///    is exactly the first-collision part of the MultipleScattering one.
///  - A path's value X is the sum of its next-event terms; E[X] = L (truncation aside).
///
/// Coverage and background: the pixel's alpha is the fraction of its paths whose camera ray
/// had a real collision, an unbiased estimate of 1 - T(camera ray), the reference's converged
/// alpha A. With a background B, each path's value is X + (1 - hit) B.rgb and its alpha
/// hit + (1 - hit) B.a, so the pixel estimates L + T B.rgb, A + (1 - A) B.a, the reference's
/// "over" composite. Without jitterPixels, pixels whose centre ray misses the box are B
/// exactly (no paths); with it every pixel takes its paths (a ray that misses counts as B).
///
/// Statistics. Per pixel, samplesPerPixel independent paths; the pixel is the mean of their
/// values and its standard error sqrt(sample variance / samplesPerPixel): about 68 % of renders
/// land within one standard error of the exact value of the model, 99.7 % within three. Each
/// path has its own random stream (xoshiro256++ keyed by a hash of (seed, pixel, path index)),
/// so the images are bit-identical for a given seed whatever the number of threads, and a
/// path's first collision does not depend on the mode.

#include "sss/volume_clip.h"
#include "sss/api.h"
#include "sss/camera.h"
#include "sss/image.h"
#include "sss/light.h"
#include "sss/transfer_function.h"
#include "sss/volume.h"

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <vector>

SSS_BEGIN_API

namespace sss {

/// Which orders of scattering renderVolumePathTraced() includes.
enum class VolumeScatteringMode {
    SingleScattering,   ///< only light scattered exactly once (the first collision's term)
    MultipleScattering  ///< all orders
};

/// Options of renderVolumePathTraced().
struct VolumePathTracerOptions {
    /// Paths per pixel, in [1, 1 << 24] (default: 64). The standard error falls as 1 / sqrt.
    int samplesPerPixel = 64;
    /// Seed of the random streams (default: 1). Same seed, same images, whatever `threads`.
    std::uint64_t seed = 1;
    /// Worker threads over image rows, >= 0; 0 = std::thread::hardware_concurrency() (default).
    int threads = 0;
    /// Single or multiple scattering (default: multiple).
    VolumeScatteringMode mode = VolumeScatteringMode::MultipleScattering;
    /// Henyey-Greenstein mean cosine, in (-1, 1) (default: 0.5, positive = forward).
    double g = 0.5;
    /// Scatterings after which a path is truncated (truncatedPaths), >= 1 (default: 100000).
    int maxBounces = 100000;
    /// Scatterings after which Russian roulette on the throughput starts, >= 0 (default: 3).
    int rouletteStartBounce = 3;
    /// Cells of the majorant grid along each axis (at most one per voxel), in [1, 1024];
    /// 1 = one global majorant (default: 32; on the 32^3 bucky-like volume it takes 5 extinction
    /// lookups per path where one global majorant takes 57, 2.6x faster).
    int majorantGridResolution = 32;
    /// Colour composited behind the volume (see the file comment), finite (default: black).
    glm::dvec4 background{0.0};
    /// Each path through a uniformly random point of its pixel instead of the centre: the image
    /// is then the pixel-area average (default: false, the reference's centre rays).
    bool jitterPixels = false;
    /// Clip planes and crop box, as VolumeScatteringRenderer::setClip (default: none).
    VolumeClip clip{};
    /// The field between voxel centres, as VolumeRenderOptions::reconstruction (default: Trilinear).
    VolumeReconstruction reconstruction = VolumeReconstruction::Trilinear;
};

/// What renderVolumePathTraced() returns.
struct VolumePathTracerResult {
    /// Radiance per pixel (linear rgb, composited over the background) and coverage alpha.
    Image image{1, 1};
    /// Standard error of each pixel's rgb and alpha (0 where the ray misses the box).
    Image standardError{1, 1};
    /// sqrt(sum of squared standard errors / sum of squared means) over the rgb of the pixels
    /// that took paths: the expected relRmse of `image` against the exact one (0 if all black).
    double relativeRmseEstimate = 0.0;
    /// Pixels that took samplesPerPixel paths: those whose centre ray meets the box (all of
    /// them with jitterPixels); the others are the background, without paths.
    int coveredPixels = 0;
    /// Mean paths per pixel over the whole image.
    double meanSamplesPerPixel = 0.0;
    /// Mean real collisions (scattering vertices) per path.
    double meanCollisionsPerPath = 0.0;
    /// Mean extinction lookups per path (tentative collisions of delta and ratio tracking): the
    /// cost, and what the majorant grid reduces.
    double meanLookupsPerPath = 0.0;
    std::int64_t paths = 0;           ///< paths run in all
    std::int64_t truncatedPaths = 0;  ///< paths ended at maxBounces (bias bound; 0 usually)
    /// Lookups where sigma_t exceeded its cell's majorant (the result would be biased): 0
    /// unless something is wrong. Reported so tests can check it.
    std::int64_t majorantViolations = 0;
    /// Cells of the majorant grid along x, y, z.
    glm::ivec3 majorantGrid{0};
};

/// Renders the volume as a participating medium (see the file comment) with the scene
/// conventions of renderVolumeReference(): `volume` classified by tf.table(tfEntries), placed
/// by `model`, lit by `lights` (any number; none gives black), seen by `camera`, in a
/// width x height image (row 0 at the top).
/// @throws Error InvalidArgument for a size outside [1, kMaxImageSide], tfEntries outside
///         2..65536, a model matrix that is not finite or singular, an invalid light, or an
///         invalid option (the message names the VolumePathTracerOptions field).
VolumePathTracerResult renderVolumePathTraced(const Volume& volume, const TransferFunction& tf, int tfEntries,
                                              const glm::mat4& model, const std::vector<Light>& lights,
                                              const Camera& camera, int width, int height,
                                              const VolumePathTracerOptions& options = {});

}  // namespace sss

SSS_END_API
