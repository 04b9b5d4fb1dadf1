// The calibrated scattering profile (sss/bssrdf.h, ScatteringProfile::Calibrated) against the
// physical ground truth, the slab random walk (sss/random_walk.h): energy conservation, the
// single-scattering term against the exact half-space result, the calibration table against a
// fresh walk off its grid, and the slab radiance near the normal for a few presets. The paper's
// dipole stays as it was (its 300 test vectors are checked in test_bssrdf.cpp).
#include "cpu/test_helpers.h"

#include <catch2/catch.hpp>
#include <sss/bssrdf.h>
#include <sss/materials.h>
#include <sss/random_walk.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

using namespace sss;
using Catch::Matchers::Contains;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kCone = 15.0;  // exit cone of the slab comparisons, degrees

DipoleConstants calibrated(const ScatteringMaterial& m) { return deriveDipoleConstants(m, 1.0, ScatteringProfile::Calibrated); }
DipoleConstants dipole(const ScatteringMaterial& m) { return deriveDipoleConstants(m, 1.0, ScatteringProfile::Dipole); }

ScatteringMaterial withReducedAlbedo(double albedo, double eta) {
    ScatteringMaterial m;
    m.sigmaS = glm::dvec3(albedo);
    m.sigmaA = glm::dvec3(1.0 - albedo);
    m.eta = eta;
    m.name = "test";
    return m;
}

glm::dvec3 coneRadiance(const DipoleConstants& c, double incidenceDeg) {
    return profileSlabConeRadiance(c, std::cos(incidenceDeg * kPi / 180.0), kCone);
}

}  // namespace

TEST_CASE("profile: names parse and print", "[cpu][profile]") {
    CHECK(parseScatteringProfile("calibrated") == ScatteringProfile::Calibrated);
    CHECK(parseScatteringProfile("dipole") == ScatteringProfile::Dipole);
    CHECK_FALSE(parseScatteringProfile("Dipole").has_value());
    CHECK(toString(ScatteringProfile::Calibrated) == "calibrated");
    CHECK(toString(ScatteringProfile::Dipole) == "dipole");
    REQUIRE_SSS_ERROR(profileCalibrationScale(1.5, 1.3), ErrorKind::InvalidArgument, Contains("reduced albedo"));
    REQUIRE_SSS_ERROR(dipolePlaneIntegral(dipole(materialPreset("potato")), 0.0), ErrorKind::InvalidArgument,
                      Contains("cosIncidence"));
}

TEST_CASE("profile: the dipole profile is the paper's, the calibrated one only rescales it", "[cpu][profile]") {
    const ScatteringMaterial m = materialPreset("marble");
    const DipoleConstants d = dipole(m), c = calibrated(m);
    CHECK(d.profileScale == glm::dvec3(1.0));
    CHECK(d.singleScattering == 0.0);
    CHECK(c.singleScattering == 1.0);
    CHECK(c.sigmaTr == d.sigmaTr);
    CHECK(c.de == d.de);
    const glm::dvec3 xi(0.0), n(0.0, 0.0, 1.0), wi = glm::normalize(glm::dvec3(0.3, 0.1, 1.0)), xo(1.2, -0.4, 0.0);
    const glm::dvec3 sd = evaluateSd(d, xi, n, wi, xo, n), sc = evaluateSd(c, xi, n, wi, xo, n);
    // Entry cosine 0.95: a quarter of the way from node 0 (cosine 1) to node 1 (0.81).
    const double cosI = glm::dot(wi, n);
    REQUIRE(cosI == Approx(0.951).epsilon(0.01));
    for (int ch = 0; ch < 3; ++ch) {
        const double t = (1.0 - cosI) / 0.19;
        const double scale = (1.0 - t) * c.incidenceScale[0][ch] + t * c.incidenceScale[1][ch];
        CHECK(sc[ch] == Approx(sd[ch] * scale).epsilon(1e-9));
        CHECK(scale == Approx(profileCalibrationScale(c.alphaPrime[ch], m.eta, cosI)).epsilon(1e-3));
    }
    // Marble is very bright (alpha' > 0.998): physics returns about 0.8 of the dipole's light.
    for (int ch = 0; ch < 3; ++ch) CHECK(c.incidenceScale[0][ch] < 0.85);
    CHECK(evaluateSingleScattering(d, n, wi, n) == glm::dvec3(0.0));
    // Through a slab (exit normal opposite the entry's, light straight in): the transmission
    // factor at the thickness between the faces, sigma_t' d = 3 (between nodes 2 and 4: log2 3 + 2).
    const double d3 = 3.0 / c.sigmaTPrime.x;
    const glm::dvec3 below(0.4 / c.sigmaTPrime.x, 0.0, -d3), down(0.0, 0.0, -1.0);
    const glm::dvec3 td = evaluateSd(d, xi, n, n, below, down), tc = evaluateSd(c, xi, n, n, below, down);
    const double x = std::log2(3.0) + 2.0, t = x - 3.0;
    const double through = c.transmissionScale[3].x * std::pow(c.transmissionScale[4].x / c.transmissionScale[3].x, t);
    CHECK(tc.x == Approx(td.x * through).epsilon(1e-9));
    CHECK(through == Approx(profileTransmissionScale(c.alphaPrime.x, m.eta, 3.0)).epsilon(1e-9));
    for (const glm::dvec3& k : d.transmissionScale) CHECK(k == glm::dvec3(1.0));
}

TEST_CASE("profile: slab transmittance against fresh finite-slab walks off the table's grid", "[cpu][profile]") {
    // The calibrated profile's diffuse transmittance (profileSlabTransmittance: the factor is
    // exact on a slab, which sets the thickness of every pair) against simulateSlab with a finite
    // thickness, for albedos, indices and thicknesses between the table's nodes. The dipole is off
    // by -40 % to +160 % here. 100000 paths: standard error about 0.7-1.1 %; measured deviation of
    // the profile +3.6, 0.0, +3.3 and +2.3 % (the table's interpolation), bound 6 %.
    SlabRandomWalkOptions o;
    o.paths = 100000;
    o.seed = 91;
    struct Case {
        double albedo, eta, tau;
    };
    for (const Case k : {Case{0.9, 1.33, 0.7}, Case{0.9, 1.33, 3.0}, Case{0.99, 1.45, 6.0}, Case{0.6, 1.2, 1.4}}) {
        const ScatteringMaterial m = withReducedAlbedo(k.albedo, k.eta);
        o.thickness = k.tau;  // mm, sigma_t' = 1 / mm
        const SlabRandomWalkResult walk = simulateSlab(m, 0.0, o);
        const double profile = profileSlabTransmittance(calibrated(m), k.tau).x;
        const double paper = profileSlabTransmittance(dipole(m), k.tau).x;
        const Estimate& t = walk.channels[0].transmitted;
        INFO("alpha' " << k.albedo << " eta " << k.eta << " tau " << k.tau << ": walk " << t.value << " +- "
                       << t.standardError << ", calibrated " << profile << ", dipole " << paper);
        CHECK(profile == Approx(t.value).epsilon(0.06));
    }
}

TEST_CASE("profile: single scattering equals the exact half-space result", "[cpu][profile]") {
    // Integrated over the exit hemisphere, the single-scattering term must give the exact single
    // reflectance of an isotropic half-space (isotropicHalfSpaceReflectance, no Monte Carlo).
    // Quadrature error of the 256 x 64 midpoint rule: below 1e-4 relative.
    for (double eta : {1.0, 1.3, 1.6}) {
        for (double incidence : {0.0, 45.0, 70.0}) {
            for (double albedo : {0.2, 0.9}) {
                const ScatteringMaterial m = withReducedAlbedo(albedo, eta);
                DipoleConstants c = calibrated(m);
                c.profileScale = glm::dvec3(0.0);  // the single-scattering part alone
                const double cosI = std::cos(incidence * kPi / 180.0);
                const double single = profileDiffuseReflectance(c, cosI).x;
                const HalfSpaceReflectance exact = isotropicHalfSpaceReflectance(albedo, eta, incidence);
                INFO("eta " << eta << " incidence " << incidence << " albedo " << albedo);
                CHECK(single == Approx(exact.single).epsilon(2e-3));
            }
        }
    }
}

TEST_CASE("profile: the calibration table matches a fresh walk off its grid", "[cpu][profile]") {
    // alpha' = 0.97 and 0.6 at eta = 1.33 and 1.45 lie between the table's nodes. The factor is the
    // walk's multiple-scattering reflectance over the dipole's, at normal incidence. 200000 paths:
    // standard error about 0.15 % (high albedo) to 0.4 % (low); measured interpolation error
    // below 0.6 %, bound 1.5 %.
    SlabRandomWalkOptions o;
    o.paths = 200000;
    o.seed = 77;
    for (double eta : {1.33, 1.45}) {
        ScatteringMaterial m = withReducedAlbedo(0.97, eta);
        m.sigmaS.y = 0.6;
        m.sigmaA.y = 0.4;
        const SlabRandomWalkResult walk = simulateSlab(m, 0.0, o);
        const DipoleConstants d = dipole(m);
        const glm::dvec3 dipoleR = fresnelTransmittance(eta, 1.0) * dipolePlaneIntegral(d, 1.0) * fresnelHemisphereIntegral(eta);
        for (int ch : {0, 1}) {
            const double expected = walk.channels[ch].multiple.value / dipoleR[ch];
            const double table = profileCalibrationScale(d.alphaPrime[ch], eta);
            INFO("eta " << eta << " alpha' " << d.alphaPrime[ch] << " walk/dipole " << expected << " table " << table);
            CHECK(table == Approx(expected).epsilon(0.015));
        }
    }
}

TEST_CASE("profile: energy is conserved for every preset and eta in [1, 2]", "[cpu][profile]") {
    // Total diffuse reflectance (multiple + single, per incident power) <= 1. The dipole breaks it
    // (cream R: 1.20 at normal incidence), so the check can fail.
    CHECK(profileDiffuseReflectance(dipole(materialPreset("cream")), 1.0).x > 1.1);
    for (const std::string& name : materialPresetNames()) {
        const DipoleConstants c = calibrated(materialPreset(name));
        for (double incidence : {0.0, 60.0}) {
            const glm::dvec3 r = profileDiffuseReflectance(c, std::cos(incidence * kPi / 180.0));
            INFO(name << " at " << incidence << " deg: " << r.x << " " << r.y << " " << r.z);
            CHECK(r.x <= 1.0);
            CHECK(r.y <= 1.0);
            CHECK(r.z <= 1.0);
        }
    }
    // The hardest case, no absorption at all (spectralon-like): everything that enters, 1 - F,
    // must come out again. Measured: within 0.5 % of 1 - F at 0-75 degrees for every eta here
    // (the dipole alone: up to 1.30 at eta 1, 75 degrees).
    for (double eta : {1.0, 1.25, 1.5, 1.75, 2.0}) {
        for (double incidence : {0.0, 45.0, 75.0}) {
            const double cosI = std::cos(incidence * kPi / 180.0);
            const double r = profileDiffuseReflectance(calibrated(withReducedAlbedo(1.0, eta)), cosI).x;
            const double entered = fresnelTransmittance(eta, cosI);
            INFO("albedo 1, eta " << eta << ", incidence " << incidence << ": " << r << ", entered " << entered);
            CHECK(r <= 1.0 + 1e-5);  // the quadratures' error
            CHECK(r == Approx(entered).epsilon(0.01));
        }
    }
}

TEST_CASE("profile: slab radiance near the normal against the exact half-space", "[cpu][profile]") {
    // The goal: within 5 % of physics at 0 and 45 degrees for every channel of these
    // presets. Physics here is the exact radiance of the isotropic half-space
    // (isotropicHalfSpaceReflectance, which the random walk reproduces within its standard
    // error, test_random_walk.cpp), so the check has no noise. Measured worst calibrated error:
    // 1.4 % (printed by sss-bench --accuracy slab); the dipole is off by 22 % to x100.
    for (const char* name : {"cream", "potato", "marble", "skimmilk", "ketchup", "skin1", "apple", "chicken1"}) {
        const ScatteringMaterial m = materialPreset(name);
        const DipoleConstants c = calibrated(m), d = dipole(m);
        for (double incidence : {0.0, 45.0}) {
            const glm::dvec3 model = coneRadiance(c, incidence), paper = coneRadiance(d, incidence);
            for (int ch = 0; ch < 3; ++ch) {
                const double exact = isotropicHalfSpaceReflectance(c.alphaPrime[ch], m.eta, incidence, kCone).coneRadiance;
                INFO(name << " ch " << ch << " incidence " << incidence << ": exact " << exact << ", calibrated "
                          << model[ch] << ", dipole " << paper[ch]);
                CHECK(std::abs(model[ch] / exact - 1.0) < 0.05);
                CHECK(std::abs(paper[ch] / exact - 1.0) > 0.15);
            }
        }
    }
}

TEST_CASE("profile: low albedo, ketchup's green and blue against the random walk", "[cpu][profile]") {
    // Ketchup G and B have single-scattering albedos 0.067 and 0.020: what comes back is mostly
    // single scattering, which the dipole lacks (it returns x30 and x100 too much). Within 10 %
    // of the walk: the walk's cone radiance at 400000 paths has a standard error of 6-15 % here,
    // so the bound is 10 % plus 3 standard errors; the exact half-space value (no noise) must be
    // within 10 % on its own.
    const ScatteringMaterial m = materialPreset("ketchup");
    SlabRandomWalkOptions o;
    o.paths = 400000;
    o.coneHalfAngleDeg = kCone;
    const SlabRandomWalkResult walk = simulateSlab(m, 0.0, o);
    const DipoleConstants c = calibrated(m), d = dipole(m);
    const glm::dvec3 model = coneRadiance(c, 0.0), paper = coneRadiance(d, 0.0);
    for (int ch : {1, 2}) {
        const Estimate w = walk.channels[ch].coneRadiance;
        const double exact = isotropicHalfSpaceReflectance(c.alphaPrime[ch], m.eta, 0.0, kCone).coneRadiance;
        INFO("ketchup ch " << ch << ": walk " << w.value << " +- " << w.standardError << ", exact " << exact
                           << ", calibrated " << model[ch] << ", dipole " << paper[ch]);
        CHECK(std::abs(model[ch] - w.value) <= 0.10 * w.value + 3.0 * w.standardError);
        CHECK(std::abs(model[ch] / exact - 1.0) < 0.10);
        CHECK(paper[ch] / exact > 10.0);
    }
}
