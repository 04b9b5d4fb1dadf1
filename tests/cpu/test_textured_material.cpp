// Textured translucent materials (sss/materials.h, TexturedScattering): the reflectance of a texel
// becomes coefficients through the calibrated profile's reflectance (materialFromReflectance), and
// those coefficients must reflect that colour physically, i.e. in the slab random walk.
#include "cpu/test_helpers.h"
#include "mesh/reflectance_table.h"

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

namespace {

// The textured rule on the two-material half-space (materials side by side, the interface at
// x = 0, lit head-on by unit irradiance): the radiosity leaving at x per the rule of
// mesh/reflectance_table.h. x_o's profile spreads the light of the whole plane, a share F of it
// from beyond the interface: the entries' mean ln gathered is (1 - F) ln g_own + F ln g_other.
// The surroundings' mean is over two squares around x_o (detail::kSurroundingWidths; the
// texture's mip chain, exact here), a share B of them beyond the interface. The
// rule is exp of their mean (kSurroundingShare), plus x_o's single scattering. `geometricMean`
// false: the exit point's material alone, g_own.
double ruleRadiosity(double x, const ScatteringMaterial& own, const ScatteringMaterial& other, int channel,
                     bool geometricMean) {
    auto multipleOf = [&](const DipoleConstants& c) {
        return fresnelTransmittance(c.eta, 1.0) * dipolePlaneIntegral(c, 1.0)[channel] * fresnelHemisphereIntegral(c.eta);
    };
    const DipoleConstants c = deriveDipoleConstants(own, 1.0, ScatteringProfile::Calibrated);
    const DipoleConstants o = deriveDipoleConstants(other, 1.0, ScatteringProfile::Calibrated);
    const glm::dvec3 z{0.0, 0.0, 1.0};
    const double d = std::abs(x);
    // Log-spaced midpoint rule in r: the profile's integral and the part beyond the interface.
    const double mfp = 1.0 / (own.sigmaA[channel] + own.sigmaS[channel]);
    const double r0 = 1e-5 * mfp, r1 = 400.0 * mfp;
    const int n = 4000;
    double whole = 0.0, beyond = 0.0;
    for (int k = 0; k < n; ++k) {
        const double ra = r0 * std::pow(r1 / r0, double(k) / n), rb = r0 * std::pow(r1 / r0, double(k + 1) / n);
        const double r = std::sqrt(ra * rb), area = 3.141592653589793 * (rb * rb - ra * ra);
        const double s = evaluateSd(c, glm::dvec3(0.0), z, z, glm::dvec3(r, 0.0, 0.0), z)[channel] * area;
        whole += s;
        if (r > d) beyond += s * std::acos(d / r) / 3.141592653589793;
    }
    const double entries = beyond / whole;
    double surroundings = 0.0;
    for (double width : detail::kSurroundingWidths) {
        width /= c.sigmaTr[channel];
        surroundings += 0.5 * std::max(0.0, 0.5 * width - d) / width;
    }
    const double share = (1.0 - detail::kSurroundingShare) * entries + detail::kSurroundingShare * surroundings;
    const double multiple = multipleOf(c), otherMultiple = multipleOf(o);
    const double single = profileDiffuseReflectance(c, 1.0)[channel] - multiple;
    if (!geometricMean) return multiple + single;
    return std::exp((1.0 - share) * std::log(multiple) + share * std::log(otherMultiple)) + single;
}

}  // namespace

TEST_CASE("two texels side by side: the textured rule against the random walk", "[textured-material][random-walk]") {
    // The goal: a two-material slab's transition matches the random walk within 10 %
    // relRmse. Two colours of one mean free path (a texture changes the albedo, not the path)
    // meet at x = 0; the random walk (simulateSplitSlab) carries the light across, and the rule
    // is evaluated as the renderers evaluate it (the GPU follows the CPU reference of the same
    // rule: test_mesh_textured.cpp). Window: +-3 mm, about 4 diffusion lengths of the darker side
    // and 0.6 of the lighter one's widest channel, where the transition happens. Measured relRmse
    // over the window, all channels (4M paths, 12 bins): the exit point's material alone 0.316,
    // the rule 0.064; the pair rules measured before it, x_o's profile times
    // (R(x_i) / R(x_o))^m, 0.194 (m 0.5) and 0.136 (m 1) (docs/textured-materials.md).
    const glm::dvec3 light{0.75, 0.55, 0.35}, dark{0.12, 0.3, 0.06};
    const glm::dvec3 mfp{0.8, 0.8, 0.8};
    const ScatteringMaterial left = materialFromReflectance(light, mfp, 1.3), right = materialFromReflectance(dark, mfp, 1.3);
    SplitSlabOptions o;
    o.paths = 4'000'000;
    o.entryHalfWidth = 40.0;
    o.tallyHalfWidth = 3.0;
    o.bins = 12;
    o.seed = 11;
    const SplitSlabResult walk = simulateSplitSlab(left, right, o);
    std::array<double, 2> error{};
    for (bool geometricMean : {false, true}) {
        double sumError = 0.0, sumWalk = 0.0;
        for (int c = 0; c < 3; ++c)
            for (std::size_t b = 0; b < walk.binCentres.size(); ++b) {
                const double x = walk.binCentres[b];
                const double rule = x < 0.0 ? ruleRadiosity(x, left, right, c, geometricMean)
                                            : ruleRadiosity(x, right, left, c, geometricMean);
                const double truth = walk.radiosity[static_cast<size_t>(c)][b].value;
                sumError += (rule - truth) * (rule - truth);
                sumWalk += truth * truth;
                if (geometricMean && b % 2 == 0)
                    std::printf("[textured] channel %d x %+.2f mm: walk %.4f rule %.4f\n", c, x, truth, rule);
            }
        error[geometricMean ? 1 : 0] = std::sqrt(sumError / sumWalk);
        std::printf("[textured] two texels, %s: relRmse %.4f\n", geometricMean ? "the rule" : "exit point alone",
                    error[geometricMean ? 1 : 0]);
    }
    CHECK(error[1] < 0.07);
    CHECK(error[1] < 0.25 * error[0]);
}

TEST_CASE("the textured rule's surroundings come from ln gathered's mip chain at a level set by the texel density",
          "[textured-material]") {
    // LogGatheredMips: level 0 is ln gathered of each texel; each level above is the mean of 2 x 2
    // (a geometric mean of gathered), as glGenerateTextureMipmap builds it on the GPU.
    Image8 image(4, 2);
    const std::uint8_t values[8] = {10, 60, 120, 250, 200, 30, 90, 180};
    for (int i = 0; i < 8; ++i) image.at(i % 4, i / 4) = glm::u8vec4(values[i], values[7 - i], 128, 255);
    const detail::ReflectanceTable& table = detail::reflectanceTable(1.3, ScatteringProfile::Calibrated);
    const detail::LogGatheredMips mips(image, table);
    auto logOf = [&](std::uint8_t v) {
        return std::log(std::max(detail::invertReflectance(table, detail::srgbToLinear(v)).gathered, detail::kMinGathered));
    };
    // Texture coordinate (0, 0) is the image's bottom-left: row 1 of the image is v in [0, 0.5].
    CHECK(mips(glm::dvec2(0.125, 0.75), 0.0, 0) == Approx(logOf(values[0])).epsilon(1e-12));
    CHECK(mips(glm::dvec2(0.875, 0.25), 0.0, 1) == Approx(logOf(values[0])).epsilon(1e-12));
    // Level 1 (2 x 1): the left texel holds the mean of the image's left 2 x 2 block.
    const double left = 0.25 * (logOf(values[0]) + logOf(values[1]) + logOf(values[4]) + logOf(values[5]));
    CHECK(mips(glm::dvec2(0.25, 0.5), 1.0, 0) == Approx(left).epsilon(1e-12));
    // Level 2 (1 x 1) is the mean of all; levels beyond the chain clamp to it, between levels linear.
    double all = 0.0;
    for (std::uint8_t v : values) all += logOf(v) / 8.0;
    CHECK(mips(glm::dvec2(0.3, 0.6), 2.0, 0) == Approx(all).epsilon(1e-12));
    CHECK(mips(glm::dvec2(0.3, 0.6), 9.0, 0) == Approx(all).epsilon(1e-12));
    CHECK(mips(glm::dvec2(0.25, 0.5), 1.5, 0) == Approx(0.5 * (left + all)).epsilon(1e-12));
    CHECK(mips.baseLevelRgba().size() == 4u * 8u);

    // surroundingLevel: log2 of the width in texels, 0 below one texel.
    CHECK(detail::surroundingLevel(2.0, 8.0) == Approx(4.0));
    CHECK(detail::surroundingLevel(0.05, 8.0) == 0.0);

    // meanTexelDensity: a 2 x 2 square mapped onto the whole of a 64 x 32 texture, scaled by 3.
    const Mesh square = Mesh::fromArrays({{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}}, {0, 1, 2, 0, 2, 3},
                                         {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}}, "square",
                                         {{0, 0}, {1, 0}, {1, 1}, {0, 1}});
    const double density = detail::meanTexelDensity(square, glm::mat4(3.0f), 64, 32);  // w = 3 as well
    CHECK(density == Approx(std::sqrt(64.0 * 32.0) / 6.0).epsilon(1e-9));
    CHECK(detail::meanTexelDensity(Mesh::fromArrays({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2}, {}, "no uv"),
                                   glm::mat4(1.0f), 64, 64) == 0.0);
}
