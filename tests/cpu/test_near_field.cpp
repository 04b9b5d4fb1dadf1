// The profile's near field (src/mesh/near_field.h): the disk integral against the plane integral
// it must reduce to, and the table's limits.
#include "mesh/near_field.h"
#include "mesh/near_field_cache.h"

#include <catch2/catch.hpp>
#include <sss/bssrdf.h>
#include <sss/materials.h>

#include <algorithm>
#include <cmath>
#include <numbers>

using namespace sss;

namespace {

DipoleConstants constants(const char* preset, ScatteringProfile profile) {
    return deriveDipoleConstants(materialPreset(preset), 1.0, profile);  // lengths in mm
}

void requireClose(const glm::dvec3& a, const glm::dvec3& b, double relative) {
    for (int c = 0; c < 3; ++c) {
        INFO("channel " << c << ": " << a[c] << " against " << b[c]);
        REQUIRE(a[c] == Approx(b[c]).epsilon(relative));
    }
}

}  // namespace

TEST_CASE("near field: lit head-on, the disk is the plane integral's circle", "[cpu][near-field]") {
    for (const ScatteringProfile profile : {ScatteringProfile::Dipole, ScatteringProfile::Calibrated})
        for (const char* preset : {"marble", "skin1", "ketchup"})
            for (const double radius : {0.2, 1.0, 5.0}) {
                INFO(preset << ", radius " << radius << " mm");
                const DipoleConstants c = constants(preset, profile);
                requireClose(detail::dipoleDiskIntegral(c, 1.0, radius), dipolePlaneIntegral(c, 1.0, radius), 2e-3);
            }
}

TEST_CASE("near field: a disk wider than the profile holds cos theta times the plane integral", "[cpu][near-field]") {
    // The light's disk covers the plane once, foreshortened by cos theta.
    const DipoleConstants c = constants("skin1", ScatteringProfile::Calibrated);
    for (const double mu : {0.9, 0.5, 0.2}) {
        INFO("cos theta " << mu);
        requireClose(detail::dipoleDiskIntegral(c, mu, 400.0), mu * dipolePlaneIntegral(c, mu), 5e-3);
    }
}

TEST_CASE("near field: the table grows with its radius and vanishes at grazing light", "[cpu][near-field]") {
    const DipoleConstants c = constants("marble", ScatteringProfile::Calibrated);
    const detail::NearFieldTable none = detail::tabulateNearField(c, 0.0, 1.0);
    const detail::NearFieldTable small = detail::tabulateNearField(c, 0.5, 1.0), large = detail::tabulateNearField(c, 20.0, 1.0);
    CHECK(none.radius == 0.0f);
    CHECK(none.reflectance.back().x == 0.0f);
    CHECK(small.reflectance[0].x == Approx(0.0f).margin(1e-3));  // T(eta, 0) = 0
    for (int i = 1; i < detail::kNearFieldNodes; ++i)
        for (int ch = 0; ch < 3; ++ch) {
            INFO("node " << i << ", channel " << ch);
            REQUIRE(small.reflectance[i][ch] > 0.0f);
            REQUIRE(large.reflectance[i][ch] > small.reflectance[i][ch]);
        }
    // Head-on, a disk of many diffusion lengths holds the whole light: T(eta, 1) times the
    // plane integral, per unit irradiance.
    const glm::dvec3 whole = fresnelTransmittance(c.eta, 1.0) * dipolePlaneIntegral(c, 1.0);
    for (int ch = 0; ch < 3; ++ch) CHECK(large.reflectance.back()[ch] == Approx(whole[ch]).epsilon(0.01));
}

TEST_CASE("near field behind: the light through a slab falls with depth at the transport coefficient's rate",
          "[cpu][near-field]") {
    // Far from the lit surface diffusion leaves one decaying mode, e^(-sigma_tr d), times the
    // spread of the light from each entry point: the log-slope of the disk integral between 4 and
    // 6 diffusion lengths is sigma_tr plus about 1 / d. Measured: 1.20 sigma_tr in marble, 0.71 to
    // 1.20 in skin1 (the calibrated profile's factor where light goes through flattens its blue).
    // Extinction (sigma_t') instead of sigma_tr would be 2 to 10 times steeper.
    for (const ScatteringProfile profile : {ScatteringProfile::Dipole, ScatteringProfile::Calibrated})
        for (const char* preset : {"marble", "skin1"}) {
            const DipoleConstants c = constants(preset, profile);
            for (int ch = 0; ch < 3; ++ch) {
                const double length = 1.0 / c.sigmaTr[ch], radius = 40.0 * length;
                const double near = detail::dipoleDiskIntegralBehind(c, 4.0 * length, radius)[ch];
                const double far = detail::dipoleDiskIntegralBehind(c, 6.0 * length, radius)[ch];
                INFO(preset << ", channel " << ch << ": " << near << " at 4 lengths, " << far << " at 6");
                REQUIRE(far > 0.0);
                const double rate = std::log(near / far) / (2.0 * length) / c.sigmaTr[ch];
                CHECK(rate > 0.65);
                CHECK(rate < 1.3);
            }
        }
}

TEST_CASE("near field behind: the table falls with depth, grows with the disk, and ends at six diffusion lengths",
          "[cpu][near-field]") {
    const DipoleConstants c = constants("skin1", ScatteringProfile::Calibrated);
    const detail::NearFieldTable small = detail::tabulateNearField(c, 2.0, 1.0), large = detail::tabulateNearField(c, 20.0, 1.0);
    const double longest = 1.0 / std::min({c.sigmaTr.x, c.sigmaTr.y, c.sigmaTr.z});
    CHECK(large.behindDepth == Approx(6.0 * longest).epsilon(1e-5));
    REQUIRE(small.behindDepth == large.behindDepth);  // the same depths node for node
    for (int i = 0; i < detail::kNearFieldNodes; ++i)
        for (int ch = 0; ch < 3; ++ch) {
            INFO("node " << i << ", channel " << ch);
            REQUIRE(large.behind[i][ch] >= 0.0f);
            // Within a diffusion length of the lit surface the light may still rise (the fluence
            // peaks below it); from the 14th node on (a diffusion length of the widest channel) it falls.
            if (i >= 14) REQUIRE(large.behind[i][ch] <= large.behind[i - 1][ch]);
            if (i < detail::kNearFieldNodes / 2) REQUIRE(large.behind[i][ch] > small.behind[i][ch]);
        }
    // At the deepest node the widest channel keeps a few hundredths of what enters at the
    // surface (measured 0.044).
    CHECK(large.behind.back().x < 0.06f * large.behind[0].x);
}

TEST_CASE("near field: its radius is the edges asked for, within the disk, and none on fine meshes", "[cpu][near-field]") {
    CHECK(detail::nearFieldRadius(1.0f, 2.0, 4.0, 10.0f) == Approx(2.0f));
    CHECK(detail::nearFieldRadius(2.0f, 2.0, 4.0, 3.0f) == Approx(3.0f));  // at most the disk
    CHECK(detail::nearFieldRadius(0.0f, 2.0, 4.0, 10.0f) == 0.0f);         // off
    CHECK(detail::nearFieldRadius(1.0f, 2.0, detail::kNearFieldMinEdgeRatio, 10.0f) == Approx(2.0f));
    CHECK(detail::nearFieldRadius(1.0f, 2.0, 0.99 * detail::kNearFieldMinEdgeRatio, 10.0f) == 0.0f);
}

TEST_CASE("near field: the correction's weight is 1 within its reach and falls as the area within it", "[cpu][near-field]") {
    const double k = detail::kNearFieldCorrectionFreePaths;
    CHECK(detail::nearFieldCorrection(0.5 * k) == 1.0f);
    CHECK(detail::nearFieldCorrection(k) == 1.0f);
    CHECK(detail::nearFieldCorrection(2.0 * k) == Approx(0.25f));
    CHECK(detail::nearFieldCorrection(10.0 * k) == Approx(0.01f));
    // The table applies it per channel to the edge in reduced mean free paths, not diffusion
    // lengths: skin1's blue, sigma_t' 1.97 / mm against sigma_tr 1.46, at 5 mm edges.
    const DipoleConstants skin = constants("skin1", ScatteringProfile::Calibrated);
    const detail::NearFieldTable table = detail::tabulateNearField(skin, 1.0, 5.0);
    for (int c = 0; c < 3; ++c) CHECK(table.correction[c] == Approx(detail::nearFieldCorrection(5.0 * skin.sigmaTPrime[c])));
}

TEST_CASE("near field of a textured material: each albedo's share within the radius over the widest one's",
          "[cpu][near-field][textured]") {
    const TexturedScattering textured = texturedScattering(materialPreset("skin1"));
    const ScatteringMaterial widest =
        materialFromReflectance({0.6, 0.4, 0.3}, textured.meanFreePath, textured.eta, ScatteringProfile::Calibrated);
    detail::NearFieldTable table = detail::tabulateNearField(constants("skin1", ScatteringProfile::Calibrated), 2.0, 2.0);
    detail::tabulateTexturedNearFieldShare(table, widest, 1.0, ScatteringProfile::Calibrated);
    // Node i holds reduced albedo 1 - (1 - i / 32)^2: the widest material's own share is 1 there,
    // a darker (lower-albedo, narrower) material keeps more of its light near, a brighter one less.
    auto shareAt = [&](double albedo, int c) {
        const double f = (1.0 - std::sqrt(1.0 - albedo)) * (detail::kNearFieldNodes - 1);
        const int i = std::min(static_cast<int>(f), detail::kNearFieldNodes - 2);
        return glm::mix(table.texturedShare[i][c], table.texturedShare[i + 1][c], static_cast<float>(f - i));
    };
    for (int c = 0; c < 3; ++c) {
        INFO("channel " << c);
        const double albedo = widest.sigmaS[c] / (widest.sigmaS[c] + widest.sigmaA[c]);
        CHECK(shareAt(albedo, c) == Approx(1.0f).epsilon(0.01));
        for (int i = 1; i < detail::kNearFieldNodes; ++i) CHECK(table.texturedShare[i][c] < table.texturedShare[i - 1][c]);
        CHECK(table.texturedShare[0][c] > 1.0f);
        CHECK(table.texturedShare[detail::kNearFieldNodes - 1][c] < 1.0f);
    }
    // Without a near field there is nothing to scale.
    detail::NearFieldTable none = detail::tabulateNearField(constants("skin1", ScatteringProfile::Calibrated), 0.0, 2.0);
    detail::tabulateTexturedNearFieldShare(none, widest, 1.0, ScatteringProfile::Calibrated);
    for (const glm::vec3& share : none.texturedShare) CHECK(share == glm::vec3(1.0f));
}

TEST_CASE("near field points: divisions per triangle follow the spacing, at most 8", "[cpu][near-field]") {
    CHECK(detail::nearFieldDivisions(1.0f, 0.3f) == 4);
    CHECK(detail::nearFieldDivisions(1.0f, 0.25f) == 4);  // exactly four spacings
    CHECK(detail::nearFieldDivisions(0.1f, 0.3f) == 1);   // narrower than the spacing: its corners
    CHECK(detail::nearFieldDivisions(1.0f, 0.0f) == 1);   // no spacing: corners only
    CHECK(detail::nearFieldDivisions(1.0f, 1e-4f) == detail::kMaxNearFieldDivisions);
}

TEST_CASE("near field points: each triangle's grid follows the previous one's", "[cpu][near-field]") {
    // Divisions 4, 1 and 2: 15, 3 and 6 points.
    const detail::NearFieldPointLayout layout = detail::layoutNearFieldPoints({1.0f, 0.1f, 0.5f}, 0.25f);
    REQUIRE(layout.triangles.size() == 3);
    CHECK(layout.triangles[0] == (0u << 3 | 3u));
    CHECK(layout.triangles[1] == (15u << 3 | 0u));
    CHECK(layout.triangles[2] == (18u << 3 | 1u));
    REQUIRE(layout.pointTriangles.size() == 24);
    CHECK(std::count(layout.pointTriangles.begin(), layout.pointTriangles.end(), 0u) == 15);
    CHECK(std::count(layout.pointTriangles.begin(), layout.pointTriangles.end(), 1u) == 3);
    CHECK(std::count(layout.pointTriangles.begin(), layout.pointTriangles.end(), 2u) == 6);
    CHECK(std::is_sorted(layout.pointTriangles.begin(), layout.pointTriangles.end()));
}

TEST_CASE("near field rings: the azimuth's means of the lit rise, closed form against quadrature", "[cpu][near-field]") {
    for (const double r : {0.5, 2.0}) {
        for (const double t : {-3.0, -2.0, -1.0, -0.3, 0.0, 0.4, 1.2, 1.9, 2.5}) {
            double h = 0.0, q = 0.0;
            constexpr int kSteps = 20000;
            for (int j = 0; j < kSteps; ++j) {
                const double lit = std::max(r * std::cos(std::numbers::pi * (j + 0.5) / kSteps) - t, 0.0);
                h += lit / kSteps;
                q += lit * lit / kSteps;
            }
            const glm::dvec2 m = detail::nearFieldRingMoments(r, t);
            INFO("r " << r << ", t " << t);
            CHECK(m.x == Approx(h).margin(1e-7).epsilon(1e-5));
            CHECK(m.y == Approx(q).margin(1e-7).epsilon(1e-5));
        }
    }
}

namespace {

// What shaders/mesh/near_field.glsl's nearFieldRingLit gives, summed over the taps: the light
// entering a surface whose cos theta is c at x_o and rises by g per unit length, per unit irradiance.
glm::dvec3 ringsLit(const detail::NearFieldTable& table, double c, double g) {
    auto nearFieldAt = [&](double cosTheta, int ch) {
        const double f = std::clamp(cosTheta, 0.0, 1.0) * (detail::kNearFieldNodes - 1);
        const int i = std::min(static_cast<int>(f), detail::kNearFieldNodes - 2);
        return table.reflectance[i][ch] + (f - i) * (table.reflectance[i + 1][ch] - table.reflectance[i][ch]);
    };
    glm::dvec3 sum(0.0);
    for (int k = 0; k < detail::kNearFieldTaps; ++k) {
        const detail::NearFieldRingTable& ring = table.rings[k];
        const double t = -c / g;
        if (!(t < ring.outer)) continue;
        for (int ch = 0; ch < 3; ++ch) {
            double h, q;
            if (!(t > -ring.outer)) {
                h = -t;
                q = t * t + 0.5 * ring.meanSquareRadius[ch];
            } else {
                const double f = 0.5 * (t / ring.outer + 1.0) * (detail::kNearFieldRingNodes - 1);
                const int i = std::min(static_cast<int>(f), detail::kNearFieldRingNodes - 2);
                h = ring.h[i][ch] + (f - i) * (ring.h[i + 1][ch] - ring.h[i][ch]);
                q = ring.q[i][ch] + (f - i) * (ring.q[i + 1][ch] - ring.q[i][ch]);
            }
            sum[ch] += table.tapWeight[k][ch] * g * h * nearFieldAt(g * q / std::max(h, 1e-30), ch);
        }
    }
    return sum;
}

// The light entering a sphere of radius `radius` (mm, marble) lit along +z that reaches the point
// a distance t beyond its terminator (t < 0: before it), per unit irradiance, by quadrature over
// the lit cap within 60 mm of the terminator.
glm::dvec3 sphereBeyondTerminator(const DipoleConstants& c, double radius, double t) {
    const double a = t / radius;
    const glm::dvec3 no(std::cos(a), 0.0, -std::sin(a)), xo = radius * no, toLight(0.0, 0.0, 1.0);
    constexpr int kPolar = 300, kAzimuth = 300;
    const double span = 60.0 / radius;
    glm::dvec3 sum(0.0);
    for (int i = 0; i < kPolar; ++i) {
        const double b = (i + 0.5) / kPolar * span;  // from the x axis
        for (int j = 0; j < kAzimuth; ++j) {
            const double p = (j + 0.5) / kAzimuth * 2.0 * std::numbers::pi;
            const glm::dvec3 ni(std::cos(b), std::sin(b) * std::cos(p), std::sin(b) * std::sin(p));
            const double cosI = ni.z;
            if (cosI <= 0.0) continue;
            const double area = radius * radius * std::sin(b) * (span / kPolar) * (2.0 * std::numbers::pi / kAzimuth);
            sum += fresnelTransmittance(c.eta, cosI) * cosI * area * evaluateSd(c, radius * ni, ni, toLight, xo, no);
        }
    }
    return sum;
}

}  // namespace

TEST_CASE("near field rings: across a sphere's terminator, the light that diffuses past it", "[cpu][near-field]") {
    // Marble, a near field 70 mm wide (the 2 m Buddha's), on a sphere of 100 mm radius lit from
    // the side: the rings against the exact integral over the lit cap, from 4 mm before the
    // terminator to 24 mm (three red diffusion lengths) beyond it. Measured, per channel: 0.74-0.93
    // (the rings ignore that light entering at a grazing angle heads on towards the dark side,
    // 5-10 %, and the rise's curvature). With one tap per ring at its median radius, as before:
    // 0.71 at -4 mm, 0.5 at the terminator, 0.15 at 4 mm and nothing from 8 mm on.
    const DipoleConstants c = constants("marble", ScatteringProfile::Calibrated);
    const detail::NearFieldTable table = detail::tabulateNearField(c, 70.0, 70.0);
    constexpr double kRadius = 100.0;
    for (const double t : {-4.0, 0.0, 4.0, 8.0, 16.0, 24.0}) {
        const glm::dvec3 rings = ringsLit(table, -std::sin(t / kRadius), 1.0 / kRadius);
        const glm::dvec3 exact = sphereBeyondTerminator(c, kRadius, t);
        for (int ch = 0; ch < 3; ++ch) {
            INFO("t " << t << " mm, channel " << ch << ": rings " << rings[ch] << ", exact " << exact[ch]);
            CHECK(rings[ch] / exact[ch] > 0.65);
            CHECK(rings[ch] / exact[ch] < 1.45);
        }
    }
}

TEST_CASE("near field taps: rings in eighths of the profile, then its tail out to the disk's edge", "[cpu][near-field]") {
    // Marble, 70 mm (the 2 m Buddha's near field): the taps' radii increase, each channel's
    // weights sum to 1, and the tail's rings hold what is left beyond 7/8 of the light in halves,
    // so a point in a cast shadow finds a lit surface several diffusion lengths away.
    const DipoleConstants c = constants("marble", ScatteringProfile::Calibrated);
    const detail::NearFieldTable table = detail::tabulateNearField(c, 70.0, 70.0);
    glm::dvec3 sum(0.0);
    for (int k = 0; k < detail::kNearFieldTaps; ++k) {
        sum += glm::dvec3(table.tapWeight[k]);
        if (k > 0) CHECK(table.tapRadius[k] > table.tapRadius[k - 1]);
        CHECK(table.rings[k].outer > table.tapRadius[k]);
    }
    requireClose(sum, glm::dvec3(1.0), 1e-5);
    CHECK(table.rings[detail::kNearFieldTaps - 1].outer == Approx(70.0).epsilon(1e-3));
    // The channels' mean share of the last two rings: 1/128 each, less the step of the bins
    // (0.0056 measured for the last, which holds the rest).
    for (int k : {detail::kNearFieldTaps - 2, detail::kNearFieldTaps - 1}) {
        const glm::vec3 w = table.tapWeight[k];
        CHECK((w.x + w.y + w.z) / 3.0 > 0.6 / 128.0);
        CHECK((w.x + w.y + w.z) / 3.0 < 1.05 / 128.0);
    }
    // The last tap lies more than two diffusion lengths of marble's red (8.5 mm) out (19.9 mm
    // measured; 7.2 mm with eight taps).
    CHECK(table.tapRadius[detail::kNearFieldTaps - 1] > 17.0);
}
