// Scattering materials and the directional-dipole constants derived from them (spec
// mesh-scattering.md §1.1-1.2). Everything here runs once per material, in double: the 3 C_2 fit
// sums terms near 1600 down to 0.3, which float32 would leave with ~1e-4 absolute error.
#include "sss/bssrdf.h"

#include "sss/error.h"

#include <glm/common.hpp>
#include <glm/exponential.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

namespace sss {
namespace {

std::string str(const glm::dvec3& v) {
    std::ostringstream s;
    s.precision(9);
    s << '(' << v.x << ", " << v.y << ", " << v.z << ')';
    return s.str();
}

bool isFinite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

[[noreturn]] void fail(const std::string& field, const std::string& rule, const std::string& got) {
    throw Error(ErrorKind::InvalidArgument, "ScatteringMaterial::" + field + " must be " + rule + ", got " + got);
}

std::string num(double v) {
    std::ostringstream s;
    s.precision(9);
    s << v;
    return s.str();
}

// C_phi(eta) = (1 - 2 C_1) / 4.
double cPhiOf(double eta) { return 0.25 * (1.0 - fresnelMoment2C1(eta)); }

}  // namespace

void ScatteringMaterial::validate() const {
    if (!isFinite(sigmaA) || sigmaA.x < 0.0 || sigmaA.y < 0.0 || sigmaA.z < 0.0)
        fail("sigmaA", "finite and >= 0 in every channel", str(sigmaA));
    if (!isFinite(sigmaS) || sigmaS.x < 0.0 || sigmaS.y < 0.0 || sigmaS.z < 0.0)
        fail("sigmaS", "finite and >= 0 in every channel", str(sigmaS));
    if (!std::isfinite(g) || g <= -1.0 || g >= 1.0) fail("g", "in (-1, 1)", num(g));
    // Outside [0.4, 2.5] the Fresnel-moment fits turn C_phi(eta) or C_phi(1/eta) negative.
    if (!std::isfinite(eta) || eta < 0.4 || eta > 2.5) fail("eta", "in [0.4, 2.5]", num(eta));
    const glm::dvec3 sigmaTPrime = sigmaA + sigmaS * (1.0 - g);
    if (sigmaTPrime.x <= 0.0 || sigmaTPrime.y <= 0.0 || sigmaTPrime.z <= 0.0)
        throw Error(ErrorKind::InvalidArgument,
                    "ScatteringMaterial::sigmaA + sigmaS * (1 - g) must be > 0 in every channel (\"" + name +
                        "\" does not attenuate light), got " + str(sigmaTPrime));
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

DipoleConstants deriveDipoleConstants(const ScatteringMaterial& material, double millimetresPerUnit) {
    material.validate();
    if (!std::isfinite(millimetresPerUnit) || millimetresPerUnit <= 0.0)
        throw Error(ErrorKind::InvalidArgument,
                    "deriveDipoleConstants: millimetresPerUnit must be finite and > 0, got " + num(millimetresPerUnit));
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

}  // namespace sss
