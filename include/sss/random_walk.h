#pragma once
/// @file
/// Physical ground truth for subsurface scattering: a Monte Carlo random walk, in double
/// precision, through a homogeneous medium bounded by a smooth dielectric, and the exact
/// (Chandrasekhar H-function) results it is validated against. Nothing here is a diffusion
/// approximation; the dipoles of sss/bssrdf.h are measured against it.
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

#include "sss/bssrdf.h"

#include <array>
#include <cstdint>
#include <vector>

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

}  // namespace sss
