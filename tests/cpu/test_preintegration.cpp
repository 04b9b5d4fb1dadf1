// The pre-integrated transfer-function table (src/volume/preintegration.h) against integrals
// computed here independently: a fine Riemann sum of the same model along the segment.
#include "volume/preintegration.h"

#include "test_helpers.h"

#include <sss/transfer_function.h>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace sss;

namespace {

// The transfer function at TF coordinate x, interpolated between entries as the GPU does.
glm::dvec4 lookup(const std::vector<glm::vec4>& table, double x) {
    const double u = std::clamp(x, 0.0, 1.0) * (table.size() - 1);
    const size_t i = std::min(static_cast<size_t>(u), table.size() - 2);
    const double f = u - i;
    return glm::dvec4(table[i]) * (1.0 - f) + glm::dvec4(table[i + 1]) * f;
}

struct Exact {
    glm::dvec3 colour{0.0};
    double alpha = 0.0;
    double depth = 0.0;  // opacity-weighted mean position, as a fraction from the front
};

// Front to back through a segment `voxels` long over which the TF coordinate goes linearly
// from x0 to x1: 200000 steps.
Exact integrate(const std::vector<glm::vec4>& table, double x0, double x1, double voxels) {
    constexpr int kSteps = 200000;
    Exact e;
    double transmittance = 1.0, weightedDepth = 0.0;
    for (int k = 0; k < kSteps; ++k) {
        const double s = (k + 0.5) / kSteps;
        const glm::dvec4 tf = lookup(table, x0 + (x1 - x0) * s);
        const double a = 1.0 - std::pow(1.0 - std::min(tf.a, 1.0 - 1e-7), voxels / kSteps);
        e.colour += transmittance * a * glm::dvec3(tf);
        weightedDepth += transmittance * a * s;
        transmittance *= 1.0 - a;
    }
    e.alpha = 1.0 - transmittance;
    e.depth = e.alpha > 0.0 ? weightedDepth / e.alpha : 0.5;
    return e;
}

}  // namespace

TEST_CASE("pre-integration: the diagonal is the point classification with opacity correction", "[preintegration]") {
    const TransferFunction tf({{0.0f, {1.0f, 0.0f, 0.0f}, 0.0f}, {0.5f, {0.2f, 0.6f, 0.1f}, 0.4f},
                               {1.0f, {0.0f, 0.3f, 1.0f}, 0.95f}});
    const std::vector<glm::vec4> table = tf.table(256);
    for (const float voxels : {0.5f, 1.0f, 2.0f}) {
        const std::vector<glm::vec4> pre = detail::preintegrate(table, 256, voxels);
        for (const int i : {0, 40, 128, 200, 255}) {
            const glm::vec4 entry = pre[static_cast<size_t>(i) * 256 + i];
            const double alpha = 1.0 - std::pow(1.0 - table[i].a, double(voxels));
            INFO("entry " << i << ", segment " << voxels << " voxels");
            CHECK(entry.a == Approx(alpha).margin(1e-6));
            CHECK(entry.r == Approx(table[i].r * alpha).margin(1e-6));
            CHECK(entry.b == Approx(table[i].b * alpha).margin(1e-6));
        }
    }
}

TEST_CASE("pre-integration: segments across a thin opaque band match the integral", "[preintegration]") {
    // A band of opacity 0.9 only 0.02 wide in value: a point-sampled ray whose samples step over
    // it sees nothing; the table must hold what a segment crossing it really absorbs.
    const TransferFunction tf({{0.0f, {0.1f, 0.1f, 0.9f}, 0.0f}, {0.485f, {0.1f, 0.1f, 0.9f}, 0.0f},
                               {0.49f, {0.9f, 0.2f, 0.1f}, 0.9f}, {0.51f, {0.9f, 0.2f, 0.1f}, 0.9f},
                               {0.515f, {0.1f, 0.1f, 0.9f}, 0.0f}, {1.0f, {0.1f, 0.1f, 0.9f}, 0.05f}});
    const std::vector<glm::vec4> table = tf.table(256);
    const std::vector<glm::vec4> pre = detail::preintegrate(table, 256, 1.0f);
    const size_t layer = 256u * 256u;
    // (front, back) entries: across the band both ways, beside it, a long stretch.
    for (const auto [front, back] : {std::pair{120, 135}, std::pair{135, 120}, std::pair{100, 110},
                                     std::pair{0, 255}, std::pair{255, 0}, std::pair{124, 131}}) {
        const Exact e = integrate(table, front / 255.0, back / 255.0, 1.0);
        const glm::vec4 entry = pre[static_cast<size_t>(back) * 256 + front];
        const float depth = entry.a > 0.0f ? pre[layer + static_cast<size_t>(back) * 256 + front].r / entry.a : 0.5f;
        INFO("front " << front << ", back " << back << ": exact alpha " << e.alpha << ", colour " << e.colour.r
                      << " " << e.colour.g << " " << e.colour.b << ", depth " << e.depth);
        // Half-entry sub-steps stay within this margin of the fine sum; one-entry sub-steps were up
        // to 9e-3 off (measured).
        CHECK(entry.a == Approx(e.alpha).margin(5e-3));
        CHECK(entry.r == Approx(e.colour.r).margin(5e-3));
        CHECK(entry.g == Approx(e.colour.g).margin(5e-3));
        CHECK(entry.b == Approx(e.colour.b).margin(5e-3));
        CHECK(depth == Approx(e.depth).margin(2e-2));
    }
    // Opacity does not depend on the direction of travel.
    CHECK(pre[135u * 256u + 120u].a == Approx(pre[120u * 256u + 135u].a).margin(1e-6));
}

TEST_CASE("pre-integration: where a homogeneous stretch adds its light", "[preintegration]") {
    CHECK(detail::meanContributionDepth(0.0) == Approx(0.5));
    // Continuous where the series hands over to the closed form (slope -1/12 there).
    CHECK(detail::meanContributionDepth(0.0999) == Approx(detail::meanContributionDepth(0.1001) + 0.0002 / 12.0).margin(3e-6));
    // The mean of x under tau e^(-tau x) on [0, 1], by a fine sum.
    for (const double tau : {0.01, 0.5, 3.0, 40.0}) {
        double num = 0.0, den = 0.0;
        for (int k = 0; k < 100000; ++k) {
            const double x = (k + 0.5) / 100000.0, w = std::exp(-tau * x);
            num += x * w;
            den += w;
        }
        CHECK(detail::meanContributionDepth(tau) == Approx(num / den).epsilon(1e-4));
    }
}
