#pragma once
/// @file
/// Physical ground truth for subsurface scattering: a Monte Carlo random walk, in double
/// precision, through a homogeneous medium bounded by a smooth dielectric, and the exact
/// (Chandrasekhar H-function) results it is validated against. Nothing here is a diffusion
/// approximation; the dipoles of sss/bssrdf.h are measured against it. The same medium inside
/// a closed triangle mesh, rendered as an image: renderMeshRandomWalk(), its own section below.
/// Two materials side by side in the half-space (the edge of a texture): simulateSplitSlab(),
/// also in its own section.
///
/// THE MODEL (simulateSlab()):
///
/// Geometry. The medium fills the half-space z < 0; its boundary is the plane z = 0, a smooth
/// (specular) interface between the outside (index n_out) and the medium (n_in), relative index
/// eta = n_in / n_out = ScatteringMaterial::eta. It is infinite in x and y. Lengths in mm.
///
/// Medium, per RGB channel c: absorption sigma_a[c] and scattering sigma_s[c] (mm^-1,
/// ScatteringMaterial::sigmaA, sigmaS), extinction sigma_t = sigma_a + sigma_s, single-scattering
/// albedo sigma_s / sigma_t, Henyey-Greenstein phase function of mean cosine g (positive = forward;
/// |g| < 1e-3 is sampled as exactly isotropic). The presets of sss/materials.h store the REDUCED
/// sigma_s' with g = 0, so a walk with a preset is the isotropic walk of the similarity relation,
/// the medium the diffusion models describe; pass (sigma_s, g) for the anisotropic one.
///
/// Light. A collimated pencil beam of unit power meets the boundary at the origin at
/// `incidenceDeg` to the normal (in the x-z plane). A fraction F(theta_i) (exact unpolarised
/// Fresnel reflectance) is reflected specularly: that is `specular`, exact, not subsurface light.
/// The rest, 1 - F, is refracted into the medium by Snell's law. By translation invariance every
/// total below (a fraction of the incident power) equals the same quantity per unit area for a
/// uniform, infinitely wide beam of unit irradiance on the surface (irradiance, not power per
/// area normal to the beam), so the radiances below are per unit incident irradiance.
///
/// Transport (analog: every path carries the same weight 1 - F(theta_i) from entry to its end).
/// Free paths are -ln(xi) / sigma_t. At a collision the path is absorbed with probability
/// sigma_a / sigma_t, else it scatters (a new direction from the phase function). A path that
/// reaches z = 0 from inside at cosine mu to the normal is reflected with probability
/// F_in(mu), the exact unpolarised Fresnel reflectance for the inside-to-outside crossing (1 under
/// total internal reflection, eta sin(theta) >= 1), and otherwise leaves, refracted, at
/// cos(theta_o) = sqrt(1 - eta^2 (1 - mu^2)). A path ends when it leaves (diffuse reflection),
/// is absorbed, or is truncated: it would scatter for the (maxEvents + 1)-th time. Truncation is
/// the only bias and its size is reported (`truncated`); it matters only when sigma_a is 0 or
/// nearly so (an albedo-1 walk in a half-space always returns, but after a heavy-tailed number of
/// events, P(more than n) ~ n^-1/2). There is no Russian roulette.
///
/// Tallies, per channel, as fractions of the incident power:
///  - diffuse: leaves through the boundary; = single + multiple. single: the path scattered
///    exactly once (it may have been reflected internally before leaving); multiple: twice or
///    more. (Unscattered light cannot come back out of a half-space.)
///  - absorbed, truncated. Per path exactly one of leaving, absorbed, truncated happens, so
///    specular + diffuse + absorbed + truncated = 1 to rounding.
///  - Outgoing radiance, azimuthally averaged, per unit incident irradiance, in bins of
///    cos(theta_o) (outside) uniform in [0, 1]: the power leaving into the bin divided by its
///    projected solid angle pi (mu2^2 - mu1^2). coneRadiance: the same for the cone
///    theta_o <= coneHalfAngleDeg around the normal (projected solid angle pi sin^2(half angle)),
///    i.e. the radiance leaving near the normal, averaged with weight cos(theta_o) over the cone.
///  - Radial exit profile R(r), azimuthally averaged, in mm^-2: the power leaving through the
///    annulus r1 <= r < r2 around the entry point, divided by its area pi (r2^2 - r1^2), for
///    profileBins equal annuli out to profileMaxRadius; light leaving farther is in diffuse only.
///    (Under oblique incidence the profile is not radially symmetric; this is its ring average.)
///
/// Statistics. Each channel runs `paths` independent paths. Every tally above is w0 times the
/// fraction p of paths that did the thing (w0 = 1 - F(theta_i)) over a normalisation, so the
/// standard error is that of a binomial proportion, w0 sqrt(p (1 - p) / paths) / normalisation:
/// the standard deviation of the estimate over repeated runs; about 68 % of runs land within one
/// of the exact value (truncation aside), 99.7 % within three. Paths are split into chunks of
/// 16384 in a fixed order, each chunk with its own random stream (xoshiro256++, its state drawn by
/// splitmix64 from a hash of (seed, channel, chunk)), and all tallies are integer counts, so the
/// result is bit-identical for a given seed whatever the number of threads.
///
/// The exact references (chandrasekharH(), isotropicHalfSpaceReflectance()) hold for isotropic
/// scattering (g = 0) in a half-space; see each function.

#include "sss/api.h"
#include "sss/bssrdf.h"
#include "sss/camera.h"
#include "sss/image.h"
#include "sss/light.h"
#include "sss/mesh.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

SSS_BEGIN_API

namespace sss {

/// Options of simulateSlab().
struct SlabRandomWalkOptions {
    /// Paths per channel, >= 1 (default: 1000000). The standard error falls as 1 / sqrt(paths).
    std::int64_t paths = 1'000'000;
    /// Seed of the random streams (default: 1). Same seed, same result, whatever `threads`.
    std::uint64_t seed = 1;
    /// Worker threads, >= 0; 0 = std::thread::hardware_concurrency() (default: 0).
    int threads = 0;
    /// Scattering events after which a path is truncated (counted in `truncated`), >= 1
    /// (default: 1000000). Costs time only for media with albedo very close to 1.
    std::int64_t maxEvents = 1'000'000;
    /// Half-angle of the exit cone around the normal for coneRadiance, degrees, in (0, 90]
    /// (default: 5).
    double coneHalfAngleDeg = 5.0;
    /// Bins of the outgoing-radiance table, uniform in cos(theta_o) on [0, 1], in [1, 100000]
    /// (default: 20).
    int angleBins = 20;
    /// Outer radius of the radial exit profile, mm, finite and > 0 (default: 10).
    double profileMaxRadius = 10.0;
    /// Equal-width annuli of the radial exit profile, in [1, 1000000] (default: 100).
    int profileBins = 100;
    /// Thickness of the medium in mm, > 0; infinity (the default) is the half-space. A finite
    /// value makes it the slab -thickness < z < 0 with a second smooth boundary at the bottom (the
    /// same eta, the same exact Fresnel crossing); what leaves through it is tallied in
    /// SlabChannelResult::transmitted and the fields after it. The tallies of the top boundary
    /// keep their meaning (light that comes back out of the top unscattered, after an internal
    /// reflection at the bottom, counts as ballistic).
    double thickness = std::numeric_limits<double>::infinity();
};

/// A Monte Carlo estimate and its standard error (see the file comment).
struct Estimate {
    double value = 0.0;
    double standardError = 0.0;
};

/// The tallies of one channel (see the file comment), all per unit incident power or irradiance.
struct SlabChannelResult {
    Estimate diffuse;    ///< total diffuse reflectance: power leaving through the boundary
    Estimate single;     ///< part of `diffuse` that scattered exactly once
    Estimate multiple;   ///< part of `diffuse` that scattered twice or more
    Estimate absorbed;   ///< power absorbed in the medium
    Estimate truncated;  ///< power of paths truncated at maxEvents (bias bound; 0 in most media)
    Estimate coneRadiance;        ///< radiance leaving within coneHalfAngleDeg of the normal
    Estimate coneRadianceSingle;  ///< its single-scattering part
    /// Outgoing radiance per cos(theta_o) bin (SlabRandomWalkResult::angleBinEdges), sr^-1.
    std::vector<Estimate> angleRadiance;
    std::vector<Estimate> angleRadianceSingle;  ///< its single-scattering part
    /// Radial exit profile R(r) per annulus (SlabRandomWalkResult::profileBinEdges), mm^-2.
    std::vector<Estimate> profile;
    std::vector<Estimate> profileSingle;  ///< its single-scattering part
    /// Finite slabs (SlabRandomWalkOptions::thickness): power leaving through the bottom after
    /// scattering at least once (single + multiple), its single-scattering part, the power
    /// leaving unscattered through either face (the refracted beam attenuated by
    /// exp(-sigma_t thickness / cos), after internal reflections), and the radiance leaving the
    /// bottom within coneHalfAngleDeg of its normal after scattering (per unit irradiance on the
    /// top). All 0 for the half-space. diffuse + transmitted + ballistic + absorbed + truncated +
    /// specular = 1.
    Estimate transmitted;
    Estimate transmittedSingle;
    Estimate ballistic;
    Estimate transmittedConeRadiance;
    std::int64_t truncatedPaths = 0;      ///< number of truncated paths
    double meanEvents = 0.0;              ///< mean scattering events per path (the cost)
};

/// What simulateSlab() returns.
struct SlabRandomWalkResult {
    std::array<SlabChannelResult, 3> channels;  ///< R, G, B
    /// Specular reflectance F(theta_i) at entry, exact (no variance), the same for all channels.
    double specular = 0.0;
    double incidenceDeg = 0.0;
    std::int64_t paths = 0;  ///< paths per channel
    double coneHalfAngleDeg = 0.0;
    std::vector<double> angleBinEdges;    ///< cos(theta_o) edges, angleBins + 1 values from 0 to 1
    std::vector<double> profileBinEdges;  ///< radius edges in mm, profileBins + 1 values from 0
};

/// Random walk in the semi-infinite medium z < 0 made of `material` (validated; see
/// ScatteringMaterial::validate()), lit by a pencil beam at `incidenceDeg` degrees to the normal.
/// See the file comment for the model, the tallies and the standard errors.
/// @throws Error InvalidArgument for an invalid material, an incidence angle outside [0, 90) or
///         not finite, or invalid options (naming the SlabRandomWalkOptions field).
SlabRandomWalkResult simulateSlab(const ScatteringMaterial& material, double incidenceDeg,
                                  const SlabRandomWalkOptions& options = {});

/// Chandrasekhar's H-function for isotropic scattering with single-scattering albedo `albedo`
/// in [0, 1], at `mu` in [0, 1]: the solution of
///   1 / H(mu) = sqrt(1 - albedo) + (albedo / 2) integral_0^1 mu' H(mu') / (mu + mu') dmu',
/// solved on a graded composite Gauss-Legendre rule (about 1e-9 relative) and evaluated
/// at `mu` by the same equation. H(albedo = 1, mu = 1) = 2.90781.
/// @throws Error InvalidArgument for an albedo or mu outside [0, 1] or not finite.
double chandrasekharH(double albedo, double mu);

/// Exact reflectance of a semi-infinite, isotropically scattering medium of single-scattering
/// albedo `albedo` below a smooth dielectric of relative index `eta` (n_inside / n_outside), lit
/// by a collimated beam at `incidenceDeg`: the values simulateSlab() estimates for g = 0 (its
/// specular, diffuse, single, multiple and cone radiance). For eta = 1 the diffuse reflectance is
/// the plane albedo 1 - H(mu0) sqrt(1 - albedo), with the reflected radiance
/// L(mu) = albedo / (4 pi) H(mu0) H(mu) / (mu + mu0) per unit irradiance. For eta != 1 the
/// Fresnel reflections inside are added by solving the adding equation
///   L_up(mu) = rho(mu, mu0') E' + 2 pi integral_0^1 rho(mu, mu') F_in(mu') L_up(mu') mu' dmu'
/// for the upward radiance just inside (rho the index-matched reflection function above, mu0' and
/// E' = 1 - F(theta_i) the refracted beam), which is exact because isotropic scattering makes
/// the reflected radiance independent of azimuth; what leaves is (1 - F_in) L_up, with radiance
/// divided by eta^2 outside. Single scattering is the same with H = 1 and no internal reflection
/// back into the medium (it can only come back by scattering again).
struct HalfSpaceReflectance {
    double specular = 0.0;      ///< F(theta_i)
    double diffuse = 0.0;       ///< power leaving after scattering, per incident power
    double single = 0.0;        ///< part of diffuse that scattered exactly once
    double multiple = 0.0;      ///< diffuse - single
    double coneRadiance = 0.0;  ///< radiance leaving within coneHalfAngleDeg of the normal
};

/// See HalfSpaceReflectance. `coneHalfAngleDeg` as SlabRandomWalkOptions (default: 5).
/// @throws Error InvalidArgument for an albedo outside [0, 1], an eta outside [0.4, 2.5], an
///         incidence outside [0, 90) or a cone half-angle outside (0, 90] (or any not finite).
HalfSpaceReflectance isotropicHalfSpaceReflectance(double albedo, double eta, double incidenceDeg,
                                                   double coneHalfAngleDeg = 5.0);

// ---- two materials side by side -------------------------------------------------------------

/// THE SPLIT HALF-SPACE (simulateSplitSlab()): the walk of simulateSlab() in a medium made of two
/// materials side by side, the ground truth for a material that changes across a surface (a
/// texture edge). Everything not said here is as in the file comment.
///
/// Geometry. The half-space z < 0 below the smooth boundary z = 0. Material `left` fills x < 0
/// and `right` fills x >= 0, through the whole depth: the plane x = 0 inside the medium is
/// index-matched (both materials have the same eta), so light crosses it unchanged and only the
/// coefficients change there. Infinite in y.
///
/// Light. A collimated beam at normal incidence of unit irradiance on the strip |x| <= W
/// (entryHalfWidth), all y. By translation invariance in y each path stands for a unit length
/// of the strip in y: it enters at x uniform in [-W, W] (y irrelevant), carries the power
/// 2 W (1 - F(0)) / paths (F(0) the exact Fresnel reflectance at normal incidence, `specular`)
/// and goes straight down (normal incidence does not bend the beam).
///
/// Transport, per channel, analog as simulateSlab(). Free flights are exact for the
/// piecewise-constant extinction: each flight draws an optical depth tau = -ln(xi) and spends it
/// along the ray at the local sigma_t; where the ray meets the plane x = 0 before tau is used up
/// it crosses with the optical depth it has left (tau minus sigma_t of the side it leaves times
/// the distance) and goes on at the other side's sigma_t. (Not delta tracking: no null
/// collisions, no majorant.) At a collision the path is absorbed with probability
/// sigma_a / sigma_t of the material it is in, else it scatters with that material's g
/// (Henyey-Greenstein). At z = 0: exact Fresnel reflection or refraction out (total internal
/// reflection included), as simulateSlab(); a reflection starts a new flight. Truncation at
/// maxEvents as simulateSlab(), counted.
///
/// Tallies, per channel. radiosity: the power leaving through the boundary per unit area, per
/// unit incident irradiance, in `bins` equal bins of the exit point's x over [-T, T]
/// (tallyHalfWidth): with k of the paths leaving in a bin of width dx,
///   radiosity = (k / paths) 2 W (1 - F(0)) / dx   (power per unit length in y over the bin's area
/// per unit length in y). Far from x = 0 (many diffusion lengths) and from the strip's ends it is
/// the uniformly lit half-space of that material: simulateSlab(material, 0).diffuse of its channel.
/// Light that entered beyond |x| = W is missing: where both sides are one material a bin at
/// |x| <= T is low by at most the power of simulateSlab() that leaves farther than W - T from its
/// entry point (its radial profile), so take W - T many diffusion lengths 1 / sigma_tr. The
/// defaults (W - T = 15 mm) suit diffusion lengths up to about 1.5 mm; potato's red (14 mm)
/// loses 1.2e-3 of its 0.76 beyond 57 mm and 5e-5 beyond 97 mm.
/// diffuse, absorbed, truncated: fractions of the power incident on the strip, so that
/// specular + diffuse + absorbed + truncated = 1 to rounding.
///
/// Statistics as simulateSlab(): each channel runs `paths` paths in chunks of 16384, each chunk its
/// own xoshiro256++ stream keyed by (seed, channel, chunk) (a family of streams apart from
/// simulateSlab()'s, so the two are independent for the same seed), all tallies integer counts:
/// bit-identical for a seed whatever the thread count. Each estimate is w p / normalisation with a
/// binomial proportion p, standard error w sqrt(p (1 - p) / paths) / normalisation.

/// Options of simulateSplitSlab().
struct SplitSlabOptions {
    /// Paths per channel, >= 1 (default: 4000000). Only about T / W of them leave inside the
    /// tallied strip; a bin's standard error falls as 1 / sqrt(paths).
    std::int64_t paths = 4'000'000;
    /// Seed of the random streams (default: 1). Same seed, same result, whatever `threads`.
    std::uint64_t seed = 1;
    /// Worker threads, >= 0; 0 = std::thread::hardware_concurrency() (default: 0).
    int threads = 0;
    /// Scattering events after which a path is truncated (counted in truncatedPaths), >= 1
    /// (default: 1000000). Costs time only for media with albedo very close to 1.
    std::int64_t maxEvents = 1'000'000;
    /// Half-width W of the lit strip, mm: light enters uniformly on -W <= x <= W at normal
    /// incidence; finite and > 0 (default: 20).
    double entryHalfWidth = 20.0;
    /// Half-width T of the tallied strip, mm: exits are binned over -T <= x <= T; finite, > 0 and
    /// <= entryHalfWidth (default: 5).
    double tallyHalfWidth = 5.0;
    /// Equal-width bins over [-T, T], in [1, 1000000] (default: 40). An even count puts a bin edge
    /// on the interface x = 0; an odd count puts a bin centre there.
    int bins = 40;
};

/// What simulateSplitSlab() returns; every array is indexed by channel (R, G, B).
struct SplitSlabResult {
    std::vector<double> binEdges;    ///< x of the bin edges in mm, bins + 1 values from -T to T
    std::vector<double> binCentres;  ///< x of the bin centres in mm, bins values
    /// Radiosity leaving the boundary per bin, per unit incident irradiance (see the section
    /// comment): the diffuse reflectance of the material underneath far from the interface.
    std::array<std::vector<Estimate>, 3> radiosity;
    /// Power leaving the boundary anywhere (not only in the bins), absorbed, and truncated at
    /// maxEvents, each per unit power incident on the strip |x| <= W.
    std::array<Estimate, 3> diffuse;
    std::array<Estimate, 3> absorbed;
    std::array<Estimate, 3> truncated;
    std::array<std::int64_t, 3> truncatedPaths{};  ///< number of truncated paths (bias bound; 0 in most media)
    std::array<double, 3> meanEvents{};            ///< mean scattering events per path (the cost)
    /// Specular reflectance F(0) at entry, exact, the same for all channels and both materials.
    double specular = 0.0;
    std::int64_t paths = 0;       ///< paths per channel
    double entryHalfWidth = 0.0;  ///< W, mm
    double tallyHalfWidth = 0.0;  ///< T, mm
};

/// Random walk in the half-space z < 0 made of `left` (x < 0) and `right` (x >= 0), each
/// validated (see ScatteringMaterial::validate()), lit at normal incidence on |x| <= W. See the
/// section comment for the model, the tallies and their normalisation.
/// @throws Error InvalidArgument for an invalid material (the message says which), materials
///         with different eta (naming both), or invalid options (naming the SplitSlabOptions
///         field).
SplitSlabResult simulateSplitSlab(const ScatteringMaterial& left, const ScatteringMaterial& right,
                                  const SplitSlabOptions& options = {});

// ---- inside a closed triangle mesh ----------------------------------------------------------

/// THE MESH WALK (renderMeshRandomWalk()): the medium of simulateSlab() filling the inside of a
/// closed triangle mesh, rendered as an image of the light that leaves it after scattering.
///
/// Geometry, camera, facing and lights as renderMeshReference() (sss/mesh_reference.h): the
/// mesh is placed by the model matrix, pixel (x, y) has its ray through its centre clipped to
/// [near, far], the first triangle hit gives x_o and w_o points back along the ray, directional
/// lights give irradiance E = color * intensity normal to the beam from direction w_l =
/// -normalize(direction), point lights E = color * intensity / |position - x|^2 from w_l =
/// normalize(position - x), spot lights that times spotConeFactor() at x. Normals are the
/// interpolated vertex normals (transformed by the inverse transpose, normalised), turned to
/// the side of the triangle's geometric normal that faces the ray that meets it; where a
/// shading normal would send a refracted or reflected direction to the wrong side of the
/// triangle itself (or faces away from the ray), that one event uses the geometric normal
/// instead. Lengths are scene units; the material's mm^-1 coefficients are multiplied by
/// millimetresPerUnit. Radiance is linear RGB in the lights'
/// units (per unit E, per steradian); alpha is 1 where the camera ray hits the mesh.
///
/// What is rendered: the radiance at x_o towards the eye from light that entered the medium,
/// scattered at least once and left at x_o. Not included: the specular reflection at x_o (the
/// renderers compare subsurface light only), light transmitted without scattering, light that
/// leaves the mesh and enters it again elsewhere (a concave mesh lighting itself), and light
/// from a point of the surface other than through refraction of the delta lights.
///
/// Radiance across the boundary. Radiance / n^2 is conserved by a smooth refraction, so light
/// leaving a medium of relative index eta with Fresnel transmittance T has radiance
/// T * L_inside / eta^2 outside, and light going in T * eta^2 * L_outside inside. A collimated
/// beam of irradiance E (normal to the beam) meeting the surface at cos_out = n . w_l to the
/// normal is refracted into a beam of irradiance (normal to it) E * T * cos_out / cos_in inside,
/// cos_in = sqrt(1 - (1 - cos_out^2) / eta^2), the power per unit surface area E cos_out T
/// spread over the narrower (eta > 1) refracted cross-section.
///
/// The estimator: adjoint paths from the eye, one RGB channel per path. The pixel value is
/// L = (T(eta, n_o . w_o) / eta^2) * L_in, where L_in is the radiance inside at x_o travelling
/// back along the refracted camera ray, which starts the path in direction a_0 =
/// refract(-w_o, n_o). Along a path of current direction a:
///  - A free path s = -ln(xi) / sigma_t (per channel). If the ray p + t a meets the mesh at
///    t < s (BVH closest hit), the path is at the boundary: it is reflected specularly with the
///    exact unpolarised Fresnel reflectance F (1 under total internal reflection), else it
///    leaves and ends: outside there are only delta lights, which no sampled direction hits.
///  - Else it collides at p = p + s a. With survival weighting the path weight w is multiplied
///    by the albedo sigma_s / sigma_t (the collision pdf is sigma_t exp(-sigma_t s), the in-
///    scattering term of the transfer equation sigma_s exp(-sigma_t s) times the in-scattered
///    radiance), and then:
///  - Next-event estimation through the boundary, per light: the in-scattered radiance of the
///    unscattered, refracted beam at p is exactly p_HG(d . (-a)) * E_in(p), d the beam's
///    propagation direction inside and E_in its irradiance normal to it,
///      E_in(p) = E(x) * T(eta, n(x) . w_l) * cos_out / cos_in * exp(-sigma_t |p - x|) * V(x),
///    where x is the surface point where the beam that reaches p entered, n(x) its normal and
///    V(x) = 1 when a shadow ray from x (just off the surface) to the light meets no triangle.
///    x is found by fixed-point iteration: d = refract(-w_l, n) with n first the normal at the
///    light's previous entry point on this path (at the start, or after an internal
///    reflection, the normal met there); x = the first hit of the ray from p along -d; d is
///    recomputed from n(x) (and w_l from x, for a point light); repeated until d changes by less
///    than 1e-9 or the triangle hit is the one of the previous guess, 4 ray queries at most. The
///    geometry (x on the ray from p along -d) is the last traced one; T and cos_out / cos_in are
///    those at x. (On a flat face one query suffices; with interpolated normals the direction
///    used may differ from the converged one by the change of the normal within a triangle.)
///    Exact for a planar boundary and a directional light (the "large box" test reproduces the
///    slab); on a curved boundary it neglects the focusing or spreading of the refracted beam
///    (its Jacobian, caustics), any other entry point whose refracted ray also reaches p, and
///    for a point light the divergence of the beam over |p - x| inside (the 1 / distance^2 is
///    taken at x). It is the usual single-scattering approximation of renderers, not a bias of
///    the walk itself.
///  - The path scatters: a new direction from the Henyey-Greenstein phase function around a
///    (radiance arriving from -a' and leaving along -a turns by a' . a, so sampling around the
///    adjoint direction is sampling the phase function), w unchanged.
///  - Russian roulette once w < 1/4: the path goes on with probability 4 w, at weight 1/4.
///  - Truncation: a path that would scatter for the (maxEvents + 1)-th time ends, counted in
///    truncatedPaths: the only bias, as in simulateSlab().
/// A path's value X = (T_o / eta^2) * sum over its collisions of w * NEE is an unbiased
/// estimate of the pixel's radiance (truncation aside); X_1, its first collision's term only, of
/// its single-scattering part (paths that scattered exactly once, internal reflections before
/// that included, as in simulateSlab()).
///
/// Acceleration (unbiased; it changes the cost, not the expected value). A grid of lower
/// bounds on the distance from any point of a cell to the surface (exact distances at the cell
/// centres near the surface minus half the cell diagonal; farther away an exact distance
/// transform of the cells the triangles touch minus a cell diagonal): a free path shorter than
/// the bound at its start cannot reach the boundary, so its ray query is skipped (this changes
/// nothing in the result: with neeRoulette off the image is bit-identical with and without the
/// grid). And Russian roulette on the next-event estimation at p, in two stages: it is made with
/// probability q1 = exp(-sigma_t * bound(p)); once the first query has found the distance t to
/// the entry point (t >= bound), each light's beam is followed on (fixed point, shadow ray) with
/// probability q2 = exp(-sigma_t t) / q1; the term is divided by q1 q2 = exp(-sigma_t t), so it
/// is never larger than the same term at the surface (no spikes), and deep collisions, whose
/// beams are attenuated to nothing, cost a grid lookup instead of several ray queries.
///
/// Open meshes: a path only ends at the boundary when it crosses a triangle; through a hole
/// the medium goes on outside until the path leaves the mesh's bounding box (it then ends,
/// counted in escapedPaths: 0 for a closed mesh, up to rounding).
///
/// Statistics. Per pixel and channel, pathsPerPixel independent paths; the pixel is the mean
/// of their values X and its standard error sqrt(sample variance / pathsPerPixel) (the single-
/// scattering image likewise from X_1): about 68 % of renders land within one standard error of
/// the exact value of the model, 99.7 % within three. Each pixel and channel has its own
/// random stream (xoshiro256++ keyed by a hash of (seed, pixel, channel)), so the images are
/// bit-identical for a given seed whatever the number of threads.

/// Options of renderMeshRandomWalk().
struct MeshRandomWalkOptions {
    /// Paths per pixel and channel, >= 1 (default: 256). The standard error falls as 1 / sqrt.
    int pathsPerPixel = 256;
    /// Seed of the random streams (default: 1). Same seed, same images, whatever `threads`.
    std::uint64_t seed = 1;
    /// Worker threads, >= 0; 0 = std::thread::hardware_concurrency() (default: 0).
    int threads = 0;
    /// Scattering events after which a path is truncated (truncatedPaths), >= 1 (default:
    /// 1000000). Costs time only for media with albedo very close to 1.
    std::int64_t maxEvents = 1'000'000;
    /// Millimetres per scene unit for the material coefficients, finite and > 0 (default: 1000,
    /// as ScatteringScale and MeshReferenceOptions).
    double millimetresPerUnit = 1000.0;
    /// Colour of pixels whose ray misses the mesh (alpha 0), finite (default: black).
    glm::dvec3 background{0.0};
    /// Cells of the distance-bound grid over the mesh's bounding box, in [0, 2^26]; 0 = no grid
    /// (every free path queries the BVH; no next-event roulette) (default: 2^20, 4 MiB).
    int distanceGridCells = 1 << 20;
    /// Russian roulette on next-event estimation by the distance bound (see the section
    /// comment); only with a grid (default: true).
    bool neeRoulette = true;
};

/// What renderMeshRandomWalk() returns.
struct MeshRandomWalkResult {
    /// Radiance per pixel (rgb) and coverage (a: 1 on the mesh, 0 on the background).
    Image image{1, 1};
    /// Standard error of each pixel's mean (rgb; 0 on the background) and the paths per channel
    /// taken there (a).
    Image standardError{1, 1};
    /// The single-scattering part of `image` (rgb) and coverage (a).
    Image singleScattering{1, 1};
    /// Standard error of `singleScattering` (rgb) and the paths per channel (a).
    Image singleStandardError{1, 1};
    /// sqrt(sum of squared standard errors / sum of squared means) over all covered pixels and
    /// channels: the expected relRmse of `image` against the exact one (0 if all black).
    double relativeRmseEstimate = 0.0;
    /// Pixels whose ray hits the mesh.
    int coveredPixels = 0;
    /// Mean paths per covered pixel, all three channels together (3 * pathsPerPixel).
    double meanPathsPerPixel = 0.0;
    /// Mean scattering events per path (the cost), over all paths.
    double meanEventsPerPath = 0.0;
    /// Mean BVH queries (free-path, next-event and shadow rays) per path.
    double meanRayQueriesPerPath = 0.0;
    /// Mean next-event estimations made per path (after the roulette).
    double meanNextEventsPerPath = 0.0;
    std::int64_t paths = 0;           ///< paths run in all
    std::int64_t truncatedPaths = 0;  ///< paths truncated at maxEvents (bias bound; 0 in most media)
    std::int64_t escapedPaths = 0;    ///< paths that left the bounding box (open meshes; see above)
    /// Edge of the distance grid's cubic cells in scene units (0 without a grid).
    double distanceGridCellSize = 0.0;
};

/// Renders `mesh` placed by `model`, filled with `material` (validated; see
/// ScatteringMaterial::validate()), lit by `lights` (any number, each validated; none gives
/// black on the mesh), seen by `camera`, in a width x height image, by the random walk above.
/// @throws Error InvalidArgument for a size outside [1, kMaxImageSide], invalid options (naming
///         the MeshRandomWalkOptions field), an invalid material or light, a model matrix that
///         is not finite or singular, or a mesh without triangles or with zero surface area.
MeshRandomWalkResult renderMeshRandomWalk(const Mesh& mesh, const glm::mat4& model, const ScatteringMaterial& material,
                                          const std::vector<Light>& lights, const Camera& camera, int width, int height,
                                          const MeshRandomWalkOptions& options = {});

}  // namespace sss

SSS_END_API
