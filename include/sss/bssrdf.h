#pragma once
/// @file
/// The directional dipole BSSRDF (Frisvad, Hachisuka, Kjeldsen, ACM TOG 34(1), 2014) on the CPU,
/// in double precision: scattering materials, their derived constants, and the per-pair
/// evaluation. The evaluation compiles the same formula text as the shaders
/// (shaders/common/dirpole.glsl), so this is also the reference the GPU passes are tested against.
///
/// Conventions (all vectors in one world frame):
///  - x_i, n_i: entry point and its outward normal; w_i: direction from x_i TOWARDS the light.
///  - x_o, n_o: exit point and its outward normal; w_o: direction from x_o towards the viewer.
///  - Lengths are in the unit the constants were derived for (deriveDipoleConstants()'s
///    millimetresPerUnit): millimetres by default, scene units when a scale is given.
///  - Results are per RGB channel.

#include "sss/api.h"
#include <glm/vec3.hpp>

#include <array>
#include <limits>
#include <optional>
#include <string>
#include <string_view>

SSS_BEGIN_API

namespace sss {

/// Which subsurface-scattering profile the renderers (GPU and CPU reference) use.
enum class ScatteringProfile {
    /// Physically calibrated (the default): the directional dipole's spatial and directional
    /// shape, with each channel rescaled so that its multiple-scattering reflectance equals the
    /// random walk's (profileCalibrationScale()), plus the single-scattering term the dipole
    /// omits (evaluateSingleScattering()). Measured against the random walk in sss-bench
    /// --accuracy slab.
    Calibrated,
    /// The paper's directional dipole alone (Frisvad et al. 2014, as Dal Corso et al. 2017 use
    /// it): no rescaling, no single scattering. Reproduces the thesis; 22-37 % brighter than the
    /// random walk, and wrong by far at low albedo (ketchup G and B).
    Dipole,
};

/// The calibrated profile's factor is tabulated at these many entry cosines,
/// profileIncidenceNode(i) = 1 - 0.19 i (1 down to 0.05), and interpolated linearly between them.
inline constexpr int kProfileIncidenceNodes = 6;
/// Entry cosine of node i of the calibration, 1 - 0.19 i.
constexpr double profileIncidenceNode(int i) { return 1.0 - 0.19 * i; }
/// The calibrated profile's transmission factor (light going through a thin part, see
/// profileTransmissionScale()) is tabulated at these many reduced optical thicknesses,
/// profileThicknessNode(i) = 0.25 * 2^i (0.25 to 16), its logarithm interpolated linearly in log2
/// between.
inline constexpr int kProfileThicknessNodes = 7;
/// Reduced optical thickness sigma_t' d of node i of the transmission calibration, 0.25 * 2^i.
constexpr double profileThicknessNode(int i) { return 0.25 * static_cast<double>(1 << i); }

/// "calibrated" or "dipole".
std::string_view toString(ScatteringProfile profile);
/// Parses "calibrated" or "dipole" (exact, lower case); nullopt otherwise.
std::optional<ScatteringProfile> parseScatteringProfile(std::string_view name);

/// A homogeneous scattering medium, coefficients per RGB channel in mm^-1.
/// Measured data sets (Jensen 2001, Narasimhan 2006) give only the reduced scattering
/// coefficient sigma_s' = sigma_s (1 - g); store it in sigmaS with g = 0 (see materials.h).
struct ScatteringMaterial {
    glm::dvec3 sigmaA{0.0024, 0.0090, 0.12};  ///< absorption coefficient, mm^-1, each >= 0 (default: potato)
    glm::dvec3 sigmaS{0.68, 0.70, 0.55};      ///< scattering coefficient, mm^-1, each >= 0 (default: potato)
    double g = 0.0;                           ///< Henyey-Greenstein mean cosine, in (-1, 1) (default: 0)
    /// Relative index of refraction n_inside / n_outside, in [0.4, 2.5], the range where the
    /// Fresnel-moment fits stay positive (default: 1.3).
    double eta = 1.3;
    std::string name = "potato";  ///< label for messages and UIs (default: "potato")

    /// Checks every field: finite; sigmaA, sigmaS >= 0; sigmaA + sigmaS (1 - g) > 0 in every
    /// channel (the diffusion coefficient must be finite); g in (-1, 1); eta in [0.4, 2.5].
    /// @throws Error InvalidArgument naming the field and the bad value
    ///         ("ScatteringMaterial::eta must be in [0.4, 2.5], got 0").
    void validate() const;
};

/// Material constants of the directional dipole, derived once per material in double.
/// Per channel (dvec3) unless noted; coefficients in unit^-1 and lengths in unit, where unit is
/// the length unit the constants were derived for.
struct DipoleConstants {
    glm::dvec3 sigmaSPrime{0.0};  ///< reduced scattering sigma_s (1 - g)
    glm::dvec3 sigmaTPrime{0.0};  ///< reduced extinction sigma_s' + sigma_a
    glm::dvec3 sigmaT{0.0};       ///< unreduced extinction sigma_s + sigma_a (back-lit d_r only)
    glm::dvec3 alphaPrime{0.0};   ///< reduced albedo sigma_s' / sigma_t'
    glm::dvec3 D{0.0};            ///< diffusion coefficient 1 / (3 sigma_t')
    /// Effective transport coefficient sqrt(sigma_a / D); 0 where sigma_a = 0 (spectralon), so
    /// samplers that draw distances with it need their own floor.
    glm::dvec3 sigmaTr{0.0};
    /// Extrapolation distance 2.131 D / sqrt(alpha') (paper eq. 21). alpha' is floored at 1e-12
    /// here, so a channel without scattering (merlot G, B) gets a far, not an infinite, virtual source.
    glm::dvec3 de{0.0};
    double eta = 1.0;            ///< relative index n_inside / n_outside
    double twoC1 = 0.0;          ///< 2 C_1(eta), d'Eon-Irving fit
    double threeC2 = 0.0;        ///< 3 C_2(eta), d'Eon-Irving fit
    double cPhi = 0.0;           ///< C_phi(eta) = (1 - 2 C_1(eta)) / 4
    double cE = 0.0;             ///< C_E(eta) = (1 - 3 C_2(eta)) / 2
    double A = 0.0;              ///< boundary mismatch (1 - C_E) / (2 C_phi)
    double cPhiInv = 0.0;        ///< C_phi(1 / eta), which enters only the normalisation
    double normalization = 0.0;  ///< 1 / (4 C_phi(1/eta)) / (4 pi^2)
    double millimetresPerUnit = 1.0;  ///< the length unit of the constants, in mm
    ScatteringProfile profile = ScatteringProfile::Dipole;  ///< the profile these constants describe
    /// Per-channel factor on S_d (1 after deriveDipoleConstants()): renderers fold in a
    /// correction for the part of the profile their sampling disk cuts off.
    glm::dvec3 profileScale{1.0};
    /// Per-channel factor on S_d at the entry cosines profileIncidenceNode(i), interpolated
    /// linearly in w_i . n_i (clamped to [0.05, 1]): 1 for the dipole; for the calibrated profile
    /// profileCalibrationScale(alpha', eta, node) per channel.
    std::array<glm::dvec3, kProfileIncidenceNodes> incidenceScale{
        glm::dvec3(1.0), glm::dvec3(1.0), glm::dvec3(1.0), glm::dvec3(1.0), glm::dvec3(1.0), glm::dvec3(1.0)};
    /// Per-channel factor on S_d where light goes through (the dipole's back-lit branch), at the
    /// reduced optical thicknesses profileThicknessNode(i) of the medium between x_i and x_o
    /// (estimated per pair as sigma_t' (x . n_o - x . n_i) / 2), log-interpolated in log2 thickness
    /// and held at both ends: 1 for the dipole; profileTransmissionScale(alpha', eta, node) per channel
    /// for the calibrated profile.
    std::array<glm::dvec3, kProfileThicknessNodes> transmissionScale{
        glm::dvec3(1.0), glm::dvec3(1.0), glm::dvec3(1.0), glm::dvec3(1.0),
        glm::dvec3(1.0), glm::dvec3(1.0), glm::dvec3(1.0)};
    /// Single-scattering albedo sigma_s / sigma_t (UNREDUCED), per channel.
    glm::dvec3 albedo{0.0};
    double g = 0.0;                 ///< Henyey-Greenstein mean cosine of the single-scattering term
    double singleScattering = 0.0;  ///< weight of the single-scattering term: 1 calibrated, 0 dipole
};

/// 2 C_1(eta), the first Fresnel moment times two (d'Eon and Irving 2011 polynomial fits, branch
/// eta < 1 or eta >= 1).
double fresnelMoment2C1(double eta);

/// 3 C_2(eta), the second Fresnel moment times three (d'Eon and Irving 2011 polynomial fits).
double fresnelMoment3C2(double eta);

/// Validates `material` and derives its constants. Lengths are expressed in a unit of
/// `millimetresPerUnit` mm: coefficients become sigma_mm * millimetresPerUnit, so positions can
/// be passed in scene units directly (1 = millimetres, the default). `profile` sets
/// profileScale and singleScattering (the dipole's fields are the same for both).
/// @throws Error InvalidArgument for an invalid material or a millimetresPerUnit that is not
///         finite and > 0.
DipoleConstants deriveDipoleConstants(const ScatteringMaterial& material, double millimetresPerUnit = 1.0,
                                      ScatteringProfile profile = ScatteringProfile::Dipole);

/// The calibrated profile's factor for one channel of reduced albedo `reducedAlbedo` in [0, 1],
/// relative index `eta` and entry cosine `cosIncidence`: the exact multiple-scattering diffuse
/// reflectance of an isotropic half-space (isotropicHalfSpaceReflectance(), which the random walk
/// reproduces within its standard error) divided by the directional dipole's (T(mu_i) times its
/// plane integral times the hemispherical integral of T). Tabulated by sss-calibrate
/// (src/mesh/profile_calibration_table.inc: 13 eta from 1 to 2.5, 37 albedos dense towards 1, the
/// 6 entry cosines of profileIncidenceNode()); linear in eta, log-linear in s = sqrt(1 - alpha'),
/// linear in the entry cosine (clamped to [0.05, 1]). eta below 1 uses the eta = 1 row, above
/// 2.5 the 2.5 row; alpha' below 2.5e-5 the last column.
/// @throws Error InvalidArgument for an albedo outside [0, 1], or an eta or cosIncidence that is
///         not finite.
double profileCalibrationScale(double reducedAlbedo, double eta, double cosIncidence = 1.0);

/// The calibrated profile's factor for light going THROUGH a slab of reduced optical thickness
/// `opticalThickness` = sigma_t' d, for one channel of reduced albedo `reducedAlbedo` in [0, 1]
/// and relative index `eta`: the random walk's diffuse transmittance (light leaving the far face
/// after scattering at least once; simulateSlab with a finite thickness, normal incidence)
/// divided by the dipole's (profileSlabTransmittance() of the dipole), from the table that
/// sss-calibrate --transmission generates. Thin slabs: the dipole transmits up to 4x too much
/// (diffusion needs several mean free paths); thick ones: too little (it ignores the far face
/// and falls off as exp(-sigma_tr d) / d, not exp(-sigma_tr d)). Interpolated linearly in eta,
/// log-linearly in s = sqrt(1 - alpha') and in log2 of the thickness (the logarithm of the factor) (held at the table's ends:
/// eta in [1, 2.5], thickness in [0.25, 16]).
/// @throws Error InvalidArgument for an albedo outside [0, 1], a thickness not > 0 or an eta that
///         is not finite.
double profileTransmissionScale(double reducedAlbedo, double eta, double opticalThickness);

/// Integral of S_d over the far face of a slab: the entry point at the origin with normal +z, lit
/// at normal incidence, the exit points on the plane z = -thickness with normal -z (the dipole's
/// back-lit branch, including profileScale and the profile's transmissionScale), per channel,
/// without Fresnel factors. Same quadrature as dipolePlaneIntegral().
/// @throws Error InvalidArgument unless thickness is finite and > 0.
glm::dvec3 dipoleSlabTransmissionIntegral(const DipoleConstants& constants, double thickness);

/// Diffuse transmittance of the profile through a slab of thickness `thickness` (constants'
/// unit) lit at normal incidence, per unit incident power: T(eta, 1) times
/// dipoleSlabTransmissionIntegral() times fresnelHemisphereIntegral(). What the random walk's
/// SlabChannelResult::transmitted estimates physically.
glm::dvec3 profileSlabTransmittance(const DipoleConstants& constants, double thickness);

/// Integral of S_d over the plane z = 0 around an entry point at the origin with normal +z,
/// lit from w_i = (sin theta, 0, cos theta) at cos theta = `cosIncidence` in (0, 1], out to
/// distance `maxRadius` (default: infinity), per channel, without Fresnel factors (includes
/// profileScale). Log-spaced midpoint rule in r (and in the azimuth off normal incidence):
/// relative error below 1e-4 on the presets. In units of the constants' length unit^0 (S_d dA).
/// @throws Error InvalidArgument for cosIncidence outside (0, 1] or maxRadius not > 0.
glm::dvec3 dipolePlaneIntegral(const DipoleConstants& constants, double cosIncidence,
                               double maxRadius = std::numeric_limits<double>::infinity());

/// Hemispherical integral of the exit transmittance, integral T(eta, mu) mu dw (sr), by the
/// midpoint rule in mu (1e-8 relative). The radiance leaving at mu per unit plane-integrated
/// S_d is T(mu), so this turns a plane integral into a reflectance.
double fresnelHemisphereIntegral(double eta);

/// Single scattering of a locally flat, semi-infinite medium (the term the dipole omits): the
/// radiance leaving at x towards w_o per unit irradiance on the surface from direction w_i
/// (both outside, unit, n the outward unit normal), per channel, in sr^-1:
///   albedo T(eta, w_i.n) T(eta, w_o.n) p(cos theta') / (eta^2 (mu_i' + mu_o'))
/// with mu' the refracted cosines inside and p the Henyey-Greenstein phase function between the
/// refracted propagation directions; times constants.singleScattering (0 for the dipole).
/// Exact for a half-space with a smooth boundary (checked against the random walk's single
/// tally); zero when either direction is below the surface.
glm::dvec3 evaluateSingleScattering(const DipoleConstants& constants, const glm::dvec3& n, const glm::dvec3& wi,
                                    const glm::dvec3& wo);

/// Total diffuse reflectance of the profile for a semi-infinite medium lit by a collimated beam at
/// cos theta = `cosIncidence`, per unit incident power: T(mu_i) dipolePlaneIntegral() times
/// fresnelHemisphereIntegral(), plus the single-scattering term integrated over the exit
/// hemisphere. Energy conservation asks for <= 1.
glm::dvec3 profileDiffuseReflectance(const DipoleConstants& constants, double cosIncidence);

/// Radiance leaving a half-space of the profile's medium towards the unit direction `wo`
/// (normal +z) per unit irradiance on the surface from a collimated beam at cos theta =
/// `cosIncidence` (w_i = (sin theta, 0, cos theta)), per channel, in sr^-1: T(mu_i) times
/// dipolePlaneIntegral() times T(mu_o), plus evaluateSingleScattering(). This is what a renderer
/// of the profile gives at the middle of a wide, thick, evenly lit slab, and what the slab random
/// walk's radiance estimates physically (sss-bench --accuracy slab).
glm::dvec3 profileSlabRadiance(const DipoleConstants& constants, double cosIncidence, const glm::dvec3& wo);

/// profileSlabRadiance() averaged over the exit cone theta_o <= `coneHalfAngleDeg` around the
/// normal with weight cos(theta_o): the quantity the slab random walk's coneRadiance and
/// isotropicHalfSpaceReflectance() give. Quadrature: 8 rings (uniform in cos^2) x 16 azimuths.
/// @throws Error InvalidArgument for a cone half-angle outside (0, 90].
glm::dvec3 profileSlabConeRadiance(const DipoleConstants& constants, double cosIncidence, double coneHalfAngleDeg);

/// profileDiffuseReflectance() under uniform diffuse light: its cosine-weighted mean over the
/// incidence directions (4-node Gauss-Legendre in cos^2 theta). What a uniform environment of
/// unit radiance gives as exitant radiance, for a Lambertian view of the profile.
glm::dvec3 profileDiffuseReflectanceUniform(const DipoleConstants& constants);

/// Total diffuse reflectance R_d of a semi-infinite medium under uniform illumination, per
/// channel: the classic dipole's closed form (Jensen et al. 2001), with the constants' boundary
/// term A: R_d = alpha'/2 (1 + exp(-4/3 A s)) exp(-s), s = sqrt(3 (1 - alpha')). Used for the
/// light a uniform environment gives a scattering surface.
glm::dvec3 dipoleDiffuseReflectance(const DipoleConstants& constants);

/// Exact dielectric Fresnel transmittance T = 1 - F_r(eta, cosTheta) of an unpolarised ray
/// meeting the boundary at cosTheta to the normal (outside). 0 for cosTheta <= 0 and under total
/// internal reflection.
double fresnelTransmittance(double eta, double cosTheta);

/// Diffuse part S_d of the directional dipole, without Fresnel factors, per channel, in
/// unit^-2. Normals and w_i are normalised here (they need only be non-zero). Degenerate
/// configurations (x_o = x_i, x_o - x_i parallel to n_i, grazing or back-facing light, flipped
/// normals) give finite values >= 0, never NaN or Inf.
/// @throws Error InvalidArgument if an argument is not finite or a direction is zero.
glm::dvec3 evaluateSd(const DipoleConstants& constants, const glm::dvec3& xi, const glm::dvec3& ni,
                      const glm::dvec3& wi, const glm::dvec3& xo, const glm::dvec3& no);

/// The BSSRDF T(eta, w_i . n_i) S_d T(eta, w_o . n_o) without the single-scattering term, in the
/// units of evaluateSd(). Zero when the light or the viewer is behind its surface.
/// @throws Error InvalidArgument if an argument is not finite or a direction is zero.
glm::dvec3 evaluateBssrdf(const DipoleConstants& constants, const glm::dvec3& xi, const glm::dvec3& ni,
                          const glm::dvec3& wi, const glm::dvec3& xo, const glm::dvec3& no,
                          const glm::dvec3& wo);

}  // namespace sss

SSS_END_API
