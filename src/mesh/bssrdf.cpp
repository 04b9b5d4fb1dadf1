// Scattering materials and the directional-dipole constants derived from them (spec
// mesh-scattering.md §1.1-1.2). Everything here runs once per material, in double: the 3 C_2 fit
// sums terms near 1600 down to 0.3, which float32 would leave with ~1e-4 absolute error.
#include "sss/bssrdf.h"

#include "sss/error.h"
#include "util/format.h"

#include "mesh/profile_calibration_table.inc"
#include "mesh/profile_transmission_table.inc"

#include <glm/common.hpp>
#include <glm/exponential.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <iterator>
#include <limits>
#include <cmath>
#include <numbers>
#include <string>

namespace sss {
namespace {

using detail::formatNumber;
using detail::formatVec;

bool isFinite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

[[noreturn]] void fail(const std::string& field, const std::string& rule, const std::string& got) {
    throw Error(ErrorKind::InvalidArgument, "ScatteringMaterial", field, "must be " + rule + ", got " + got);
}

// C_phi(eta) = (1 - 2 C_1) / 4.
double cPhiOf(double eta) { return 0.25 * (1.0 - fresnelMoment2C1(eta)); }

}  // namespace

void ScatteringMaterial::validate() const {
    if (!isFinite(sigmaA) || sigmaA.x < 0.0 || sigmaA.y < 0.0 || sigmaA.z < 0.0)
        fail("sigmaA", "finite and >= 0 in every channel", formatVec(sigmaA));
    if (!isFinite(sigmaS) || sigmaS.x < 0.0 || sigmaS.y < 0.0 || sigmaS.z < 0.0)
        fail("sigmaS", "finite and >= 0 in every channel", formatVec(sigmaS));
    if (!std::isfinite(g) || g <= -1.0 || g >= 1.0) fail("g", "in (-1, 1)", formatNumber(g));
    // Outside [0.4, 2.5] the Fresnel-moment fits turn C_phi(eta) or C_phi(1/eta) negative.
    if (!std::isfinite(eta) || eta < 0.4 || eta > 2.5) fail("eta", "in [0.4, 2.5]", formatNumber(eta));
    const glm::dvec3 sigmaTPrime = sigmaA + sigmaS * (1.0 - g);
    if (sigmaTPrime.x <= 0.0 || sigmaTPrime.y <= 0.0 || sigmaTPrime.z <= 0.0)
        throw Error(ErrorKind::InvalidArgument,
                    "ScatteringMaterial::sigmaA + sigmaS * (1 - g) must be > 0 in every channel (\"" + name +
                        "\" does not attenuate light), got " + formatVec(sigmaTPrime));
}

double fresnelMoment2C1(double eta) {
    const double n = eta, n2 = n * n, n3 = n2 * n, n4 = n3 * n, n5 = n4 * n;
    if (eta < 1.0) return 0.919317 - 3.4793 * n + 6.75335 * n2 - 7.80989 * n3 + 4.98554 * n4 - 1.36881 * n5;
    return -9.23372 + 22.2272 * n - 20.9292 * n2 + 10.2291 * n3 - 2.54396 * n4 + 0.254913 * n5;
}

double fresnelMoment3C2(double eta) {
    const double n = eta, n2 = n * n, n3 = n2 * n, n4 = n3 * n, n5 = n4 * n;
    if (eta < 1.0) return 0.828421 - 2.62051 * n + 3.36231 * n2 - 1.95284 * n3 + 0.236494 * n4 + 0.145787 * n5;
    return -1641.1 + 135.926 / n3 - 656.175 / n2 + 1376.53 / n + 1213.67 * n - 568.556 * n2 + 164.798 * n3 -
           27.0181 * n4 + 1.91826 * n5;
}

std::string_view toString(ScatteringProfile profile) {
    return profile == ScatteringProfile::Dipole ? "dipole" : "calibrated";
}

std::optional<ScatteringProfile> parseScatteringProfile(std::string_view name) {
    if (name == "calibrated") return ScatteringProfile::Calibrated;
    if (name == "dipole") return ScatteringProfile::Dipole;
    return std::nullopt;
}

namespace {

// Interval i and weight t in [0, 1] of x on a sorted grid of n >= 2 nodes, held at both ends.
void locateOnGrid(const double* grid, int n, double x, int& i, double& t) {
    i = 0;
    while (i < n - 2 && x > grid[i + 1]) ++i;
    t = std::clamp((x - grid[i]) / (grid[i + 1] - grid[i]), 0.0, 1.0);
}

// a (b / a)^t where both are positive (factors that span orders of magnitude), else linear.
double logLerp(double a, double b, double t) {
    if (a > 0.0 && b > 0.0) return a * std::pow(b / a, t);
    return (1.0 - t) * a + t * b;
}

// A calibration table scale[eta][s][k] (s = sqrt(1 - alpha')) at (eta, reducedAlbedo) and node
// position x in [0, K - 1]: linear in eta, log-linear in s (the factors fall by orders of magnitude
// as alpha' drops), linear or log-linear along k.
template <std::size_t E, std::size_t S, std::size_t K>
double interpolateCalibration(const double (&etas)[E], const double (&ss)[S], const double (&scale)[E][S][K], double eta,
                              double reducedAlbedo, double x, bool logAlongK) {
    int ie = 0, is = 0;
    double te = 0.0, ts = 0.0;
    locateOnGrid(etas, static_cast<int>(E), eta, ie, te);
    locateOnGrid(ss, static_cast<int>(S), std::sqrt(1.0 - reducedAlbedo), is, ts);
    x = std::clamp(x, 0.0, static_cast<double>(K - 1));
    const int ik = std::min(static_cast<int>(x), static_cast<int>(K) - 2);
    const double tk = x - ik;
    auto alongS = [&](int e, int k) { return logLerp(scale[e][is][k], scale[e][is + 1][k], ts); };
    auto atEta = [&](int e) {
        const double a = alongS(e, ik), b = alongS(e, ik + 1);
        return logAlongK ? logLerp(a, b, tk) : (1.0 - tk) * a + tk * b;
    };
    return std::max(0.0, (1.0 - te) * atEta(ie) + te * atEta(ie + 1));
}

void checkReducedAlbedoAndEta(const char* where, double reducedAlbedo, double eta) {
    if (!std::isfinite(reducedAlbedo) || reducedAlbedo < 0.0 || reducedAlbedo > 1.0)
        throw Error(ErrorKind::InvalidArgument,
                    std::string(where) + ": reduced albedo must be in [0, 1], got " + formatNumber(reducedAlbedo));
    if (!std::isfinite(eta))
        throw Error(ErrorKind::InvalidArgument, std::string(where) + ": eta must be finite, got " + formatNumber(eta));
}

}  // namespace

double profileCalibrationScale(double reducedAlbedo, double eta, double cosIncidence) {
    checkReducedAlbedoAndEta("profileCalibrationScale", reducedAlbedo, eta);
    if (!std::isfinite(cosIncidence))
        throw Error(ErrorKind::InvalidArgument,
                    "profileCalibrationScale: cosIncidence must be finite, got " + formatNumber(cosIncidence));
    // Entry cosines mu = 1 - 0.19 k; linear between them.
    return interpolateCalibration(calibration::kEta, calibration::kS, calibration::kScale, eta, reducedAlbedo,
                                  (1.0 - cosIncidence) / 0.19, false);
}

double profileTransmissionScale(double reducedAlbedo, double eta, double opticalThickness) {
    checkReducedAlbedoAndEta("profileTransmissionScale", reducedAlbedo, eta);
    if (std::isnan(opticalThickness) || opticalThickness <= 0.0)
        throw Error(ErrorKind::InvalidArgument,
                    "profileTransmissionScale: optical thickness must be > 0, got " + formatNumber(opticalThickness));
    // Thicknesses 0.25 * 2^k; log-linear along them too (the factor spans orders of magnitude).
    return interpolateCalibration(transmission_calibration::kEta, transmission_calibration::kS,
                                  transmission_calibration::kScale, eta, reducedAlbedo,
                                  std::log2(opticalThickness) + 2.0, true);
}

DipoleConstants deriveDipoleConstants(const ScatteringMaterial& material, double millimetresPerUnit,
                                      ScatteringProfile profile) {
    material.validate();
    if (!std::isfinite(millimetresPerUnit) || millimetresPerUnit <= 0.0)
        throw Error(ErrorKind::InvalidArgument,
                    "deriveDipoleConstants: millimetresPerUnit must be finite and > 0, got " +
                    formatNumber(millimetresPerUnit));
    DipoleConstants c;
    c.millimetresPerUnit = millimetresPerUnit;
    // sigma per mm -> per unit; every length below then comes out in units.
    const glm::dvec3 sigmaA = material.sigmaA * millimetresPerUnit;
    const glm::dvec3 sigmaS = material.sigmaS * millimetresPerUnit;
    c.sigmaSPrime = sigmaS * (1.0 - material.g);
    c.sigmaTPrime = c.sigmaSPrime + sigmaA;
    c.sigmaT = sigmaS + sigmaA;
    c.alphaPrime = c.sigmaSPrime / c.sigmaTPrime;
    c.D = 1.0 / (3.0 * c.sigmaTPrime);
    c.sigmaTr = glm::sqrt(sigmaA / c.D);
    c.de = 2.131 * c.D / glm::sqrt(glm::max(c.alphaPrime, glm::dvec3(1e-12)));

    // eta = n_in / n_out everywhere except the normalisation, which uses C_phi(1 / eta).
    c.eta = material.eta;
    c.twoC1 = fresnelMoment2C1(c.eta);
    c.threeC2 = fresnelMoment3C2(c.eta);
    c.cPhi = 0.25 * (1.0 - c.twoC1);
    c.cE = 0.5 * (1.0 - c.threeC2);
    c.A = (1.0 - c.cE) / (2.0 * c.cPhi);
    c.cPhiInv = cPhiOf(1.0 / c.eta);
    c.normalization = 1.0 / (4.0 * c.cPhiInv) / (4.0 * std::numbers::pi * std::numbers::pi);

    c.profile = profile;
    c.albedo = glm::dvec3(0.0);
    for (int i = 0; i < 3; ++i)
        if (c.sigmaT[i] > 0.0) c.albedo[i] = sigmaS[i] / c.sigmaT[i];
    c.g = material.g;
    if (profile == ScatteringProfile::Calibrated) {
        for (int m = 0; m < kProfileIncidenceNodes; ++m)
            for (int i = 0; i < 3; ++i)
                c.incidenceScale[static_cast<size_t>(m)][i] =
                    profileCalibrationScale(std::clamp(c.alphaPrime[i], 0.0, 1.0), c.eta, profileIncidenceNode(m));
        for (int d = 0; d < kProfileThicknessNodes; ++d)
            for (int i = 0; i < 3; ++i)
                c.transmissionScale[static_cast<size_t>(d)][i] =
                    profileTransmissionScale(std::clamp(c.alphaPrime[i], 0.0, 1.0), c.eta, profileThicknessNode(d));
        c.singleScattering = 1.0;
    }
    return c;
}

glm::dvec3 dipoleDiffuseReflectance(const DipoleConstants& c) {
    glm::dvec3 r;
    for (int i = 0; i < 3; ++i) {
        const double s = std::sqrt(3.0 * std::max(0.0, 1.0 - c.alphaPrime[i]));
        r[i] = 0.5 * c.alphaPrime[i] * (1.0 + std::exp(-4.0 / 3.0 * c.A * s)) * std::exp(-s);
    }
    return r;
}

glm::dvec3 dipolePlaneIntegral(const DipoleConstants& c, double cosIncidence, double maxRadius) {
    if (!(cosIncidence > 0.0) || cosIncidence > 1.0)
        throw Error(ErrorKind::InvalidArgument, "dipolePlaneIntegral: cosIncidence must be in (0, 1], got " +
                                                formatNumber(cosIncidence));
    if (!(maxRadius > 0.0))
        throw Error(ErrorKind::InvalidArgument, "dipolePlaneIntegral: maxRadius must be > 0, got " +
                                                formatNumber(maxRadius));
    // The kernel lives between a small fraction of the shortest mean free path and many
    // transport lengths of the longest; sigma_tr = 0 (no absorption) has no finite tail, so the
    // grid stops at 1e4 reduced mean free paths there.
    double shortest = std::numeric_limits<double>::infinity(), longest = 0.0;
    for (int i = 0; i < 3; ++i) {
        const double mfp = 1.0 / c.sigmaTPrime[i];
        shortest = std::min(shortest, mfp);
        longest = std::max(longest, c.sigmaTr[i] > 0.0 ? std::min(60.0 / c.sigmaTr[i], 1e4 * mfp) : 1e4 * mfp);
    }
    const double r0 = 1e-7 * shortest, r1 = std::min(longest, maxRadius);
    if (!(r1 > r0)) return glm::dvec3(0.0);
    const double sinI = std::sqrt(std::max(0.0, 1.0 - cosIncidence * cosIncidence));
    const glm::dvec3 wi{sinI, 0.0, cosIncidence}, n{0.0, 0.0, 1.0};
    const bool symmetric = sinI < 1e-12;
    const int radial = 4000, azimuthal = symmetric ? 1 : 48;
    const double l0 = std::log(r0), dl = (std::log(r1) - l0) / radial;
    glm::dvec3 sum(0.0);
    for (int i = 0; i < radial; ++i) {
        const double r = std::exp(l0 + (i + 0.5) * dl);
        for (int j = 0; j < azimuthal; ++j) {
            // The kernel is mirror-symmetric about the plane of incidence: phi in [0, pi], twice.
            const double phi = std::numbers::pi * (j + 0.5) / azimuthal;
            const glm::dvec3 xo{r * std::cos(phi), r * std::sin(phi), 0.0};
            sum += evaluateSd(c, glm::dvec3(0.0), n, wi, xo, n) * (r * r * dl * 2.0 * std::numbers::pi / azimuthal);
        }
    }
    return sum;
}

glm::dvec3 dipoleSlabTransmissionIntegral(const DipoleConstants& c, double thickness) {
    if (!std::isfinite(thickness) || thickness <= 0.0)
        throw Error(ErrorKind::InvalidArgument,
                    "dipoleSlabTransmissionIntegral: thickness must be finite and > 0, got " + formatNumber(thickness));
    // Lateral offsets from a small fraction of the thickness out to many transport lengths (the
    // kernel falls off as exp(-sigma_tr sqrt(rho^2 + d^2))).
    double longest = 0.0;
    for (int i = 0; i < 3; ++i) {
        const double mfp = 1.0 / c.sigmaTPrime[i];
        longest = std::max(longest, c.sigmaTr[i] > 0.0 ? std::min(60.0 / c.sigmaTr[i], 1e4 * mfp) : 1e4 * mfp);
    }
    const double r0 = 1e-4 * std::min(thickness, 1.0 / std::max({c.sigmaTPrime.x, c.sigmaTPrime.y, c.sigmaTPrime.z}));
    const double r1 = std::max(longest, 100.0 * thickness);
    const glm::dvec3 ni{0.0, 0.0, 1.0}, no{0.0, 0.0, -1.0};
    const int radial = 4000;
    const double l0 = std::log(r0), dl = (std::log(r1) - l0) / radial;
    // The pair right across (rho = 0) plus log-spaced rings; the disk inside r0 is its share.
    glm::dvec3 sum = evaluateSd(c, glm::dvec3(0.0), ni, ni, glm::dvec3(0.0, 0.0, -thickness), no) *
                     (std::numbers::pi * r0 * r0);
    for (int i = 0; i < radial; ++i) {
        const double r = std::exp(l0 + (i + 0.5) * dl);
        sum += evaluateSd(c, glm::dvec3(0.0), ni, ni, glm::dvec3(r, 0.0, -thickness), no) *
               (r * r * dl * 2.0 * std::numbers::pi);
    }
    return sum;
}

glm::dvec3 profileSlabTransmittance(const DipoleConstants& c, double thickness) {
    return fresnelTransmittance(c.eta, 1.0) * dipoleSlabTransmissionIntegral(c, thickness) *
           fresnelHemisphereIntegral(c.eta);
}

double fresnelHemisphereIntegral(double eta) {
    const int n = 100000;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        const double mu = (i + 0.5) / n;
        sum += fresnelTransmittance(eta, mu) * mu;
    }
    return 2.0 * std::numbers::pi * sum / n;
}

glm::dvec3 profileDiffuseReflectance(const DipoleConstants& c, double cosIncidence) {
    const glm::dvec3 multiple = fresnelTransmittance(c.eta, cosIncidence) * dipolePlaneIntegral(c, cosIncidence) *
                                fresnelHemisphereIntegral(c.eta);
    glm::dvec3 single(0.0);
    if (c.singleScattering > 0.0) {
        // Midpoints in mu_o and the azimuth (the phase function depends on both).
        const double sinI = std::sqrt(std::max(0.0, 1.0 - cosIncidence * cosIncidence));
        const glm::dvec3 wi{sinI, 0.0, cosIncidence}, n{0.0, 0.0, 1.0};
        const int nMu = 256, nPhi = 64;
        for (int i = 0; i < nMu; ++i) {
            const double mu = (i + 0.5) / nMu, s = std::sqrt(1.0 - mu * mu);
            for (int j = 0; j < nPhi; ++j) {
                const double phi = std::numbers::pi * (j + 0.5) / nPhi;
                const glm::dvec3 wo{s * std::cos(phi), s * std::sin(phi), mu};
                single += evaluateSingleScattering(c, n, wi, wo) * (mu * (1.0 / nMu) * (2.0 * std::numbers::pi / nPhi));
            }
        }
    }
    return multiple + single;
}

glm::dvec3 profileSlabRadiance(const DipoleConstants& c, double cosIncidence, const glm::dvec3& wo) {
    const glm::dvec3 n{0.0, 0.0, 1.0};
    const double sinI = std::sqrt(std::max(0.0, 1.0 - cosIncidence * cosIncidence));
    const glm::dvec3 wi{sinI, 0.0, cosIncidence};
    const double mu = glm::dot(glm::normalize(wo), n);
    return fresnelTransmittance(c.eta, cosIncidence) * dipolePlaneIntegral(c, cosIncidence) *
               fresnelTransmittance(c.eta, mu) +
           evaluateSingleScattering(c, n, wi, wo);
}

glm::dvec3 profileSlabConeRadiance(const DipoleConstants& c, double cosIncidence, double coneHalfAngleDeg) {
    if (!(coneHalfAngleDeg > 0.0) || coneHalfAngleDeg > 90.0)
        throw Error(ErrorKind::InvalidArgument,
                    "profileSlabConeRadiance: coneHalfAngleDeg must be in (0, 90], got " +
                    formatNumber(coneHalfAngleDeg));
    const glm::dvec3 n{0.0, 0.0, 1.0};
    const double sinI = std::sqrt(std::max(0.0, 1.0 - cosIncidence * cosIncidence));
    const glm::dvec3 wi{sinI, 0.0, cosIncidence};
    const glm::dvec3 plane = fresnelTransmittance(c.eta, cosIncidence) * dipolePlaneIntegral(c, cosIncidence);
    const double muMin = std::cos(coneHalfAngleDeg * std::numbers::pi / 180.0);
    const int rings = 8, azimuths = 16;
    glm::dvec3 sum(0.0);
    for (int i = 0; i < rings; ++i) {
        // Uniform in mu^2: equal projected solid angle per ring.
        const double u = muMin * muMin + (1.0 - muMin * muMin) * (i + 0.5) / rings;
        const double mu = std::sqrt(u), s = std::sqrt(1.0 - u);
        for (int j = 0; j < azimuths; ++j) {
            const double phi = 2.0 * std::numbers::pi * (j + 0.5) / azimuths;
            const glm::dvec3 wo{s * std::cos(phi), s * std::sin(phi), mu};
            sum += plane * fresnelTransmittance(c.eta, mu) + evaluateSingleScattering(c, n, wi, wo);
        }
    }
    return sum / double(rings * azimuths);
}

glm::dvec3 profileDiffuseReflectanceUniform(const DipoleConstants& c) {
    // Uniform radiance: irradiance weight 2 mu dmu = d(mu^2), so Gauss-Legendre in u = mu^2.
    constexpr double x[] = {0.0694318442, 0.3300094782, 0.6699905218, 0.9305681558};
    constexpr double w[] = {0.1739274226, 0.3260725774, 0.3260725774, 0.1739274226};
    glm::dvec3 sum(0.0);
    for (int i = 0; i < 4; ++i) sum += w[i] * profileDiffuseReflectance(c, std::sqrt(x[i]));
    return sum;
}

}  // namespace sss
