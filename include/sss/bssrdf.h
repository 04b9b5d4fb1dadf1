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

#include <glm/vec3.hpp>

#include <string>

namespace sss {

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
};

/// 2 C_1(eta), the first Fresnel moment times two (d'Eon and Irving 2011 polynomial fits, branch
/// eta < 1 or eta >= 1).
double fresnelMoment2C1(double eta);

/// 3 C_2(eta), the second Fresnel moment times three (d'Eon and Irving 2011 polynomial fits).
double fresnelMoment3C2(double eta);

/// Validates `material` and derives its constants. Lengths are expressed in a unit of
/// `millimetresPerUnit` mm: coefficients become sigma_mm * millimetresPerUnit, so positions can
/// be passed in scene units directly (1 = millimetres, the default).
/// @throws Error InvalidArgument for an invalid material or a millimetresPerUnit that is not
///         finite and > 0.
DipoleConstants deriveDipoleConstants(const ScatteringMaterial& material, double millimetresPerUnit = 1.0);

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
