#pragma once
/// @file
/// CPU reference renderer for subsurface scattering in meshes, in double precision: the ground
/// truth the GPU renderer (MeshScatteringRenderer, Dal Corso et al. 2017) is measured against
/// with computeErrorMetrics() (sss/image_compare.h). It integrates the same directional dipole
/// BSSRDF (sss/bssrdf.h, the very formula text of the shaders) over the lit surface by Monte
/// Carlo with shadow rays, without light buffers, scattering maps or disks.
///
/// THE MODEL (the GPU renderer implements it; the differences are its approximations):
///
/// Geometry. The mesh is placed in the world by the model matrix M: positions M p, vertex
/// normals transpose(inverse(M3)) n (not normalised per vertex). A point on a triangle with
/// barycentric weights b has position sum b_k (M p_k) and normal normalize(sum b_k (M^-T n_k))
/// (what the rasteriser interpolates). All lengths are world (scene) units; the material's
/// mm^-1 coefficients are converted with deriveDipoleConstants(material, millimetresPerUnit).
///
/// Camera. Pixel (x, y) of a W x H image, row 0 at the top, has its centre at
///   ndc = ((x + 0.5) / W * 2 - 1, 1 - (y + 0.5) / H * 2);
/// its ray is the segment from unproject(ndc, z = -1) to unproject(ndc, z = +1) through
/// inverse(camera.projection(W / H) * camera.view()) (so it is clipped to [near, far]). The
/// first triangle it hits gives x_o. A pixel whose ray hits nothing is the background.
/// w_o is the unit vector from x_o back along the ray: towards the eye for a perspective camera,
/// the reversed view direction for an orthographic one.
///
/// Facing (two-sided, as gl_FrontFacing on the GPU). The geometric normal of a triangle is
/// cross(P1 - P0, P2 - P0) of its world vertices, negated when det(M3) < 0 (a mirroring model
/// keeps counter-clockwise = front). The interpolated normal n_o is negated when the geometric
/// normal faces away from w_o; n_i is negated when it faces away from w_i. On a closed mesh with
/// outward normals neither flip happens for any point that contributes (a face turned away from
/// the viewer is hidden, one turned away from the light is in shadow).
///
/// Radiance (linear RGB, no gamma, no specular; S_d and the single-scattering term S1 are those
/// of MeshReferenceOptions::profile, S1 = 0 for the paper's dipole):
///   L_o = T(eta, n_o . w_o) * sum over lights l of
///         integral over the surface A of T(eta, n_i . w_i) S_d(x_i, n_i, w_i; x_o, n_o)
///                                       E_l(x_i) max(n_i . w_i, 0) V_l(x_i) dA_i
///       + sum over lights l of S1(n_o, w_l, w_o) E_l(x_o) max(n_o . w_l, 0) V_l(x_o)
/// with T = fresnelTransmittance(), S_d = evaluateSd() (per channel, unit^-2) and
///  - directional light: w_i = -normalize(direction), E = color * intensity;
///  - point light: w_i = normalize(position - x_i), E = color * intensity / |position - x_i|^2;
///    a spot light is a point light whose E is times spotConeFactor() at x_i;
///  - V_l = 1 when the segment from x_i towards the light (to infinity for a directional light,
///    to the light's position for a point light) meets no triangle of the mesh. The shadow ray
///    starts 1e-7 scene diagonals off the surface, on the geometric side facing the light.
/// Alpha is 1 where the mesh is hit and 0 elsewhere.
///
/// Estimator. Per pixel, independent unbiased samples x_i over the whole surface, weighted
/// f / pdf; the lights share each sample (one shadow ray per light). The pdf picks a triangle
/// in proportion to
///   0.9 * area * kbar * lightFactor / sum + 0.1 * area / total area,
/// where kbar is the sampling kernel averaged over the triangle and lightFactor says roughly how
/// much light the triangle gets (mean radiance times the largest vertex-normal cosine, times
/// 0.01 + 0.99 * the unshadowed fraction of four probe points). The kernel is the planar,
/// normal-incidence S_d profile of the material with each channel normalised to unit integral,
/// summed over channels. Triangles near x_o are split into m x m equal sub-triangles (m <= 32;
/// cells about half as large as their distance to x_o, down to half the kernel's half-width);
/// kbar is then the midpoint rule over the cells, one of which is chosen with probability
/// 0.9 * k(cell) / sum + 0.1 / m^2, else kbar = k(distance to the centroid). The point is
/// uniform within the chosen triangle or cell. The uniform-area share keeps the pdf positive
/// wherever the integrand may be, so the heuristics cost only variance, never bias.
/// Sampling stops per pixel once every channel's standard error of the mean is at most
/// max(targetRelativeError * mean, absoluteError) (tested every 16 samples from minSamples
/// on), or at maxSamples. Each pixel has its own random stream (seed, pixel index), so the
/// image does not depend on the number of threads.

#include "sss/api.h"
#include "sss/bssrdf.h"
#include "sss/camera.h"
#include "sss/image.h"
#include "sss/light.h"
#include "sss/materials.h"
#include "sss/mesh.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

SSS_BEGIN_API

namespace sss {

/// Convergence and scene options of renderMeshReference().
struct MeshReferenceOptions {
    /// Per-pixel, per-channel target for standard error / mean of the pixel value, in [0, 1)
    /// (default: 0.01). 0 runs every covered pixel to maxSamples.
    double targetRelativeError = 0.01;
    /// A channel also counts as converged when its standard error is at most this, in radiance
    /// units, >= 0 (default: 0: purely relative). Bounds the work on nearly black pixels.
    double absoluteError = 0.0;
    /// Samples before the first convergence test, >= 2 (default: 64).
    int minSamples = 64;
    /// Sample cap per pixel, >= minSamples (default: 65536).
    int maxSamples = 1 << 16;
    /// Colour of pixels whose ray misses the mesh (alpha 0) (default: black).
    glm::dvec3 background{0.0};
    /// Millimetres per scene unit for the material coefficients, finite and > 0 (default: 1000,
    /// as ScatteringScale).
    double millimetresPerUnit = 1000.0;
    /// Worker threads, >= 0; 0 = std::thread::hardware_concurrency() (default: 0).
    int threads = 0;
    /// Seed of the per-pixel random streams (default: 1).
    uint64_t seed = 1;
    /// The subsurface profile, as MeshRenderOptions::profile (default: Calibrated). The
    /// calibrated profile's single scattering is added per pixel, exactly (shadow ray per light).
    ScatteringProfile profile = ScatteringProfile::Calibrated;
};

/// What renderMeshReference() returns.
struct MeshReferenceResult {
    /// Radiance per pixel (rgb) and coverage (a: 1 on the mesh, 0 on the background).
    Image image{1, 1};
    /// Standard error of each pixel's mean (rgb, radiance units; 0 on the background) and the
    /// number of samples taken there (a).
    Image standardError{1, 1};
    /// Largest standard error / mean over covered pixels and channels with a mean > 0 and a
    /// standard error above absoluteError (those below it met the target absolutely).
    double maxRelativeStandardError = 0.0;
    /// sqrt(sum of squared standard errors / sum of squared means) over all covered pixels and
    /// channels: the expected relRmse (computeErrorMetrics) of this image against the exact one.
    double relativeRmseEstimate = 0.0;
    /// Mean samples per covered pixel (0 if none).
    double meanSamplesPerPixel = 0.0;
    /// Pixels whose ray hits the mesh.
    int coveredPixels = 0;
    /// Covered pixels that stopped at maxSamples before meeting the error target.
    int unconvergedPixels = 0;
};

/// Renders the reference image of `mesh` placed by `model`, made of `material`, lit by
/// `lights` (any number, each validated; none gives black on the mesh), seen by `camera` in a
/// width x height image. See the file comment for the model and the estimator.
/// @throws Error InvalidArgument for a size outside [1, kMaxImageSide], invalid options (naming
///         the MeshReferenceOptions field), an invalid material or light, a model matrix that is
///         not finite or singular, or a mesh with zero surface area.
MeshReferenceResult renderMeshReference(const Mesh& mesh, const glm::mat4& model, const ScatteringMaterial& material,
                                        const std::vector<Light>& lights, const Camera& camera, int width, int height,
                                        const MeshReferenceOptions& options = {});

/// The same for a textured material (sss/materials.h): its reflectance texture, or else the
/// mesh's base colour, gives each point its coefficients by materialFromReflectance(), sampled
/// bilinearly (repeating) at the point's interpolated texture coordinates. The light leaving x_o
/// follows x_o's profile, scaled to an effective medium: the geometric mean of what the entry
/// points' materials gather (weighted by the light each brings, from this renderer's own samples)
/// and of the texture around x_o, over x_o's own. The rule the GPU renderer implements
/// (docs/textured-materials.md). Single scattering is x_o's.
/// @throws Error InvalidArgument as above, and when there is no texture or the mesh has no
///         texture coordinates.
MeshReferenceResult renderMeshReference(const Mesh& mesh, const glm::mat4& model, const TexturedScattering& material,
                                        const std::vector<Light>& lights, const Camera& camera, int width, int height,
                                        const MeshReferenceOptions& options = {});

}  // namespace sss

SSS_END_API
