// The physical ground truth (sss/random_walk.h): the random walk in a half-space against exact
// results. Index-matched, isotropic: Chandrasekhar's H-function (plane albedo, single scattering,
// radiance near the normal; spec physical-reference.md §2 and its worked values). Fresnel
// boundary: the adding-method solution built on the H-function, exact for isotropic scattering.
// Henyey-Greenstein: the closed-form single scattering. Plus energy conservation, determinism
// across thread counts and input validation. Each walk runs a few hundred thousand paths: the
// standard errors are about 1e-3 and the bounds 4 standard errors (the walks are seeded, so a
// pass is reproducible; the bound only has to survive a change of the random streams).
#include "cpu/test_helpers.h"

#include <catch2/catch.hpp>
#include <sss/bssrdf.h>
#include <sss/materials.h>
#include <sss/random_walk.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

using namespace sss;
using Catch::Matchers::Contains;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kSigmas = 4.0;  // bound on |walk - exact| in standard errors

double degrees(double radians) { return radians * 180.0 / kPi; }

// The spec's cone: cos(theta) > 0.97.
const double kSpecCone = degrees(std::acos(0.97));

// A material whose channels have the given single-scattering albedos (sigma_t = 1 mm^-1).
ScatteringMaterial withAlbedos(double r, double g, double b, double eta, double hg = 0.0) {
    ScatteringMaterial m;
    m.sigmaS = {r, g, b};
    m.sigmaA = {1.0 - r, 1.0 - g, 1.0 - b};
    m.g = hg;
    m.eta = eta;
    m.name = "test";
    return m;
}

// |estimate - exact| within kSigmas standard errors, and the standard error small enough that
// the check has teeth.
void checkAgainst(const Estimate& e, double exact, double maxStandardError, const std::string& what) {
    INFO(what << ": walk " << e.value << " +- " << e.standardError << ", exact " << exact << ", "
              << (e.value - exact) / e.standardError << " standard errors");
    CHECK(e.standardError > 0.0);
    CHECK(e.standardError <= maxStandardError);
    CHECK(std::abs(e.value - exact) <= kSigmas * e.standardError);
}

// Gauss-Legendre rule on [a, b] for the test's own quadratures (independent of the library's).
struct Rule {
    std::vector<double> x, w;
};
Rule gaussLegendre(int n, double a, double b) {
    Rule r;
    for (int i = 0; i < n; ++i) {
        double z = std::cos(kPi * (i + 0.75) / (n + 0.5)), p0 = 1.0, p1 = z, dp = 1.0;
        for (int it = 0; it < 100; ++it) {
            p0 = 1.0, p1 = z;
            for (int k = 2; k <= n; ++k) {
                const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
                p0 = p1, p1 = p2;
            }
            dp = n * (z * p1 - p0) / (z * z - 1.0);
            z -= p1 / dp;
        }
        r.x.push_back(0.5 * (a + b) + 0.5 * (b - a) * z);
        r.w.push_back((b - a) / ((1.0 - z * z) * dp * dp));
    }
    return r;
}

double hg(double g, double cosTheta) {
    return (1.0 - g * g) / (4.0 * kPi * std::pow(1.0 + g * g - 2.0 * g * cosTheta, 1.5));
}

// Exact unpolarised Fresnel reflectance, inside to outside (relative index eta = n_in / n_out),
// at cosine mu inside; sets the outside cosine.
double fresnelInside(double eta, double mu, double& cosOut) {
    const double s2 = eta * eta * (1.0 - mu * mu);
    if (s2 >= 1.0) {
        cosOut = 0.0;
        return 1.0;
    }
    cosOut = std::sqrt(1.0 - s2);
    const double rs = (eta * mu - cosOut) / (eta * mu + cosOut);
    const double rp = (mu - eta * cosOut) / (mu + eta * cosOut);
    return 0.5 * (rs * rs + rp * rp);
}

}  // namespace

TEST_CASE("random walk: the H-function matches tabulated values and its exact identities", "[random-walk][cpu]") {
    // Chandrasekhar, Radiative Transfer (1950), conservative isotropic scattering.
    CHECK(chandrasekharH(1.0, 1.0) == Approx(2.90781).margin(5e-6));
    CHECK(chandrasekharH(1.0, 0.1) == Approx(1.24735).margin(5e-6));
    CHECK(chandrasekharH(0.7, 0.0) == Approx(1.0).margin(1e-12));
    CHECK(chandrasekharH(0.0, 0.6) == Approx(1.0).margin(1e-12));
    // Moments: alpha_0 = integral H = (2 / albedo) (1 - sqrt(1 - albedo)); for albedo = 1,
    // alpha_1 = integral mu H = 2 / sqrt(3). (H has a mu log mu term at 0: graded panels.)
    Rule rule;
    for (auto [a, b] : {std::pair{0.0, 0.01}, {0.01, 0.1}, {0.1, 1.0}}) {
        const Rule p = gaussLegendre(10, a, b);
        rule.x.insert(rule.x.end(), p.x.begin(), p.x.end());
        rule.w.insert(rule.w.end(), p.w.begin(), p.w.end());
    }
    for (double albedo : {0.3, 0.9, 1.0}) {
        double alpha0 = 0.0, alpha1 = 0.0;
        for (size_t i = 0; i < rule.x.size(); ++i) {
            const double h = chandrasekharH(albedo, rule.x[i]);
            alpha0 += rule.w[i] * h;
            alpha1 += rule.w[i] * rule.x[i] * h;
        }
        INFO("albedo " << albedo);
        CHECK(alpha0 == Approx(2.0 / albedo * (1.0 - std::sqrt(1.0 - albedo))).epsilon(1e-6));
        if (albedo == 1.0) CHECK(alpha1 == Approx(2.0 / std::sqrt(3.0)).epsilon(1e-6));
    }
    // The spec's worked values (physical-reference.md §2): albedo 0.99, normal incidence.
    const HalfSpaceReflectance r = isotropicHalfSpaceReflectance(0.99, 1.0, 0.0, kSpecCone);
    CHECK(r.diffuse == Approx(0.752721).margin(5e-7));
    CHECK(1.0 - chandrasekharH(0.99, 1.0) * std::sqrt(0.01) == Approx(0.752721).margin(5e-7));
    CHECK(r.coneRadiance == Approx(0.241001).margin(5e-7));
    CHECK(r.specular == 0.0);
    // Single scattering, index-matched, normal incidence: (albedo / 2) (1 - ln 2).
    CHECK(r.single == Approx(0.99 / 2.0 * (1.0 - std::log(2.0))).epsilon(1e-10));
    // With a Fresnel boundary and no absorption everything that enters leaves again.
    for (double eta : {0.75, 1.3, 1.5})
        for (double incidence : {0.0, 60.0}) {
            const HalfSpaceReflectance c = isotropicHalfSpaceReflectance(1.0, eta, incidence);
            INFO("eta " << eta << ", incidence " << incidence);
            CHECK(c.specular + c.diffuse == Approx(1.0).margin(1e-9));
            CHECK(c.specular == Approx(1.0 - fresnelTransmittance(eta, std::cos(incidence * kPi / 180.0))).margin(1e-15));
        }
}

TEST_CASE("random walk: index-matched isotropic half-space matches the H-function", "[random-walk][cpu]") {
    SlabRandomWalkOptions options;
    options.paths = 200000;
    options.coneHalfAngleDeg = kSpecCone;
    options.seed = 7;
    struct Run {
        ScatteringMaterial material;
        std::vector<int> channels;
    };
    // Albedos 0.3, 0.8, 0.95 in one walk, 0.99 in a second (its other channels are cheap).
    const Run runs[] = {{withAlbedos(0.3, 0.8, 0.95, 1.0), {0, 1, 2}}, {withAlbedos(0.99, 0.1, 0.1, 1.0), {0}}};
    for (const Run& run : runs) {
        const SlabRandomWalkResult walk = simulateSlab(run.material, 0.0, options);
        CHECK(walk.specular == 0.0);
        for (int c : run.channels) {
            const double albedo = run.material.sigmaS[c];
            const HalfSpaceReflectance exact = isotropicHalfSpaceReflectance(albedo, 1.0, 0.0, kSpecCone);
            const SlabChannelResult& w = walk.channels[c];
            INFO("albedo " << albedo);
            CHECK(exact.diffuse == Approx(1.0 - chandrasekharH(albedo, 1.0) * std::sqrt(1.0 - albedo)).epsilon(1e-12));
            checkAgainst(w.diffuse, exact.diffuse, 1.2e-3, "total diffuse reflectance");
            checkAgainst(w.single, exact.single, 1e-3, "single scattering");
            checkAgainst(w.multiple, exact.multiple, 1.2e-3, "multiple scattering");
            checkAgainst(w.coneRadiance, exact.coneRadiance, 0.05 * exact.coneRadiance,
                         "radiance within cos > 0.97");
            CHECK(w.truncatedPaths == 0);
            // The check can fail: it resolves the albedo. The walk is more than kSigmas
            // standard errors from the exact values at albedo +- 0.02 (0.3), 0.01 (0.8, 0.95),
            // 0.002 (0.99).
            const double step = albedo < 0.5 ? 0.02 : albedo < 0.985 ? 0.01 : 0.002;
            for (double other : {albedo - step, albedo + step})
                CHECK(std::abs(isotropicHalfSpaceReflectance(other, 1.0, 0.0).diffuse - w.diffuse.value) >
                      kSigmas * w.diffuse.standardError);
        }
    }
}

TEST_CASE("random walk: a Fresnel boundary matches the exact adding-method solution", "[random-walk][cpu]") {
    SlabRandomWalkOptions options;
    options.paths = 120000;
    options.coneHalfAngleDeg = 10.0;
    options.seed = 11;
    // eta 1.3: total internal reflection inside; eta 0.75: none inside, but beyond 48.6 degrees
    // the beam is totally reflected at entry.
    const struct {
        double eta, incidence;
    } cases[] = {{1.3, 0.0}, {1.3, 60.0}, {0.75, 30.0}};
    for (const auto& k : cases) {
        const ScatteringMaterial material = withAlbedos(0.5, 0.9, 0.98, k.eta);
        const SlabRandomWalkResult walk = simulateSlab(material, k.incidence, options);
        const double cosI = std::cos(k.incidence * kPi / 180.0);
        CHECK(walk.specular == Approx(1.0 - fresnelTransmittance(k.eta, cosI)).margin(1e-15));
        for (int c = 0; c < 3; ++c) {
            const double albedo = material.sigmaS[c];
            const HalfSpaceReflectance exact = isotropicHalfSpaceReflectance(albedo, k.eta, k.incidence, 10.0);
            const SlabChannelResult& w = walk.channels[c];
            INFO("eta " << k.eta << ", incidence " << k.incidence << ", albedo " << albedo);
            CHECK(exact.specular == walk.specular);
            checkAgainst(w.diffuse, exact.diffuse, 1.5e-3, "total diffuse reflectance");
            checkAgainst(w.single, exact.single, 1.2e-3, "single scattering");
            checkAgainst(w.coneRadiance, exact.coneRadiance, 0.07 * exact.coneRadiance, "radiance within 10 degrees");
        }
    }
    // Normal incidence on glass: F = ((1.5 - 1) / (1.5 + 1))^2 = 0.04.
    SlabRandomWalkOptions few;
    few.paths = 100;
    CHECK(simulateSlab(withAlbedos(0.5, 0.5, 0.5, 1.5), 0.0, few).specular == Approx(0.04).margin(1e-15));
    // Beyond the critical angle of eta = 0.75 everything is reflected at entry.
    const SlabRandomWalkResult tir = simulateSlab(withAlbedos(0.5, 0.5, 0.5, 0.75), 60.0, few);
    CHECK(tir.specular == 1.0);
    CHECK(tir.channels[0].diffuse.value == 0.0);
    CHECK(tir.channels[0].absorbed.value == 0.0);
    // No absorption: all the light that enters leaves, total internal reflection or not.
    SlabRandomWalkOptions lossless;
    lossless.paths = 5000;
    lossless.maxEvents = 10000;  // (P(more events) ~ n^-1/2: the walk would be long without a cap)
    const SlabRandomWalkResult all = simulateSlab(withAlbedos(1.0, 1.0, 1.0, 1.3), 45.0, lossless);
    for (const SlabChannelResult& w : all.channels) {
        CHECK(w.absorbed.value == 0.0);
        CHECK(w.diffuse.value + w.truncated.value == Approx(1.0 - all.specular).margin(1e-12));
        CHECK(w.truncated.value < 0.05);
    }
}

TEST_CASE("random walk: Henyey-Greenstein single scattering matches its closed form", "[random-walk][cpu]") {
    // Normal incidence: the refracted beam goes straight down, so a path scattered once into
    // the upward direction at cosine mu turned by cos(theta) = -mu. Per unit irradiance,
    //   L_1(mu) = albedo (1 - F) p(-mu) / (mu + 1) just inside; what leaves is (1 - F_in(mu)) L_1,
    //   R_1 = 2 pi integral (1 - F_in(mu)) L_1(mu) mu dmu.
    // Forward scattering (g > 0) sends less light back than backward scattering (g < 0).
    SlabRandomWalkOptions options;
    options.paths = 150000;
    options.coneHalfAngleDeg = 20.0;
    options.seed = 3;
    const Rule rule = gaussLegendre(200, 0.0, 1.0);
    for (double g : {0.7, -0.5, 0.0})
        for (double eta : {1.0, 1.4}) {
            const double albedo = 0.6;
            const ScatteringMaterial material = withAlbedos(albedo, albedo, albedo, eta, g);
            const SlabRandomWalkResult walk = simulateSlab(material, 0.0, options);
            const double e = 1.0 - walk.specular;
            const double cosCone = std::cos(options.coneHalfAngleDeg * kPi / 180.0);
            double single = 0.0, cone = 0.0;
            const double muC = eta > 1.0 ? std::sqrt(1.0 - 1.0 / (eta * eta)) : 0.0;
            // (1 - F_in) has a square-root edge at the critical cosine: mu = muC + (1 - muC) t^2.
            for (size_t i = 0; i < rule.x.size(); ++i) {
                const double t = rule.x[i];
                const double mu = muC + (1.0 - muC) * t * t;
                const double jacobian = 2.0 * (1.0 - muC) * t;
                double cosOut;
                const double f = fresnelInside(eta, mu, cosOut);
                const double power = 2.0 * kPi * (1.0 - f) * albedo * e * hg(g, -mu) / (mu + 1.0) * mu;
                single += rule.w[i] * jacobian * power;
                if (cosOut >= cosCone) cone += rule.w[i] * jacobian * power;
            }
            const double sinC = std::sin(options.coneHalfAngleDeg * kPi / 180.0);
            cone /= kPi * sinC * sinC;  // (a step at the cone's edge: 200 nodes make it ~1e-3 relative)
            INFO("g " << g << ", eta " << eta);
            checkAgainst(walk.channels[0].single, single, 1.2e-3, "single scattering");
            checkAgainst(walk.channels[1].coneRadianceSingle, cone, 0.15 * cone, "single-scattered radiance, 20 degrees");
        }
}

TEST_CASE("random walk: energy is conserved and the tallies add up", "[random-walk][cpu]") {
    ScatteringMaterial material = materialPreset("skin1");
    material.g = 0.6;  // an anisotropic walk with sigma_s = sigma_s' of the table (a test value)
    SlabRandomWalkOptions options;
    options.paths = 40000;
    options.angleBins = 7;
    options.profileBins = 13;
    options.profileMaxRadius = 1e6;  // catches every exit
    const SlabRandomWalkResult walk = simulateSlab(material, 40.0, options);
    CHECK(walk.angleBinEdges.size() == 8);
    CHECK(walk.profileBinEdges.size() == 14);
    CHECK(walk.profileBinEdges.back() == 1e6);
    for (const SlabChannelResult& w : walk.channels) {
        CHECK(walk.specular + w.diffuse.value + w.absorbed.value + w.truncated.value == Approx(1.0).margin(1e-12));
        CHECK(w.single.value + w.multiple.value == Approx(w.diffuse.value).margin(1e-12));
        CHECK(w.single.value > 0.0);
        CHECK(w.multiple.value > 0.0);
        CHECK(w.truncatedPaths == 0);
        CHECK(w.meanEvents > 1.0);
        // Power = radiance x projected solid angle, summed over the bins, is all that left.
        double angular = 0.0, angularSingle = 0.0, radial = 0.0;
        for (size_t i = 0; i < w.angleRadiance.size(); ++i) {
            const double m1 = walk.angleBinEdges[i], m2 = walk.angleBinEdges[i + 1];
            angular += w.angleRadiance[i].value * kPi * (m2 * m2 - m1 * m1);
            angularSingle += w.angleRadianceSingle[i].value * kPi * (m2 * m2 - m1 * m1);
        }
        for (size_t i = 0; i < w.profile.size(); ++i) {
            const double r1 = walk.profileBinEdges[i], r2 = walk.profileBinEdges[i + 1];
            radial += w.profile[i].value * kPi * (r2 * r2 - r1 * r1);
        }
        CHECK(angular == Approx(w.diffuse.value).epsilon(1e-9));
        CHECK(angularSingle == Approx(w.single.value).epsilon(1e-9));
        CHECK(radial == Approx(w.diffuse.value).epsilon(1e-9));
    }
    // Truncation: a lossless channel stopped after 5 events; the rest is counted, not lost.
    SlabRandomWalkOptions shortWalks;
    shortWalks.paths = 20000;
    shortWalks.maxEvents = 5;
    const SlabRandomWalkResult cut = simulateSlab(withAlbedos(1.0, 0.5, 0.5, 1.3), 0.0, shortWalks);
    const SlabChannelResult& lossless = cut.channels[0];
    CHECK(lossless.truncatedPaths > 1000);
    CHECK(lossless.truncated.value == Approx(double(lossless.truncatedPaths) / 20000 * (1.0 - cut.specular)));
    CHECK(lossless.absorbed.value == 0.0);
    CHECK(cut.specular + lossless.diffuse.value + lossless.truncated.value == Approx(1.0).margin(1e-12));
    CHECK(lossless.meanEvents <= 5.0);
}

TEST_CASE("random walk: the result depends on the seed, not on the thread count", "[random-walk][cpu]") {
    const ScatteringMaterial material = withAlbedos(0.9, 0.7, 0.95, 1.3, 0.3);
    SlabRandomWalkOptions options;
    options.paths = 50000;  // 4 chunks per channel, 12 work units
    options.angleBins = 5;
    options.profileBins = 6;
    options.profileMaxRadius = 3.0;
    auto run = [&](int threads, uint64_t seed) {
        SlabRandomWalkOptions o = options;
        o.threads = threads;
        o.seed = seed;
        return simulateSlab(material, 20.0, o);
    };
    auto same = [](const SlabRandomWalkResult& a, const SlabRandomWalkResult& b) {
        auto eq = [](const Estimate& x, const Estimate& y) {
            return x.value == y.value && x.standardError == y.standardError;
        };
        auto eqs = [&](const std::vector<Estimate>& x, const std::vector<Estimate>& y) {
            if (x.size() != y.size()) return false;
            for (size_t i = 0; i < x.size(); ++i)
                if (!eq(x[i], y[i])) return false;
            return true;
        };
        for (int c = 0; c < 3; ++c) {
            const SlabChannelResult& p = a.channels[c];
            const SlabChannelResult& q = b.channels[c];
            if (!eq(p.diffuse, q.diffuse) || !eq(p.single, q.single) || !eq(p.absorbed, q.absorbed) ||
                !eq(p.coneRadiance, q.coneRadiance) || !eqs(p.angleRadiance, q.angleRadiance) ||
                !eqs(p.profile, q.profile) || !eqs(p.profileSingle, q.profileSingle) || p.meanEvents != q.meanEvents)
                return false;
        }
        return a.specular == b.specular;
    };
    const SlabRandomWalkResult one = run(1, 5);
    CHECK(same(one, run(2, 5)));
    CHECK(same(one, run(5, 5)));
    CHECK(same(one, run(0, 5)));
    const SlabRandomWalkResult other = run(2, 6);
    CHECK_FALSE(same(one, other));
    // Different seeds are independent estimates of the same thing.
    for (int c = 0; c < 3; ++c) {
        const Estimate& a = one.channels[c].diffuse;
        const Estimate& b = other.channels[c].diffuse;
        CHECK(std::abs(a.value - b.value) <= kSigmas * std::hypot(a.standardError, b.standardError));
    }
    // Channels have their own streams: equal coefficients, different samples.
    const SlabRandomWalkResult grey = simulateSlab(withAlbedos(0.8, 0.8, 0.8, 1.3), 0.0, options);
    CHECK(grey.channels[0].diffuse.value != grey.channels[1].diffuse.value);
}

TEST_CASE("random walk: bad input is rejected with a message naming it", "[random-walk][cpu]") {
    const ScatteringMaterial ok = withAlbedos(0.5, 0.5, 0.5, 1.3);
    SlabRandomWalkOptions o;
    o.paths = 10;
    const auto kind = ErrorKind::InvalidArgument;
    ScatteringMaterial bad = ok;
    bad.eta = 0.0;
    REQUIRE_SSS_ERROR(simulateSlab(bad, 0.0, o), kind, Contains("eta"));
    bad = ok;
    bad.sigmaA.y = -1.0;
    REQUIRE_SSS_ERROR(simulateSlab(bad, 0.0, o), kind, Contains("sigmaA"));
    bad = ok;
    bad.g = 1.0;
    REQUIRE_SSS_ERROR(simulateSlab(bad, 0.0, o), kind, Contains("g"));
    REQUIRE_SSS_ERROR(simulateSlab(ok, -1.0, o), kind, Contains("simulateSlab: incidenceDeg must be in [0, 90), got -1"));
    REQUIRE_SSS_ERROR(simulateSlab(ok, 90.0, o), kind, Contains("incidenceDeg"));
    REQUIRE_SSS_ERROR(simulateSlab(ok, std::nan(""), o), kind, Contains("incidenceDeg"));
    auto withOption = [&](auto set) {
        SlabRandomWalkOptions x = o;
        set(x);
        return x;
    };
    REQUIRE_SSS_ERROR(simulateSlab(ok, 0.0, withOption([](auto& x) { x.paths = 0; })), kind,
                      Contains("SlabRandomWalkOptions::paths must be >= 1, got 0"));
    REQUIRE_SSS_ERROR(simulateSlab(ok, 0.0, withOption([](auto& x) { x.threads = -2; })), kind,
                      Contains("SlabRandomWalkOptions::threads"));
    REQUIRE_SSS_ERROR(simulateSlab(ok, 0.0, withOption([](auto& x) { x.maxEvents = 0; })), kind,
                      Contains("SlabRandomWalkOptions::maxEvents"));
    REQUIRE_SSS_ERROR(simulateSlab(ok, 0.0, withOption([](auto& x) { x.coneHalfAngleDeg = 0.0; })), kind,
                      Contains("SlabRandomWalkOptions::coneHalfAngleDeg"));
    REQUIRE_SSS_ERROR(simulateSlab(ok, 0.0, withOption([](auto& x) { x.coneHalfAngleDeg = 91.0; })), kind,
                      Contains("SlabRandomWalkOptions::coneHalfAngleDeg"));
    REQUIRE_SSS_ERROR(simulateSlab(ok, 0.0, withOption([](auto& x) { x.angleBins = 0; })), kind,
                      Contains("SlabRandomWalkOptions::angleBins"));
    REQUIRE_SSS_ERROR(simulateSlab(ok, 0.0, withOption([](auto& x) { x.profileBins = 0; })), kind,
                      Contains("SlabRandomWalkOptions::profileBins"));
    REQUIRE_SSS_ERROR(simulateSlab(ok, 0.0, withOption([](auto& x) { x.profileMaxRadius = INFINITY; })), kind,
                      Contains("SlabRandomWalkOptions::profileMaxRadius"));
    REQUIRE_SSS_ERROR(chandrasekharH(1.5, 0.5), kind, Contains("chandrasekharH: albedo must be in [0, 1], got 1.5"));
    REQUIRE_SSS_ERROR(chandrasekharH(0.5, -0.1), kind, Contains("mu must be in [0, 1]"));
    REQUIRE_SSS_ERROR(isotropicHalfSpaceReflectance(0.5, 3.0, 0.0), kind, Contains("eta must be in [0.4, 2.5]"));
    REQUIRE_SSS_ERROR(isotropicHalfSpaceReflectance(0.5, 1.3, 95.0), kind, Contains("incidenceDeg"));
    REQUIRE_SSS_ERROR(isotropicHalfSpaceReflectance(-0.5, 1.3, 0.0), kind, Contains("albedo"));
    REQUIRE_SSS_ERROR(isotropicHalfSpaceReflectance(0.5, 1.3, 0.0, 0.0), kind, Contains("coneHalfAngleDeg"));
}

// Not a test: a report (hidden; run with "[random-walk-report]", about a minute on one core).
// For the Jensen presets (reduced coefficients, isotropic walk, eta of the preset) it prints per
// channel the random walk's total diffuse reflectance next to the dipoles':
//  - walk 0 deg: collimated normal incidence, per incident power (specular excluded), +- its
//    standard error, and its single-scattering part;
//  - walk diffuse: under uniform diffuse illumination, the cosine-weighted mean over incidence
//    angles (Gauss-Legendre in cos^2 of the incidence angle, 4 nodes), per incident power;
//  - classic: dipoleDiffuseReflectance(), Jensen's closed form, per power that ENTERED (it has
//    no entry Fresnel term), so next to it the walk at 0 deg divided by 1 - F(0);
//  - dirpole: the directional dipole's plane integral at normal incidence with its Fresnel
//    factors, T(0) * integral S_d dA * integral T(mu) mu dw, what the renderers produce for a lit
//    plane, per incident power.
TEST_CASE("random walk: report of total diffuse reflectance, walk against the dipoles", "[.][random-walk-report]") {
    SlabRandomWalkOptions options;
    options.paths = 100000;
    const Rule incidence = gaussLegendre(4, 0.0, 1.0);  // nodes in u = cos^2(theta_i)
    std::printf("%-9s %2s %8s | %-17s %7s | %8s | %8s %8s | %8s\n", "preset", "ch", "albedo'", "walk 0 deg",
                "single", "walk dif", "walk/T0", "classic", "dirpole");
    for (const char* name : {"cream", "potato", "marble", "skimmilk", "ketchup", "skin1", "apple", "chicken1"}) {
        const ScatteringMaterial m = materialPreset(name);
        const DipoleConstants k = deriveDipoleConstants(m);
        const SlabRandomWalkResult normal = simulateSlab(m, 0.0, options);
        glm::dvec3 diffuseLit(0.0);
        for (size_t i = 0; i < incidence.x.size(); ++i) {
            const double theta = std::acos(std::sqrt(incidence.x[i]));
            const SlabRandomWalkResult r = simulateSlab(m, theta * 180.0 / kPi, options);
            for (int c = 0; c < 3; ++c) diffuseLit[c] += incidence.w[i] * r.channels[c].diffuse.value;
        }
        const glm::dvec3 classic = dipoleDiffuseReflectance(k);
        // Plane integral of S_d on a log grid in r; the hemispherical Fresnel integral by midpoints.
        glm::dvec3 plane(0.0);
        const int n = 20000;
        const double l0 = std::log(1e-7), l1 = std::log(1e4), dl = (l1 - l0) / n;
        for (int i = 0; i < n; ++i) {
            const double r = std::exp(l0 + (i + 0.5) * dl);
            plane += evaluateSd(k, {0, 0, 0}, {0, 0, 1}, {0, 0, 1}, {r, 0, 0}, {0, 0, 1}) * (2.0 * kPi * r * r * dl);
        }
        double hemisphere = 0.0;
        for (int i = 0; i < n; ++i) hemisphere += 2.0 * kPi * fresnelTransmittance(m.eta, (i + 0.5) / n) * (i + 0.5) / n / n;
        const double t0 = fresnelTransmittance(m.eta, 1.0);
        for (int c = 0; c < 3; ++c) {
            const SlabChannelResult& w = normal.channels[c];
            std::printf("%-9s %2s %8.5f | %.4f +- %.4f %7.4f | %8.4f | %8.4f %8.4f | %8.4f\n", name,
                        c == 0 ? "R" : c == 1 ? "G" : "B", k.alphaPrime[c], w.diffuse.value, w.diffuse.standardError,
                        w.single.value, diffuseLit[c], w.diffuse.value / t0, classic[c], t0 * plane[c] * hemisphere);
        }
    }
}

TEST_CASE("random walk: a finite slab conserves energy and lets the exact unscattered beam through", "[random-walk][cpu]") {
    // eta = 1 (no reflection at either face), normal incidence, sigma_t = 1 / mm, 0.7 mm: the
    // unscattered beam leaves the bottom with exp(-0.7) exactly, whatever the albedo. Albedo 0
    // scatters nothing, so nothing else leaves either face.
    SlabRandomWalkOptions o;
    o.paths = 200000;
    o.thickness = 0.7;
    o.seed = 5;
    const SlabRandomWalkResult matched = simulateSlab(withAlbedos(0.9, 0.5, 0.0, 1.0), 0.0, o);
    for (const SlabChannelResult& w : matched.channels) checkAgainst(w.ballistic, std::exp(-0.7), 1.5e-3, "unscattered");
    CHECK(matched.channels[2].transmitted.value == 0.0);
    CHECK(matched.channels[2].diffuse.value == 0.0);
    CHECK(matched.channels[0].transmitted.value > 0.1);  // a thin, bright slab lets light through
    CHECK(matched.channels[0].transmitted.value > matched.channels[1].transmitted.value);
    // With Fresnel faces every path ends in exactly one tally: the fractions sum to 1.
    const SlabRandomWalkResult glass = simulateSlab(withAlbedos(0.99, 0.7, 0.2, 1.4), 30.0, o);
    for (const SlabChannelResult& w : glass.channels) {
        CHECK(glass.specular + w.diffuse.value + w.transmitted.value + w.ballistic.value + w.absorbed.value +
                  w.truncated.value ==
              Approx(1.0).margin(1e-12));
        CHECK(w.transmittedSingle.value <= w.transmitted.value);
        CHECK(w.transmittedConeRadiance.value > 0.0);
    }
    // A slab far thicker than any path reaches is the half-space, draw for draw.
    SlabRandomWalkOptions deep = o;
    deep.paths = 20000;
    deep.thickness = 1e12;
    SlabRandomWalkOptions half = deep;
    half.thickness = std::numeric_limits<double>::infinity();
    const SlabRandomWalkResult a = simulateSlab(withAlbedos(0.95, 0.5, 0.1, 1.3), 0.0, deep);
    const SlabRandomWalkResult b = simulateSlab(withAlbedos(0.95, 0.5, 0.1, 1.3), 0.0, half);
    for (int c = 0; c < 3; ++c) {
        CHECK(a.channels[c].diffuse.value == b.channels[c].diffuse.value);
        CHECK(a.channels[c].transmitted.value == 0.0);
        CHECK(b.channels[c].ballistic.value == 0.0);
    }
    for (double bad : {0.0, -1.0, std::nan("")}) {
        SlabRandomWalkOptions wrong = o;
        wrong.thickness = bad;
        CHECK_THROWS_WITH(simulateSlab(withAlbedos(0.5, 0.5, 0.5, 1.3), 0.0, wrong), Contains("thickness"));
    }
}

// ---- two materials side by side (simulateSplitSlab) ----------------------------------------------

namespace {

// 1 / min(sigma_tr, sigma_t) of one channel, mm: the diffusion length 1 / sigma_tr
// (sigma_tr = sqrt(3 sigma_a sigma_t')), or the mean free path where that is longer (at low
// albedo the exact exit profile decays no faster than exp(-sigma_t r), slower than diffusion
// says). Light is insensitive to a change of material a few of these away.
double decayLength(const ScatteringMaterial& m, int c) {
    const double sigmaT = m.sigmaA[c] + m.sigmaS[c] * (1.0 - m.g);
    return 1.0 / std::min(std::sqrt(3.0 * m.sigmaA[c] * sigmaT), sigmaT);
}

// simulateSlab() at normal incidence with one profile ring out to `radius`, so that
// beyondRadius() is the power leaving farther than `radius` from the entry point.
SlabRandomWalkResult slabWithin(const ScatteringMaterial& m, double radius, std::int64_t paths, std::uint64_t seed) {
    SlabRandomWalkOptions o;
    o.paths = paths;
    o.seed = seed;
    o.profileBins = 1;
    o.profileMaxRadius = radius;
    return simulateSlab(m, 0.0, o);
}

double beyondRadius(const SlabRandomWalkResult& slab, int c) {
    const double r = slab.profileBinEdges.back();
    return slab.channels[c].diffuse.value - slab.channels[c].profile[0].value * kPi * r * r;
}

// A bin of the split walk against the uniformly lit half-space of the material under it:
// within kSigmas combined standard errors, less on the low side by up to `missing` (the light
// that entered beyond the lit strip, see sss/random_walk.h).
void checkFarBin(const Estimate& bin, const Estimate& halfSpace, double missing, const std::string& what) {
    const double se = std::hypot(bin.standardError, halfSpace.standardError);
    INFO(what << ": split walk " << bin.value << " +- " << bin.standardError << ", half-space " << halfSpace.value
              << " +- " << halfSpace.standardError << " (less up to " << missing << "), "
              << (bin.value - halfSpace.value) / se << " standard errors");
    CHECK(bin.value - halfSpace.value <= kSigmas * se);
    CHECK(halfSpace.value - missing - bin.value <= kSigmas * se);
}

void checkEnergy(const SplitSlabResult& r) {
    for (int c = 0; c < 3; ++c) {
        INFO("channel " << c);
        const double sum = r.specular + r.diffuse[c].value + r.absorbed[c].value + r.truncated[c].value;
        CHECK(sum == Approx(1.0).margin(1e-12));
        CHECK(r.truncatedPaths[c] == 0);
        CHECK(r.meanEvents[c] > 0.0);
    }
}

}  // namespace

TEST_CASE("random walk: a half-space split into two halves of one material is that half-space", "[random-walk][cpu]") {
    // Potato on both sides of x = 0: every bin is the uniformly lit half-space, simulateSlab's
    // diffuse reflectance. A bin at |x| <= T misses at most the light that leaves farther than
    // W - T from where it entered (sss/random_walk.h); W - T = 95 mm is 6.6 of potato's longest
    // diffusion length (red, 1 / sigma_tr = 14 mm), and the walk below measures what leaves
    // beyond it: about 5e-5, against standard errors of 2e-2 for a bin (a rigorous allowance,
    // not a tolerance that matters).
    const ScatteringMaterial potato = materialPreset("potato");
    SplitSlabOptions o;
    o.paths = 300000;
    o.entryHalfWidth = 100.0;
    o.tallyHalfWidth = 5.0;
    o.bins = 10;
    o.seed = 3;
    const SplitSlabResult split = simulateSplitSlab(potato, potato, o);
    const SlabRandomWalkResult slab = slabWithin(potato, o.entryHalfWidth - o.tallyHalfWidth, 200000, 3);
    REQUIRE(split.binEdges.size() == 11);
    REQUIRE(split.binCentres.size() == 10);
    CHECK(split.binEdges.front() == -5.0);
    CHECK(split.binEdges.back() == 5.0);
    CHECK(split.binCentres[0] == Approx(-4.5).margin(1e-12));
    CHECK(split.binCentres[5] == Approx(0.5).margin(1e-12));
    CHECK(split.specular == slab.specular);
    CHECK(split.paths == 300000);
    checkEnergy(split);
    for (int c = 0; c < 3; ++c) {
        INFO("channel " << c);
        const Estimate& halfSpace = slab.channels[c].diffuse;
        const double missing = beyondRadius(slab, c);
        CHECK(missing >= -1e-12);
        CHECK(missing < 1e-3);
        // One material: wherever a path enters, it leaves with the half-space's probability.
        checkAgainst(split.diffuse[c], halfSpace.value, 2e-3, "all light leaving, per power on the strip");
        REQUIRE(split.radiosity[c].size() == 10);
        double sum = 0.0, variance = 0.0;
        for (const Estimate& bin : split.radiosity[c]) {
            CHECK(bin.standardError < 0.07 * halfSpace.value);  // the check has teeth
            checkFarBin(bin, halfSpace, missing, "one bin");
            sum += bin.value;
            variance += bin.standardError * bin.standardError;
        }
        // The mean of the bins: 1 / sqrt(10) of a bin's noise (bins' counts are multinomial,
        // slightly anti-correlated, so the independent-bins error is an upper bound).
        checkFarBin({sum / 10.0, std::sqrt(variance) / 10.0}, halfSpace, missing, "mean of the bins");
    }
}

TEST_CASE("random walk: across two materials side by side the radiosity goes from one half-space to the other",
          "[random-walk][cpu]") {
    // A light material on the left (albedos 0.97, 0.95, 0.95) and a dark one on the right
    // (0.5, 0.3, 0.2), both eta 1.3, with decay lengths (decayLength()) of at most 0.86 mm, so
    // that the tallied strip |x| <= 5 mm reaches 5.8 of them from the interface and the lit strip
    // |x| <= 15 mm 11.6 more (the allowance below, what leaves beyond 10 mm, is nothing in
    // 200000 paths). Expected: each material's half-space far from x = 0, a profile that falls across
    // it, and bins next to it strictly between the two.
    ScatteringMaterial light, dark;
    light.sigmaS = {3.88, 3.8, 2.85};
    light.sigmaA = {0.12, 0.2, 0.15};
    light.name = "light";
    dark.sigmaS = {1.0, 0.6, 0.4};
    dark.sigmaA = {1.0, 1.4, 1.6};
    dark.name = "dark";
    light.g = dark.g = 0.0;
    light.eta = dark.eta = 1.3;
    SplitSlabOptions o;
    o.paths = 1'000'000;
    o.entryHalfWidth = 15.0;
    o.tallyHalfWidth = 5.0;
    o.bins = 20;  // 0.5 mm; an edge on the interface
    o.seed = 9;
    const SplitSlabResult split = simulateSplitSlab(light, dark, o);
    const double radius = o.entryHalfWidth - o.tallyHalfWidth;
    const SlabRandomWalkResult slabLight = slabWithin(light, radius, 200000, 9);
    const SlabRandomWalkResult slabDark = slabWithin(dark, radius, 200000, 9);
    checkEnergy(split);
    const int mid = o.bins / 2;  // bins [mid - 1, mid] touch x = 0 from the left and the right
    for (int c = 0; c < 3; ++c) {
        INFO("channel " << c);
        const Estimate& left = slabLight.channels[c].diffuse;
        const Estimate& right = slabDark.channels[c].diffuse;
        REQUIRE(left.value > right.value + 0.05);  // a contrast to resolve
        const double far = 3.0 * std::max(decayLength(light, c), decayLength(dark, c));
        REQUIRE(far < 3.0);
        const std::vector<Estimate>& bins = split.radiosity[c];
        int farBins = 0;
        for (int i = 0; i < o.bins; ++i) {
            const double inner = std::min(std::abs(split.binEdges[i]), std::abs(split.binEdges[i + 1]));
            if (inner <= far) continue;
            const bool onLeft = split.binCentres[i] < 0.0;
            const SlabRandomWalkResult& slab = onLeft ? slabLight : slabDark;
            CHECK(bins[i].standardError < 0.02 * left.value);
            checkFarBin(bins[i], slab.channels[c].diffuse, beyondRadius(slab, c),
                        std::string(onLeft ? "left" : "right") + " bin at x = " + std::to_string(split.binCentres[i]));
            ++farBins;
        }
        CHECK(farBins >= 8);
        // Monotone (falling from light to dark) within the noise.
        for (int i = 0; i + 1 < o.bins; ++i) {
            INFO("bins at x = " << split.binCentres[i] << ", " << split.binCentres[i + 1] << ": " << bins[i].value
                                << ", " << bins[i + 1].value);
            const double se = std::hypot(bins[i].standardError, bins[i + 1].standardError);
            CHECK(bins[i + 1].value - bins[i].value <= kSigmas * se);
        }
        // Next to the interface, on either side: strictly (and significantly) between the far values.
        for (int i : {mid - 1, mid}) {
            INFO("bin at x = " << split.binCentres[i] << ": " << bins[i].value << " +- " << bins[i].standardError
                               << ", half-spaces " << left.value << ", " << right.value);
            CHECK(bins[i].value > right.value + kSigmas * std::hypot(bins[i].standardError, right.standardError));
            CHECK(bins[i].value < left.value - kSigmas * std::hypot(bins[i].standardError, left.standardError));
        }
        CHECK(bins[mid - 1].value > bins[mid].value);
    }
    // Swapping the materials mirrors the profile (x = 0 belongs to the right, a set of measure 0).
    SplitSlabOptions fewer = o;
    fewer.paths = 300000;
    fewer.seed = 10;
    const SplitSlabResult swapped = simulateSplitSlab(dark, light, fewer);
    for (int c = 0; c < 3; ++c)
        for (int i = 0; i < o.bins; ++i) {
            const Estimate& a = split.radiosity[c][i];
            const Estimate& b = swapped.radiosity[c][o.bins - 1 - i];
            INFO("channel " << c << ", x = " << split.binCentres[i] << ": " << a.value << " +- " << a.standardError
                            << ", mirrored " << b.value << " +- " << b.standardError);
            CHECK(std::abs(a.value - b.value) <= kSigmas * std::hypot(a.standardError, b.standardError));
        }
}

TEST_CASE("random walk: the split half-space depends on the seed, not the thread count, and checks its input",
          "[random-walk][cpu]") {
    const ScatteringMaterial potato = materialPreset("potato");
    const ScatteringMaterial ketchup = materialPreset("ketchup");
    SplitSlabOptions options;
    options.paths = 40000;  // 3 chunks per channel, 9 work units
    options.entryHalfWidth = 8.0;
    options.tallyHalfWidth = 2.0;
    options.bins = 7;
    auto run = [&](int threads, std::uint64_t seed) {
        SplitSlabOptions o = options;
        o.threads = threads;
        o.seed = seed;
        return simulateSplitSlab(potato, ketchup, o);
    };
    auto same = [](const SplitSlabResult& a, const SplitSlabResult& b) {
        auto eq = [](const Estimate& x, const Estimate& y) {
            return x.value == y.value && x.standardError == y.standardError;
        };
        for (int c = 0; c < 3; ++c) {
            if (a.radiosity[c].size() != b.radiosity[c].size()) return false;
            for (size_t i = 0; i < a.radiosity[c].size(); ++i)
                if (!eq(a.radiosity[c][i], b.radiosity[c][i])) return false;
            if (!eq(a.diffuse[c], b.diffuse[c]) || !eq(a.absorbed[c], b.absorbed[c]) ||
                !eq(a.truncated[c], b.truncated[c]) || a.meanEvents[c] != b.meanEvents[c])
                return false;
        }
        return a.specular == b.specular && a.binCentres == b.binCentres;
    };
    const SplitSlabResult one = run(1, 5);
    CHECK(same(one, run(2, 5)));
    CHECK(same(one, run(4, 5)));
    CHECK(same(one, run(0, 5)));
    CHECK_FALSE(same(one, run(2, 6)));
    checkEnergy(one);
    // Odd bins: a centre on the interface.
    CHECK(one.binCentres[3] == 0.0);

    const auto kind = ErrorKind::InvalidArgument;
    SplitSlabOptions o;
    o.paths = 10;
    REQUIRE_SSS_ERROR(simulateSplitSlab(potato, materialPreset("marble"), o), kind,
                      Contains("same eta") && Contains("\"potato\" eta 1.3") && Contains("\"marble\" eta 1.5"));
    ScatteringMaterial bad = potato;
    bad.g = 1.0;
    REQUIRE_SSS_ERROR(simulateSplitSlab(bad, ketchup, o), kind,
                      Contains("simulateSplitSlab: left material \"potato\": ScatteringMaterial::g"));
    bad = ketchup;
    bad.sigmaA.z = -1.0;
    REQUIRE_SSS_ERROR(simulateSplitSlab(potato, bad, o), kind, Contains("right material") && Contains("sigmaA"));
    auto withOption = [&](auto set) {
        SplitSlabOptions x = o;
        set(x);
        return x;
    };
    REQUIRE_SSS_ERROR(simulateSplitSlab(potato, ketchup, withOption([](auto& x) { x.paths = 0; })), kind,
                      Contains("simulateSplitSlab: SplitSlabOptions::paths must be >= 1, got 0"));
    REQUIRE_SSS_ERROR(simulateSplitSlab(potato, ketchup, withOption([](auto& x) { x.threads = -1; })), kind,
                      Contains("SplitSlabOptions::threads"));
    REQUIRE_SSS_ERROR(simulateSplitSlab(potato, ketchup, withOption([](auto& x) { x.maxEvents = 0; })), kind,
                      Contains("SplitSlabOptions::maxEvents"));
    for (double w : {0.0, -1.0, std::numeric_limits<double>::infinity(), std::nan("")})
        REQUIRE_SSS_ERROR(simulateSplitSlab(potato, ketchup, withOption([&](auto& x) { x.entryHalfWidth = w; })), kind,
                          Contains("SplitSlabOptions::entryHalfWidth"));
    for (double t : {0.0, -1.0, 20.5, std::nan("")})
        REQUIRE_SSS_ERROR(simulateSplitSlab(potato, ketchup, withOption([&](auto& x) { x.tallyHalfWidth = t; })), kind,
                          Contains("SplitSlabOptions::tallyHalfWidth"));
    REQUIRE_SSS_ERROR(simulateSplitSlab(potato, ketchup, withOption([](auto& x) { x.bins = 0; })), kind,
                      Contains("SplitSlabOptions::bins must be in [1, 1000000], got 0"));
    REQUIRE_SSS_ERROR(simulateSplitSlab(potato, ketchup, withOption([](auto& x) { x.bins = 1000001; })), kind,
                      Contains("SplitSlabOptions::bins"));
    // The boundary case T = W is allowed.
    CHECK_NOTHROW(simulateSplitSlab(potato, ketchup, withOption([](auto& x) { x.tallyHalfWidth = x.entryHalfWidth; })));
}

// Not a test: a report (hidden; run with "[split-slab-report]", about half an hour on two
// busy cores). Potato (x < 0) beside ketchup (x >= 0), the radiosity per unit incident irradiance at
// the interface, for comparison with the renderers' textured materials. Each channel is its own
// run, with the lit strip that channel needs (W - T at least 5 of potato's diffusion lengths in
// it: 14, 7.2 and 2.0 mm) and both materials' coefficients of that channel in all three of the
// walk's channels: three independent estimates, averaged. Bins 0.25 mm wide centred on
// multiples of 0.25 mm.
TEST_CASE("random walk: report of the radiosity across potato beside ketchup", "[.][split-slab-report]") {
    const ScatteringMaterial potato = materialPreset("potato");
    const ScatteringMaterial ketchup = materialPreset("ketchup");
    const struct {
        double entryHalfWidth;
        std::int64_t paths;
    } runs[3] = {{70.0, 32'000'000}, {40.0, 190'000'000}, {20.0, 400'000'000}};
    std::array<SplitSlabResult, 3> results;
    for (int c = 0; c < 3; ++c) {
        auto only = [c](ScatteringMaterial m) {
            m.sigmaA = glm::dvec3(m.sigmaA[c]);
            m.sigmaS = glm::dvec3(m.sigmaS[c]);
            return m;
        };
        SplitSlabOptions o;
        o.paths = runs[c].paths;
        o.entryHalfWidth = runs[c].entryHalfWidth;
        o.tallyHalfWidth = 3.125;
        o.bins = 25;
        o.seed = 2024;
        results[c] = simulateSplitSlab(only(potato), only(ketchup), o);
    }
    std::printf("%7s | %-22s | %-22s | %-22s\n", "x mm", "R", "G", "B");
    for (size_t i = 0; i < results[0].binCentres.size(); ++i) {
        std::printf("%7.3f", results[0].binCentres[i]);
        for (int c = 0; c < 3; ++c) {
            double value = 0.0, variance = 0.0;
            for (const std::vector<Estimate>& channel : results[c].radiosity) {
                value += channel[i].value / 3.0;
                variance += channel[i].standardError * channel[i].standardError / 9.0;
            }
            std::printf(" | %.5f +- %.5f (%4.1f%%)", value, std::sqrt(variance), 100.0 * std::sqrt(variance) / value);
        }
        std::printf("\n");
    }
}
