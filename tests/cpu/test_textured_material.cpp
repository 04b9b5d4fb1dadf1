// Textured translucent materials (sss/materials.h, TexturedScattering): the reflectance of a texel
// becomes coefficients through the calibrated profile's reflectance (materialFromReflectance), and
// those coefficients must reflect that colour physically, i.e. in the slab random walk.
#include "cpu/test_helpers.h"

#include <catch2/catch.hpp>
#include <sss/bssrdf.h>
#include <sss/error.h>
#include <sss/materials.h>
#include <sss/random_walk.h>

#include <cmath>
#include <cstdio>
#include <limits>

using namespace sss;
using Catch::Matchers::Contains;

TEST_CASE("materialFromReflectance inverts the profile's reflectance", "[textured-material]") {
    const glm::dvec3 mfp{1.0, 0.5, 2.0};
    for (ScatteringProfile profile : {ScatteringProfile::Calibrated, ScatteringProfile::Dipole}) {
        for (double eta : {1.3, 1.5}) {
            for (const glm::dvec3 reflectance : {glm::dvec3(0.8, 0.5, 0.2), glm::dvec3(0.05, 0.3, 0.65)}) {
                const ScatteringMaterial m = materialFromReflectance(reflectance, mfp, eta, profile);
                // The mean free path is kept exactly; the reflectance comes back from the table's
                // interpolation: measured within 0.22 % (96 nodes in sqrt(1 - alpha')). The
                // paper's dipole cannot reflect less than about 0.1 (its extrapolation distance
                // diverges at low albedo): darker channels are clamped to its darkest.
                const double darkest =
                    profileDiffuseReflectance(deriveDipoleConstants(materialFromReflectance(glm::dvec3(0.0), mfp, eta, profile), 1.0, profile), 1.0).x;
                const glm::dvec3 back = profileDiffuseReflectance(deriveDipoleConstants(m, 1.0, profile), 1.0);
                for (int c = 0; c < 3; ++c) {
                    INFO(toString(profile) << " eta " << eta << " channel " << c);
                    CHECK(1.0 / (m.sigmaA[c] + m.sigmaS[c]) == Approx(mfp[c]).epsilon(1e-12));
                    CHECK(back[c] == Approx(std::max(reflectance[c], darkest)).epsilon(0.004));
                }
                CHECK(m.eta == eta);
                CHECK(m.g == 0.0);
            }
        }
    }
}

TEST_CASE("materialFromReflectance clamps what the profile cannot reach and rejects bad input", "[textured-material]") {
    const ScatteringMaterial black = materialFromReflectance(glm::dvec3(0.0), glm::dvec3(1.0), 1.3);
    const ScatteringMaterial white = materialFromReflectance(glm::dvec3(1.0), glm::dvec3(1.0), 1.3);
    CHECK(black.sigmaS.x == Approx(1e-4).epsilon(1e-6));      // the floor of the reduced albedo
    CHECK(white.sigmaA.x == Approx(5e-5).epsilon(1e-6));      // the ceiling 0.99995
    CHECK_THROWS_WITH(materialFromReflectance(glm::dvec3(std::nan("")), glm::dvec3(1.0), 1.3), Contains("reflectance"));
    CHECK_THROWS_WITH(materialFromReflectance(glm::dvec3(0.5), glm::dvec3(1.0, 0.0, 1.0), 1.3), Contains("meanFreePath"));
    CHECK_THROWS_WITH(materialFromReflectance(glm::dvec3(0.5), glm::dvec3(1.0), 3.0), Contains("eta"));
    TexturedScattering t;
    t.meanFreePath = glm::dvec3(1.0, -1.0, 1.0);
    CHECK_THROWS_WITH(t.validate(), Contains("TexturedScattering") && Contains("meanFreePath"));
    const TexturedScattering marble = texturedScattering(materialPreset("marble"));
    CHECK(marble.eta == 1.5);
    CHECK(marble.meanFreePath.x == Approx(1.0 / (2.19 + 0.0021)));
}

TEST_CASE("a texel's coefficients reflect its colour in the random walk", "[textured-material][random-walk]") {
    // The goal: a flat-lit textured slab reproduces the texture's reflectance within 3 %
    // per channel, measured against the random walk at the same per-texel coefficients. The
    // colours span dark to bright; the mean free paths are skin-like and marble-like.
    SlabRandomWalkOptions o;
    o.paths = 200'000;
    o.seed = 7;
    for (const glm::dvec3 colour : {glm::dvec3(0.75, 0.45, 0.3), glm::dvec3(0.1, 0.25, 0.6)}) {
        const ScatteringMaterial m = materialFromReflectance(colour, glm::dvec3(1.2, 0.6, 0.3), 1.3);
        const SlabRandomWalkResult walk = simulateSlab(m, 0.0, o);
        for (int c = 0; c < 3; ++c) {
            const Estimate d = walk.channels[static_cast<size_t>(c)].diffuse;
            std::printf("[textured] colour %.2f walk %.4f +- %.4f (%+.2f %%)\n", colour[c], d.value, d.standardError,
                        100.0 * (d.value / colour[c] - 1.0));
            INFO("channel " << c << ": colour " << colour[c] << ", random walk " << d.value << " +- " << d.standardError);
            CHECK(std::abs(d.value / colour[c] - 1.0) < 0.03);
        }
    }
}
