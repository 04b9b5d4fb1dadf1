// Directional dipole BSSRDF on the CPU (double): the Fresnel-moment table and golden S_d values of
// spec mesh-scattering.md §1.2 / §1.5, the 300 vectors of dirpole-vectors.json, the degenerate
// configurations of §1.5, Fresnel transmittance, validation and the material presets.
#include "cpu/test_helpers.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <sss/bssrdf.h>
#include <sss/materials.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <random>
#include <string>

using namespace sss;
using glm::dvec3;

namespace {

// True if `value` rounds to `printed`, which was printed with `digits` significant digits: the
// spec tables are rounded, so half a unit in the last printed place is the honest tolerance.
bool matchesPrinted(double value, double printed, int digits) {
    const double unit = std::pow(10.0, std::floor(std::log10(std::abs(printed))) - (digits - 1));
    return std::abs(value - printed) <= 0.5001 * unit;
}

bool finiteNonNegative(const dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && v.x >= 0.0 && v.y >= 0.0 && v.z >= 0.0;
}

double channel(const dvec3& v, int c) { return c == 0 ? v.x : c == 1 ? v.y : v.z; }

// Potato with g = 0 and eta = 1.3, the material of the spec's golden values.
DipoleConstants potato() { return deriveDipoleConstants(materialPreset("potato")); }

}  // namespace

TEST_CASE("bssrdf: Fresnel-moment fits reproduce the spec table", "[cpu][bssrdf]") {
    struct Row { double eta, twoC1, threeC2, cPhi, cE, A, cPhiInv, norm; };
    // spec §1.2, printed to 5 decimals (the normaliser 1/(4 C_phi(1/eta)) from the text below it)
    const Row rows[] = {{1.0, 0.00433, -0.00684, 0.24892, 0.50342, 0.99748, 0.24892, 1.00435},
                        {1.3, 0.44529, 0.29745, 0.13868, 0.35128, 2.33899, 0.23472, 1.06509},
                        {1.33, 0.47292, 0.32553, 0.13177, 0.33723, 2.51489, 0.23352, 1.07056},
                        {1.5, 0.59654, 0.46261, 0.10086, 0.26870, 3.62517, 0.22706, 1.10105}};
    for (const Row& row : rows) {
        ScatteringMaterial m;
        m.eta = row.eta;
        const DipoleConstants c = deriveDipoleConstants(m);
        INFO("eta " << row.eta);
        const auto near = [](double v, double printed) { return std::abs(v - printed) <= 0.50001e-5; };
        CHECK(near(fresnelMoment2C1(row.eta), row.twoC1));
        CHECK(near(fresnelMoment3C2(row.eta), row.threeC2));
        CHECK(near(c.twoC1, row.twoC1));
        CHECK(near(c.threeC2, row.threeC2));
        CHECK(near(c.cPhi, row.cPhi));
        CHECK(near(c.cE, row.cE));
        CHECK(near(c.A, row.A));
        CHECK(near(c.cPhiInv, row.cPhiInv));
        CHECK(near(1.0 / (4.0 * c.cPhiInv), row.norm));
    }
    // eta < 1 uses the other branch; just below 1 it is close to the ideal C_phi = 1/4, C_E = 1/2.
    CHECK(std::abs(fresnelMoment2C1(0.9999)) < 1e-3);
    CHECK(std::abs(fresnelMoment3C2(0.9999)) < 1e-3);
}

TEST_CASE("bssrdf: potato constants and golden S_d values of the spec", "[cpu][bssrdf]") {
    const DipoleConstants c = potato();
    // Intermediates (spec §1.5), printed to 6 decimals (2 A d_e to 5, N to 7).
    const dvec3 sigmaTr{0.070095, 0.138358, 0.491121}, D{0.488472, 0.470146, 0.497512},
        de{1.042769, 1.008301, 1.170155}, twoAde{4.87804, 4.71680, 5.47395};
    for (int k = 0; k < 3; ++k) {
        CHECK(std::abs(channel(c.sigmaTr, k) - channel(sigmaTr, k)) <= 0.5001e-6);
        CHECK(std::abs(channel(c.D, k) - channel(D, k)) <= 0.5001e-6);
        CHECK(std::abs(channel(c.de, k) - channel(de, k)) <= 0.5001e-6);
        CHECK(std::abs(2.0 * c.A * channel(c.de, k) - channel(twoAde, k)) <= 0.5001e-5);
    }
    CHECK(std::abs(c.normalization - 0.0269791) <= 0.5001e-7);

    // S_d with x_i = 0, n_i = n_o = +z, x_o = (r, 0, 0); columns: w_i = +z, light on the -x side
    // (refracted towards x_o), light on the +x side. Printed to 4 significant digits.
    const double radii[] = {0.5, 1.0, 2.0, 5.0};
    const dvec3 lights[] = {{0, 0, 1}, {-1, 0, 1}, {1, 0, 1}};
    const double golden[3][3][4] = {
        {{2.238e-2, 9.567e-3, 3.559e-3, 7.207e-4}, {3.152e-2, 1.310e-2, 4.680e-3, 8.669e-4},
         {2.172e-2, 7.458e-3, 2.437e-3, 5.259e-4}},
        {{2.281e-2, 9.537e-3, 3.411e-3, 6.109e-4}, {3.220e-2, 1.311e-2, 4.522e-3, 7.455e-4},
         {2.189e-2, 7.325e-3, 2.298e-3, 4.363e-4}},
        {{1.864e-2, 6.863e-3, 1.872e-3, 1.450e-4}, {2.725e-2, 9.990e-3, 2.718e-3, 2.067e-4},
         {1.843e-2, 5.257e-3, 1.122e-3, 7.930e-5}}};
    const dvec3 z{0, 0, 1};
    for (int l = 0; l < 3; ++l)
        for (int i = 0; i < 4; ++i) {
            const dvec3 sd = evaluateSd(c, dvec3(0.0), z, lights[l], {radii[i], 0, 0}, z);
            for (int k = 0; k < 3; ++k) {
                INFO("channel " << k << ", light " << l << ", r " << radii[i] << ": " << channel(sd, k));
                CHECK(matchesPrinted(channel(sd, k), golden[k][l][i], 4));
            }
        }

    // Back-lit slab with a tilted n_i*: x_o = (1, 0, -2) on the far face, n_o = -z.
    const dvec3 back = evaluateSd(c, dvec3(0.0), z, z, {1, 0, -2}, -z);
    CHECK(matchesPrinted(back.x, 6.609e-3, 4));
    CHECK(matchesPrinted(back.y, 6.416e-3, 4));
    CHECK(matchesPrinted(back.z, 4.760e-3, 4));
}

TEST_CASE("bssrdf: all 300 dirpole-vectors.json configurations", "[cpu][bssrdf]") {
    std::ifstream in(SSS_TEST_DATA_DIR "/dirpole-vectors.json");
    REQUIRE(in);
    const nlohmann::json doc = nlohmann::json::parse(in);
    const auto& vectors = doc.at("vectors");
    REQUIRE(vectors.size() == 300u);
    const auto vec = [](const nlohmann::json& a) { return dvec3(a[0].get<double>(), a[1].get<double>(), a[2].get<double>()); };
    // The vectors were reproduced by three independent double evaluations to 1e-10 relative; the
    // same formulas in double differ only by rounding order, amplified where S_d is a difference
    // of nearly equal source terms. 1e-9 leaves room for that and still catches any formula slip.
    const double tolerance = 1e-9;
    double maxRel = 0.0;
    for (const auto& v : vectors) {
        ScatteringMaterial m;
        m.sigmaS = dvec3(v.at("sigma_s").get<double>());  // g = 0: sigma_s is sigma_s'
        m.sigmaA = dvec3(v.at("sigma_a").get<double>());
        m.eta = v.at("eta").get<double>();
        const DipoleConstants c = deriveDipoleConstants(m);
        const double sd = evaluateSd(c, vec(v.at("x_i")), vec(v.at("n_i")), vec(v.at("w_i")), vec(v.at("x_o")),
                                     vec(v.at("n_o"))).x;
        const double expected = v.at("S_d").get<double>();
        const double rel = std::abs(sd - expected) / std::abs(expected);
        maxRel = std::max(maxRel, rel);
        INFO(v.at("material").get<std::string>() << " " << v.at("channel").get<std::string>() << ": " << sd
                                                 << " vs " << expected);
        CHECK(rel <= tolerance);
    }
    std::printf("dirpole-vectors.json: 300 vectors, max relative difference %.3g\n", maxRel);
}

TEST_CASE("bssrdf: degenerate configurations stay finite and sensible", "[cpu][bssrdf]") {
    const DipoleConstants c = potato();
    const dvec3 z{0, 0, 1}, o{0.0};

    SECTION("r -> 0: x_o = x_i uses n_i* = n_i, continuous with the tangent-plane limit") {
        const dvec3 atZero = evaluateSd(c, o, z, z, o, z);
        REQUIRE(finiteNonNegative(atZero));
        CHECK(atZero.x > 0.0);
        const dvec3 nearZero = evaluateSd(c, o, z, z, {1e-9, 0, 0}, z);
        for (int k = 0; k < 3; ++k) CHECK(channel(nearZero, k) == Approx(channel(atZero, k)).epsilon(1e-6));
        CHECK(finiteNonNegative(evaluateSd(c, o, z, z, {1e-300, 0, 0}, z)));
        // d_r -> 0: with eta = 1 grazing light refracts almost along the surface (mu_0 -> 0+), and
        // d_r = D mu_0 at r = 0. The floor d_r >= 0.1 D keeps S_d bounded (the model itself
        // gives ~90x the normal-incidence peak at mu_0 = 0.1, where the floor starts).
        ScatteringMaterial unmatched;
        unmatched.eta = 1.0;
        const DipoleConstants c1 = deriveDipoleConstants(unmatched);
        const double peak = evaluateSd(c1, o, z, z, o, z).x;
        for (double e : {1e-2, 1e-4, 1e-8, 1e-12}) {
            const dvec3 sd = evaluateSd(c1, o, z, glm::normalize(dvec3(1, 0, e)), o, z);
            INFO("cos theta_i " << e << ": " << sd.x << " (normal incidence " << peak << ")");
            CHECK(finiteNonNegative(sd));
            CHECK(sd.x < 1000.0 * peak);
        }
    }
    SECTION("x parallel to n_i (thin slab, normal incidence, x_o straight below or above)") {
        const dvec3 below = evaluateSd(c, o, z, z, {0, 0, -2}, -z);
        REQUIRE(finiteNonNegative(below));
        CHECK(below.x > 0.0);  // light does come through a 2 mm potato slab
        CHECK(finiteNonNegative(evaluateSd(c, o, z, z, {0, 0, 2}, z)));
        CHECK(finiteNonNegative(evaluateSd(c, o, z, z, {0, 0, 2 * c.A * c.de.x}, -z)));  // x_o on the virtual source
        CHECK(finiteNonNegative(evaluateSd(c, o, z, z, {1e-9, 0, -2}, -z)));            // nearly parallel
    }
    SECTION("grazing and back-facing light") {
        for (const dvec3& w : {dvec3(1, 0, 0), dvec3(1, 0, -1), dvec3(0, 0, -1), dvec3(0.3, 0.4, -0.01)}) {
            INFO("w_i " << w.x << ", " << w.y << ", " << w.z);
            CHECK(finiteNonNegative(evaluateSd(c, o, z, w, {1, 0, 0}, z)));
            CHECK(finiteNonNegative(evaluateSd(c, o, z, w, o, z)));
            // No light crosses the boundary from behind or at grazing incidence.
            CHECK(evaluateBssrdf(c, o, z, w, {1, 0, 0}, z, z) == dvec3(0.0));
        }
    }
    SECTION("flipped normals") {
        for (int flips = 1; flips < 4; ++flips) {
            const dvec3 ni = (flips & 1) ? -z : z, no = (flips & 2) ? -z : z;
            CHECK(finiteNonNegative(evaluateSd(c, o, ni, z, {1, 0, 0}, no)));
            CHECK(finiteNonNegative(evaluateSd(c, o, ni, z, o, no)));
            CHECK(finiteNonNegative(evaluateBssrdf(c, o, ni, z, {1, 0, 0}, no, z)));
        }
    }
    SECTION("sigma_a = 0 (spectralon, sigma_tr = 0) and sigma_s' = 0 (merlot G, B)") {
        const DipoleConstants spectralon = deriveDipoleConstants(materialPreset("spectralon"));
        CHECK(spectralon.sigmaTr == dvec3(0.0));
        for (double r : {0.0, 0.01, 1.0, 100.0}) {
            const dvec3 sd = evaluateSd(spectralon, o, z, z, {r, 0, 0}, z);
            CHECK(finiteNonNegative(sd));
            CHECK(sd.x > 0.0);
        }
        const DipoleConstants merlot = deriveDipoleConstants(materialPreset("merlot"));
        CHECK(std::isfinite(merlot.de.y));
        for (double r : {0.0, 0.01, 1.0, 100.0}) CHECK(finiteNonNegative(evaluateSd(merlot, o, z, z, {r, 0, 0}, z)));
    }
    SECTION("random geometry over every preset never gives NaN, Inf or negative values") {
        std::mt19937 rng(7);
        std::normal_distribution<double> gauss;
        std::uniform_real_distribution<double> uni(-3.0, 1.5);
        const auto dir = [&] { return glm::normalize(dvec3(gauss(rng), gauss(rng), gauss(rng))); };
        int bad = 0;
        for (const std::string& name : materialPresetNames()) {
            const DipoleConstants m = deriveDipoleConstants(materialPreset(name));
            for (int i = 0; i < 2000; ++i) {
                const dvec3 xo = dir() * std::pow(10.0, uni(rng));
                if (!finiteNonNegative(evaluateBssrdf(m, o, dir(), dir(), xo, dir(), dir())) ||
                    !finiteNonNegative(evaluateSd(m, o, dir(), dir(), xo, dir())))
                    ++bad;
            }
        }
        CHECK(bad == 0);
    }
}

TEST_CASE("bssrdf: exact dielectric Fresnel transmittance", "[cpu][bssrdf]") {
    for (double eta : {1.3, 1.5, 0.8}) {
        const double r0 = (eta - 1.0) / (eta + 1.0);
        CHECK(fresnelTransmittance(eta, 1.0) == Approx(1.0 - r0 * r0).epsilon(1e-12));
        CHECK(fresnelTransmittance(eta, 0.0) == 0.0);
        CHECK(fresnelTransmittance(eta, -0.5) == 0.0);
    }
    CHECK(fresnelTransmittance(1.0, 0.3) == Approx(1.0).epsilon(1e-12));
    // Brewster angle: r_p = 0, so T = 1 - r_s^2 / 2.
    const double eta = 1.5, thetaB = std::atan(eta), ci = std::cos(thetaB), ct = std::sin(thetaB);
    const double rs = (ci - eta * ct) / (ci + eta * ct);
    CHECK(fresnelTransmittance(eta, ci) == Approx(1.0 - 0.5 * rs * rs).epsilon(1e-12));
    CHECK(fresnelTransmittance(0.7, 0.5) == 0.0);  // total internal reflection (sin > 0.7)
    CHECK(fresnelTransmittance(0.7, 0.9) > 0.0);
}

TEST_CASE("bssrdf: lengths scale with millimetresPerUnit", "[cpu][bssrdf]") {
    const ScatteringMaterial cream = materialPreset("cream");
    const DipoleConstants mm = deriveDipoleConstants(cream);
    const DipoleConstants metres = deriveDipoleConstants(cream, ScatteringScale{}.millimetresPerUnit);
    CHECK(metres.millimetresPerUnit == 1000.0);
    CHECK(metres.D.x == Approx(mm.D.x / 1000.0));
    const dvec3 ni = glm::normalize(dvec3(0.2, 0, 1)), wi = glm::normalize(dvec3(-1, 0.3, 1)),
                no = glm::normalize(dvec3(-0.1, 0.1, 1)), xo{3.0, 1.0, -0.2};
    const dvec3 sdMm = evaluateSd(mm, dvec3(0.0), ni, wi, xo, no);
    const dvec3 sdM = evaluateSd(metres, dvec3(0.0), ni, wi, xo / 1000.0, no);
    for (int k = 0; k < 3; ++k) CHECK(channel(sdM, k) == Approx(channel(sdMm, k) * 1e6).epsilon(1e-9));  // mm^-2 -> m^-2
}

TEST_CASE("bssrdf: material validation names the field", "[cpu][bssrdf]") {
    ScatteringMaterial m;
    CHECK_NOTHROW(m.validate());
    m.sigmaA = {-0.1, 0.0, 0.0};
    REQUIRE_SSS_ERROR(m.validate(), ErrorKind::InvalidArgument,
                      Catch::Contains("ScatteringMaterial::sigmaA") && Catch::Contains("-0.1"));
    m = {};
    m.sigmaS = {1.0, NAN, 1.0};
    REQUIRE_SSS_ERROR(m.validate(), ErrorKind::InvalidArgument, Catch::Contains("ScatteringMaterial::sigmaS"));
    for (double eta : {0.0, -1.3, 3.0, double(NAN)}) {
        m = {};
        m.eta = eta;
        REQUIRE_SSS_ERROR(m.validate(), ErrorKind::InvalidArgument, Catch::Contains("ScatteringMaterial::eta"));
    }
    for (double g : {1.0, -1.0, 2.0}) {
        m = {};
        m.g = g;
        REQUIRE_SSS_ERROR(deriveDipoleConstants(m), ErrorKind::InvalidArgument, Catch::Contains("ScatteringMaterial::g"));
    }
    m = {};
    m.sigmaA = dvec3(0.0);
    m.sigmaS = {1.0, 0.0, 1.0};
    REQUIRE_SSS_ERROR(m.validate(), ErrorKind::InvalidArgument, Catch::Contains("does not attenuate"));
    REQUIRE_SSS_ERROR(deriveDipoleConstants(ScatteringMaterial{}, 0.0), ErrorKind::InvalidArgument,
                      Catch::Contains("millimetresPerUnit"));
    const DipoleConstants c = potato();
    REQUIRE_SSS_ERROR(evaluateSd(c, dvec3(0.0), dvec3(0.0), {0, 0, 1}, {1, 0, 0}, {0, 0, 1}),
                      ErrorKind::InvalidArgument, Catch::Contains("ni"));
    REQUIRE_SSS_ERROR(evaluateSd(c, dvec3(INFINITY), {0, 0, 1}, {0, 0, 1}, {1, 0, 0}, {0, 0, 1}),
                      ErrorKind::InvalidArgument, Catch::Contains("xi"));
}

TEST_CASE("bssrdf: material presets", "[cpu][bssrdf]") {
    const auto names = materialPresetNames();
    for (const char* jensen : {"apple", "chicken1", "chicken2", "cream", "ketchup", "marble", "potato", "skimmilk",
                               "skin1", "skin2", "spectralon", "wholemilk"})
        CHECK(std::find(names.begin(), names.end(), jensen) != names.end());
    CHECK(names.size() >= 40u);
    for (const std::string& name : names) {
        INFO(name);
        const ScatteringMaterial m = materialPreset(name);
        CHECK(m.name == name);
        CHECK_NOTHROW(m.validate());
    }
    const ScatteringMaterial potatoM = materialPreset("Potato");
    CHECK(potatoM.sigmaS == dvec3(0.68, 0.70, 0.55));
    CHECK(potatoM.sigmaA == dvec3(0.0024, 0.0090, 0.12));
    CHECK(potatoM.g == 0.0);
    CHECK(potatoM.eta == 1.3);
    CHECK(materialPreset("marble").eta == 1.5);
    CHECK(materialPreset("apple").sigmaA.z == 0.046);  // the Jensen value (the thesis table misprints 0.0046)
    CHECK(materialPreset("Regular Milk").sigmaS == dvec3(4.5513, 5.8294, 7.136));
    CHECK(materialPreset("white_grapefruit_juice").name == "whitegrapefruitjuice");
    REQUIRE_SSS_ERROR(materialPreset("unobtainium"), ErrorKind::InvalidArgument,
                      Catch::Contains("unobtainium") && Catch::Contains("potato") && Catch::Contains("wholemilk"));
}
