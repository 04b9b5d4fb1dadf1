// The volume path tracer (sss/volume_path_tracer.h): against the reference's Scattering model,
// energy conservation, the slab random walk, single against multiple scattering, determinism.
#include "sss/volume_path_tracer.h"

#include "test_helpers.h"

#include <sss/image_compare.h>
#include <sss/procedural.h>
#include <sss/random_walk.h>
#include <sss/volume_reference.h>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <numbers>
#include <utility>
#include <vector>

using Catch::Contains;
using namespace sss;

namespace {

constexpr double kPi = std::numbers::pi;

Volume uniformVolume(glm::ivec3 dims, uint8_t value) {
    return Volume::fromData(dims, VoxelType::UInt8,
                            std::vector<uint8_t>(static_cast<size_t>(dims.x) * dims.y * dims.z, value));
}

TransferFunction constantTf(glm::vec3 color, float opacity) {
    return TransferFunction({{0.0f, color, opacity}, {1.0f, color, opacity}});
}

Camera orthoFront(float height) {
    Camera camera;  // at (0,0,3) looking along -z
    camera.setProjectionType(Projection::Orthographic);
    camera.setOrthoHeight(height);
    return camera;
}

// Opacity per voxel that gives sigma_t (per model unit) for voxel edge `voxel`.
float opacityFor(double sigmaT, double voxel) { return static_cast<float>(-std::expm1(-sigmaT * voxel)); }
// sigma_t of that (float) opacity, as the renderers compute it.
double sigmaOf(float opacity, double voxel) { return -std::log1p(-static_cast<double>(opacity)) / voxel; }

// Mean of channel c over the pixels with alpha > 0, and its standard error (pixels independent).
struct RegionMean {
    double value = 0, error = 0;
    int pixels = 0;
};
RegionMean regionMean(const VolumePathTracerResult& r, int c) {
    RegionMean m;
    double err2 = 0;
    for (int y = 0; y < r.image.height(); ++y)
        for (int x = 0; x < r.image.width(); ++x) {
            if (!(r.image.at(x, y).a > 0.0f)) continue;
            m.value += r.image.at(x, y)[c];
            err2 += double(r.standardError.at(x, y)[c]) * r.standardError.at(x, y)[c];
            ++m.pixels;
        }
    m.value /= m.pixels;
    m.error = std::sqrt(err2) / m.pixels;
    return m;
}

}  // namespace

TEST_CASE("volume path tracer: single scattering is the reference's Scattering model over 4 pi",
          "[volume-path-tracer][cpu]") {
    // A white TF (albedo 1, chromaticity c = 1), ambient 0, diffuse 1, g = 0: the reference
    // computes integral T sigma_t E l dt, the path tracer the same times p_HG = 1 / (4 pi).
    const Volume volume = makeBlobsVolume(16);
    const glm::vec3 white(1.0f);
    const TransferFunction tf({{0.0f, white, 0.0f}, {0.15f, white, 0.02f}, {1.0f, white, 0.5f}});
    const std::vector<Light> lights{DirectionalLight{{-0.4f, -1.0f, -0.3f}, {1.0f, 0.9f, 0.8f}, 1.5f},
                                    PointLight{{1.0f, 0.6f, 1.4f}, {0.5f, 0.7f, 1.0f}, 3.0f}};
    Camera camera;
    camera.setYaw(30.0f);
    camera.setPitch(20.0f);
    camera.frameTight(volume.worldBounds(), 1.0f, 0.02f);
    const int size = 20;

    VolumeReferenceOptions ro;
    ro.shading = ReferenceShading::Scattering;
    ro.ambient = 0.0;
    ro.diffuse = 1.0;
    ro.threads = 2;
    const ConvergedReference ref =
        renderVolumeReferenceConverged(volume, tf, 256, glm::mat4(1.0f), lights, camera, size, size, ro, 1e-4);
    REQUIRE(ref.converged);

    for (int grid : {16, 1}) {
        VolumePathTracerOptions po;
        po.mode = VolumeScatteringMode::SingleScattering;
        po.g = 0.0;
        po.samplesPerPixel = 2048;
        po.threads = 2;
        po.majorantGridResolution = grid;
        const VolumePathTracerResult pt =
            renderVolumePathTraced(volume, tf, 256, glm::mat4(1.0f), lights, camera, size, size, po);
        INFO("majorant grid " << grid << ", lookups per path " << pt.meanLookupsPerPath);
        CHECK(pt.majorantViolations == 0);
        // Per pixel and channel: z = (4 pi L_pt - L_ref) / (4 pi se). Independent pixels, so
        // max |z| over ~1000 values stays below 4.5 (P ~ 0.7 %), and mean z^2 is ~1 if the
        // standard errors are right (a 2 % bias at the measured ~1 % relative error would
        // double it).
        double z2 = 0.0, maxZ = 0.0, err2 = 0.0, ref2 = 0.0, est2 = 0.0;
        glm::dvec3 sumDiff(0.0), sumVar(0.0);  // per channel, pooled over the pixels
        int n = 0;
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const glm::vec4 r = ref.image.at(x, y), p = pt.image.at(x, y), e = pt.standardError.at(x, y);
                // Coverage: the number of paths that collided is binomial(paths, A_ref) (the
                // reference's discretisation, ~1e-4, is far below its standard deviation).
                const double paths = po.samplesPerPixel, expectedHits = r.a * paths;
                CHECK(std::abs(p.a * paths - expectedHits) <= 4.5 * std::sqrt(expectedHits * (1.0 - r.a)) + 1.0);
                // Where fewer than 20 paths are expected to collide (grazing rays through the
                // blobs' thin fringes), the sample standard error is unreliable (often 0): only
                // the coverage is checked there.
                if (expectedHits < 20.0) continue;
                for (int c = 0; c < 3; ++c) {
                    const double diff = 4.0 * kPi * p[c] - r[c];
                    err2 += diff * diff;
                    ref2 += double(r[c]) * r[c];
                    est2 += 16.0 * kPi * kPi * double(e[c]) * e[c];
                    REQUIRE(e[c] > 0.0f);
                    sumDiff[c] += diff;
                    sumVar[c] += 16.0 * kPi * kPi * double(e[c]) * e[c];
                    const double z = diff / (4.0 * kPi * e[c]);
                    z2 += z * z;
                    maxZ = std::max(maxZ, std::abs(z));
                    ++n;
                }
            }
        const double relRmse = std::sqrt(err2 / ref2);
        INFO("pixels " << n << ", mean z^2 " << z2 / n << ", max |z| " << maxZ << ", relRmse " << relRmse
                       << ", estimate " << pt.relativeRmseEstimate);
        CHECK(n > 250);
        CHECK(maxZ < 4.5);
        // The three channels of a pixel share paths, so mean z^2 scatters more than for n
        // independent values: measured 0.82 to 1.44 over 7 seeds.
        CHECK(z2 / n > 0.6);
        CHECK(z2 / n < 1.7);
        // Pooled over the pixels (independent), per channel: a bias of 1 % is ~4 standard errors.
        for (int c = 0; c < 3; ++c) {
            INFO("channel " << c << ": pooled z " << sumDiff[c] / std::sqrt(sumVar[c]));
            CHECK(std::abs(sumDiff[c]) < 4.0 * std::sqrt(sumVar[c]));
        }
        // The image's relRmse against the reference is what the standard errors predict
        // (relRmse 0.022 to 0.032 over 8 seeds, within 0.85 to 1.2 of the prediction).
        CHECK(relRmse < 1.4 * std::sqrt(est2 / ref2));
        CHECK(pt.relativeRmseEstimate < 0.04);
    }
}

TEST_CASE("volume path tracer: single scattering is the reference's physical model (VolumeModel::Physical)",
          "[volume-path-tracer][cpu]") {
    // The physical model (TF colour as albedo, Henyey-Greenstein phase, grey extinction, no
    // ambient, no chromaticity) is exactly what the path tracer's single-scattering mode
    // estimates: no factor between them. Coloured blobs, g = 0.5 and -0.3, a directional light.
    // Pooled per channel over the pixels, the difference must stay within 4 standard errors,
    // and the image's relRmse within 1.4x what the path tracer's standard errors predict.
    const Volume volume = makeBlobsVolume(16);
    const TransferFunction tf({{0.0f, {0.9f, 0.6f, 0.3f}, 0.0f}, {0.3f, {0.9f, 0.6f, 0.3f}, 0.0f},
                               {0.6f, {0.4f, 0.8f, 0.9f}, 0.5f}, {1.0f, {0.8f, 0.8f, 0.5f}, 0.8f}});
    const std::vector<Light> lights{DirectionalLight{.direction = {-0.6f, -0.8f, -0.3f}, .intensity = 3.0f}};
    Camera camera;
    camera.setYaw(30.0f);
    camera.setPitch(20.0f);
    camera.frameTight(volume.worldBounds(), 1.0f, 0.02f);
    const int size = 20;
    // Both fields: the cubic B-spline's majorants must bound it as the trilinear ones do.
    for (const auto& [g, reconstruction] : {std::pair{0.5, VolumeReconstruction::Trilinear},
                                            std::pair{-0.3, VolumeReconstruction::Trilinear},
                                            std::pair{0.5, VolumeReconstruction::CubicBSpline}}) {
        VolumeReferenceOptions ro;
        ro.reconstruction = reconstruction;
        ro.shading = ReferenceShading::Scattering;
        ro.model = VolumeModel::Physical;
        ro.anisotropy = g;
        ro.threads = 2;
        // Fine steps: the quadrature error (about 1e-4 relative) is far below the path tracer's.
        ro.stepVoxels = 1.0 / 32.0;
        ro.shadowStepVoxels = 1.0 / 16.0;
        const Image reference = renderVolumeReference(volume, tf, 256, glm::mat4(1.0f), lights, camera, size, size, ro);
        VolumePathTracerOptions po;
        po.mode = VolumeScatteringMode::SingleScattering;
        po.g = g;
        po.samplesPerPixel = 1024;
        po.threads = 2;
        po.reconstruction = reconstruction;
        const VolumePathTracerResult pt =
            renderVolumePathTraced(volume, tf, 256, glm::mat4(1.0f), lights, camera, size, size, po);
        CHECK(pt.majorantViolations == 0);
        double err2 = 0.0, ref2 = 0.0, est2 = 0.0;
        glm::dvec3 sumDiff(0.0), sumVar(0.0);
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const glm::vec4 r = reference.at(x, y), p = pt.image.at(x, y), e = pt.standardError.at(x, y);
                if (double(r.a) * po.samplesPerPixel < 20.0) continue;  // too few collisions for a standard error
                for (int c = 0; c < 3; ++c) {
                    const double diff = double(p[c]) - r[c];
                    err2 += diff * diff;
                    ref2 += double(r[c]) * r[c];
                    est2 += double(e[c]) * e[c];
                    sumDiff[c] += diff;
                    sumVar[c] += double(e[c]) * e[c];
                }
            }
        const double relRmse = std::sqrt(err2 / ref2), predicted = std::sqrt(est2 / ref2);
        INFO("g " << g << (reconstruction == VolumeReconstruction::CubicBSpline ? " cubic" : " trilinear") << ": relRmse "
                  << relRmse << ", predicted by the standard errors " << predicted);
        REQUIRE(ref2 > 0.0);
        CHECK(relRmse < 1.4 * predicted);
        for (int c = 0; c < 3; ++c) {
            INFO("channel " << c << ": pooled z " << sumDiff[c] / std::sqrt(sumVar[c]));
            CHECK(std::abs(sumDiff[c]) < 4.0 * std::sqrt(sumVar[c]));
        }
    }
}

TEST_CASE("volume path tracer: an albedo-1 cube scatters out all the power it takes from the beam",
          "[volume-path-tracer][cpu]") {
    // A unit cube, sigma_t = 2, albedo 1, g = 0.5, lit along -z (model) with E = 1: the beam
    // loses 1 - exp(-2) of its power (face area 1) to scattering, and all of it must leave.
    // What leaves is measured as the intensity I(w) = integral of L over an orthographic image
    // (jittered pixels: the pixel-area average, so the image sum is unbiased), integrated over
    // the sphere of directions w: 64 equal-area strata (8 in w.z, 8 in azimuth), one random w
    // each, in 16 independent replicates; the standard error is that of the replicate means.
    // The cube is turned by the model matrix so that w points at the camera.
    const int n = 8;
    const double voxel = 1.0 / n;
    const float opacity = opacityFor(2.0, voxel);
    const double sigma = sigmaOf(opacity, voxel);
    const Volume volume = uniformVolume({n, n, n}, 255);
    const TransferFunction tf = constantTf(glm::vec3(1.0f), opacity);
    const double expected = -std::expm1(-sigma);

    const float viewSize = 1.8f;  // > sqrt(3): the cube fits from any side
    const Camera camera = orthoFront(viewSize);
    const int pixels = 16;
    const double pixelArea = double(viewSize) / pixels * double(viewSize) / pixels;

    // Splitmix64: the test's own directions, independent of the renderer's streams.
    std::uint64_t state = 0x1234567ull;
    auto uniform = [&] {
        std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return double((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
    };
    std::uint64_t seed = 1;
    // Power leaving after scattering, one replicate: (4 pi / 64) sum of I(w_k).
    constexpr int kStrata = 8;
    auto leavingPower = [&](VolumeScatteringMode mode) {
        double sum = 0.0;
        for (int i = 0; i < kStrata; ++i)
            for (int j = 0; j < kStrata; ++j) {
                const double z = -1.0 + (i + uniform()) * 2.0 / kStrata, phi = (j + uniform()) * 2.0 * kPi / kStrata;
                const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
                const glm::dvec3 w(s * std::cos(phi), s * std::sin(phi), z);
                const glm::dvec3 helper = std::abs(w.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
                const glm::dvec3 u = glm::normalize(glm::cross(helper, w)), v = glm::cross(w, u);
                // Rows u, v, w: takes w to +z, towards the camera.
                const glm::mat3 rotation(glm::transpose(glm::dmat3(u, v, w)));
                const std::vector<Light> lights{DirectionalLight{rotation * glm::vec3(0, 0, -1), glm::vec3(1.0f), 1.0f}};
                VolumePathTracerOptions o;
                o.mode = mode;
                o.samplesPerPixel = 8;
                o.jitterPixels = true;
                o.seed = seed++;
                o.threads = 2;
                const VolumePathTracerResult r =
                    renderVolumePathTraced(volume, tf, 256, glm::mat4(rotation), lights, camera, pixels, pixels, o);
                for (int y = 0; y < pixels; ++y)
                    for (int x = 0; x < pixels; ++x) sum += r.image.at(x, y).r * pixelArea;
            }
        return 4.0 * kPi / (kStrata * kStrata) * sum;
    };
    const int replicates = 16;
    double mean = 0.0, mean2 = 0.0;
    for (int k = 0; k < replicates; ++k) {
        const double p = leavingPower(VolumeScatteringMode::MultipleScattering);
        mean += p / replicates;
        mean2 += p * p / replicates;
    }
    const double se = std::sqrt(std::max(0.0, mean2 - mean * mean) / (replicates - 1));
    const double single = leavingPower(VolumeScatteringMode::SingleScattering);
    INFO("scattered out " << mean << " +- " << se << ", taken from the beam " << expected << ", single scattering only "
                          << single);
    // Measured 0.8685 +- 0.0044 against 0.8647 (0.9 standard errors).
    // 16 replicates: the t statistic has 15 degrees of freedom, P(|t| > 4.5) ~ 0.04 %.
    CHECK(std::abs(mean - expected) < 4.5 * se);
    CHECK(se < 0.02 * expected);  // measured 0.5 %: the check sees a bias of a few per cent
    // Single scattering alone is far short (so the test sees missing orders).
    CHECK(single < 0.8 * expected);
}

TEST_CASE("volume path tracer: a thick uniform slab matches the slab random walk at eta = 1",
          "[volume-path-tracer][cpu]") {
    // A 64 x 64 x 16 box (1 x 1 x 0.25 model units), sigma_t = 100: 100 mean free paths wide,
    // 25 thick (with albedo <= 0.95 the diffuse light decays by e^-9.7 through it), lit straight
    // down on its top face with E = 1, isotropic, RGB albedo (0.95, 0.8, 0.5) from the TF colour
    // with grey extinction: one path with RGB throughput. An orthographic camera looks straight
    // down at the middle 0.1 x 0.1 (10 mean free paths, 45 from the sides): the radiance leaving
    // along the normal, per unit irradiance, which simulateSlab() estimates in a 5 degree cone.
    // The cone average differs from the normal value by the exact half-space's
    // |L(cone 5) - L(cone 0.5)| (~0.1 %), added to the tolerance.
    const glm::ivec3 dims(64, 64, 16);
    const double voxel = 1.0 / 64.0;
    const float opacity = opacityFor(100.0, voxel);
    const double sigma = sigmaOf(opacity, voxel);
    const glm::vec3 albedo(0.95f, 0.8f, 0.5f);
    const Volume volume = uniformVolume(dims, 255);
    const TransferFunction tf = constantTf(albedo, opacity);
    const std::vector<Light> lights{DirectionalLight{{0.0f, 0.0f, -1.0f}, glm::vec3(1.0f), 1.0f}};
    VolumePathTracerOptions po;
    po.g = 0.0;
    po.samplesPerPixel = 1024;
    po.threads = 2;
    const VolumePathTracerResult pt =
        renderVolumePathTraced(volume, tf, 256, glm::mat4(1.0f), lights, orthoFront(0.1f), 8, 8, po);
    REQUIRE(pt.coveredPixels == 64);
    // Single scattering has a closed form here: L_1 = a / (4 pi) * integral of sigma_t
    // exp(-2 sigma_t z) dz = a / (8 pi) (measured within 0.02 % at a relative error of 0.2 %).
    po.mode = VolumeScatteringMode::SingleScattering;
    const VolumePathTracerResult single =
        renderVolumePathTraced(volume, tf, 256, glm::mat4(1.0f), lights, orthoFront(0.1f), 8, 8, po);
    for (int c = 0; c < 3; ++c) {
        const RegionMean m = regionMean(single, c);
        INFO("channel " << c << ": single scattering " << m.value << " +- " << m.error);
        CHECK(std::abs(m.value - albedo[c] / (8.0 * kPi)) < 4.0 * m.error);
        CHECK(m.error < 0.005 * m.value);
    }
    CHECK(pt.majorantViolations == 0);
    CHECK(pt.truncatedPaths == 0);

    ScatteringMaterial material;
    material.eta = 1.0;
    material.g = 0.0;
    for (int c = 0; c < 3; ++c) {
        material.sigmaS[c] = double(albedo[c]) * sigma;
        material.sigmaA[c] = (1.0 - double(albedo[c])) * sigma;
    }
    SlabRandomWalkOptions so;
    so.paths = 2'000'000;
    so.threads = 2;
    const SlabRandomWalkResult slab = simulateSlab(material, 0.0, so);
    for (int c = 0; c < 3; ++c) {
        const RegionMean m = regionMean(pt, c);
        const Estimate walk = slab.channels[c].coneRadiance;
        const double a = double(albedo[c]);
        const double cone = isotropicHalfSpaceReflectance(a, 1.0, 0.0, 5.0).coneRadiance;
        const double normal = isotropicHalfSpaceReflectance(a, 1.0, 0.0, 0.5).coneRadiance;
        INFO("channel " << c << ": path tracer " << m.value << " +- " << m.error << ", slab walk " << walk.value
                        << " +- " << walk.standardError << ", exact at the normal " << normal);
        CHECK(std::abs(m.value - walk.value) <
              4.0 * std::hypot(m.error, walk.standardError) + std::abs(cone - normal));
        // And against the exact half-space value directly (path tracer's error only).
        CHECK(std::abs(m.value - normal) < 4.0 * m.error);
        CHECK(m.error < 0.01 * m.value);  // measured 0.2 % (R) to 0.3 % (B)
    }
}

TEST_CASE("volume path tracer: multiple scattering adds to single scattering, and vanishes with the albedo",
          "[volume-path-tracer][cpu]") {
    const Volume volume = makeBlobsVolume(16);
    const std::vector<Light> lights{DirectionalLight{{0.3f, -1.0f, -0.5f}, glm::vec3(1.0f), 2.0f}};
    Camera camera;
    camera.setYaw(-25.0f);
    camera.setPitch(15.0f);
    camera.frameTight(volume.worldBounds(), 1.0f, 0.02f);
    const int size = 16;
    auto render = [&](glm::vec3 color, VolumeScatteringMode mode, std::uint64_t seed) {
        const TransferFunction tf({{0.0f, color, 0.0f}, {0.15f, color, 0.05f}, {1.0f, color, 0.8f}});
        VolumePathTracerOptions o;
        o.mode = mode;
        o.seed = seed;
        o.samplesPerPixel = 128;
        o.threads = 2;
        return renderVolumePathTraced(volume, tf, 256, glm::mat4(1.0f), lights, camera, size, size, o);
    };
    const glm::vec3 color(0.9f, 0.6f, 0.3f);
    const auto single = render(color, VolumeScatteringMode::SingleScattering, 1);
    const auto multiple = render(color, VolumeScatteringMode::MultipleScattering, 1);
    const auto other = render(color, VolumeScatteringMode::MultipleScattering, 2);
    double sumSingle = 0, sumMultiple = 0;
    int below = 0, n = 0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            for (int c = 0; c < 3; ++c) {
                const double s = single.image.at(x, y)[c], m = multiple.image.at(x, y)[c];
                // Same seed: the single image is exactly the first-collision part of the
                // multiple one, so it can never be larger.
                REQUIRE(m >= s);
                sumSingle += s;
                sumMultiple += m;
                // Different seeds: within noise (4 combined standard errors).
                const double se = std::hypot(single.standardError.at(x, y)[c], other.standardError.at(x, y)[c]);
                if (other.image.at(x, y)[c] < s - 4.0 * se) ++below;
                if (se > 0.0) ++n;
            }
    CHECK(n > 200);
    CHECK(below == 0);
    INFO("multiple / single " << sumMultiple / sumSingle);
    CHECK(sumMultiple > 1.2 * sumSingle);  // measured 1.5: higher orders matter at these albedos
    // Single-scattering radiance is linear in the albedo (grey extinction): exactly the channel
    // ratio, with the same random numbers.
    const glm::vec4 p = single.image.at(size / 2, size / 2);
    REQUIRE(p.r > 0.0f);
    CHECK(p.g / p.r == Approx(0.6 / 0.9).epsilon(1e-5));
    CHECK(p.b / p.r == Approx(0.3 / 0.9).epsilon(1e-5));

    // Albedo 0.01: orders >= 2 carry a fraction O(albedo) of the light.
    const auto singleDark = render(glm::vec3(0.01f), VolumeScatteringMode::SingleScattering, 1);
    const auto multipleDark = render(glm::vec3(0.01f), VolumeScatteringMode::MultipleScattering, 1);
    double s = 0, m = 0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) s += singleDark.image.at(x, y).r, m += multipleDark.image.at(x, y).r;
    INFO("albedo 0.01: multiple / single " << m / s);
    CHECK(s > 0.0);
    CHECK(m >= s);
    CHECK(m < 1.02 * s);  // measured 1.007
}

TEST_CASE("volume path tracer: the image depends on the seed, not on the threads", "[volume-path-tracer][cpu]") {
    const Volume volume = makeBlobsVolume(12);
    const TransferFunction tf({{0.0f, {1, 1, 1}, 0.0f}, {1.0f, {0.8f, 0.5f, 0.3f}, 0.7f}});
    const std::vector<Light> lights{DirectionalLight{}, PointLight{}};
    Camera camera;
    camera.setYaw(40.0f);
    VolumePathTracerOptions o;
    o.samplesPerPixel = 8;
    o.background = {0.1, 0.2, 0.3, 1.0};
    for (bool jitter : {false, true}) {
        o.jitterPixels = jitter;
        o.threads = 1;
        const auto a = renderVolumePathTraced(volume, tf, 256, glm::mat4(1.0f), lights, camera, 12, 10, o);
        o.threads = 2;
        const auto b = renderVolumePathTraced(volume, tf, 256, glm::mat4(1.0f), lights, camera, 12, 10, o);
        o.threads = 5;
        const auto c = renderVolumePathTraced(volume, tf, 256, glm::mat4(1.0f), lights, camera, 12, 10, o);
        CHECK(a.image.data() == b.image.data());
        CHECK(a.image.data() == c.image.data());
        CHECK(a.standardError.data() == c.standardError.data());
        CHECK(a.meanLookupsPerPath == c.meanLookupsPerPath);
        o.seed = 2;
        const auto d = renderVolumePathTraced(volume, tf, 256, glm::mat4(1.0f), lights, camera, 12, 10, o);
        o.seed = 1;
        CHECK(a.image.data() != d.image.data());
        if (!jitter) {
            // Pixels whose centre ray misses the box are the background exactly, without paths.
            CHECK(a.image.at(0, 0) == glm::vec4(0.1f, 0.2f, 0.3f, 1.0f));
            CHECK(a.coveredPixels < 120);
            CHECK(a.paths == std::int64_t(a.coveredPixels) * 8);
        }
    }
}

TEST_CASE("volume path tracer: bad input is rejected with a message naming it", "[volume-path-tracer][cpu]") {
    const Volume volume = makeBlobsVolume(4);
    const TransferFunction tf;
    const Camera camera;
    auto render = [&](const VolumePathTracerOptions& o) {
        return renderVolumePathTraced(volume, tf, 256, glm::mat4(1.0f), {}, camera, 4, 4, o);
    };
    auto expectField = [&](VolumePathTracerOptions o, const char* field) {
        INFO(field);
        REQUIRE_SSS_ERROR(render(o), ErrorKind::InvalidArgument, Contains(field));
    };
    VolumePathTracerOptions o;
    o.samplesPerPixel = 0;
    expectField(o, "VolumePathTracerOptions::samplesPerPixel");
    o = {};
    o.threads = -1;
    expectField(o, "VolumePathTracerOptions::threads");
    o = {};
    o.g = 1.0;
    expectField(o, "VolumePathTracerOptions::g");
    o = {};
    o.g = std::nan("");
    expectField(o, "VolumePathTracerOptions::g");
    o = {};
    o.maxBounces = 0;
    expectField(o, "VolumePathTracerOptions::maxBounces");
    o = {};
    o.rouletteStartBounce = -1;
    expectField(o, "VolumePathTracerOptions::rouletteStartBounce");
    o = {};
    o.majorantGridResolution = 0;
    expectField(o, "VolumePathTracerOptions::majorantGridResolution");
    o = {};
    o.background.y = INFINITY;
    expectField(o, "VolumePathTracerOptions::background");
    o = {};
    o.mode = static_cast<VolumeScatteringMode>(7);
    expectField(o, "VolumePathTracerOptions::mode");
    REQUIRE_SSS_ERROR(renderVolumePathTraced(volume, tf, 1, glm::mat4(1.0f), {}, camera, 4, 4),
                      ErrorKind::InvalidArgument, Contains("tfEntries"));
    REQUIRE_SSS_ERROR(renderVolumePathTraced(volume, tf, 256, glm::mat4(0.0f), {}, camera, 4, 4),
                      ErrorKind::InvalidArgument, Contains("model matrix"));
    REQUIRE_SSS_ERROR(renderVolumePathTraced(volume, tf, 256, glm::mat4(1.0f), {}, camera, 0, 4),
                      ErrorKind::InvalidArgument, Contains("width and height"));
    DirectionalLight bad;
    bad.direction = glm::vec3(0.0f);
    REQUIRE_SSS_ERROR(renderVolumePathTraced(volume, tf, 256, glm::mat4(1.0f), {bad}, camera, 4, 4),
                      ErrorKind::InvalidArgument, Contains("light 0"));
    // No lights: black, but the coverage is still estimated.
    const auto dark = renderVolumePathTraced(makeBlobsVolume(8), constantTf(glm::vec3(1.0f), 0.5f), 256,
                                             glm::mat4(1.0f), {}, camera, 8, 8);
    CHECK(dark.image.at(4, 4).r == 0.0f);
    CHECK(dark.image.at(4, 4).a > 0.9f);
}

TEST_CASE("volume path tracer: report of the cost on a bucky-like volume", "[.][volume-path-tracer-report]") {
    const Volume volume = makeBuckyLikeVolume(32);
    const TransferFunction tf = TransferFunction::preset("bucky");
    const std::vector<Light> lights{DirectionalLight{{-0.5f, -1.0f, -0.6f}, glm::vec3(1.0f), 2.0f}};
    Camera camera;
    camera.setYaw(25.0f);
    camera.setPitch(15.0f);
    const int width = 80, height = 45;
    camera.frameTight(volume.worldBounds(), float(width) / float(height));
    for (auto mode : {VolumeScatteringMode::SingleScattering, VolumeScatteringMode::MultipleScattering})
        for (int grid : {1, 4, 16, 32}) {
            VolumePathTracerOptions o;
            o.mode = mode;
            o.samplesPerPixel = 64;
            o.majorantGridResolution = grid;
            const auto start = std::chrono::steady_clock::now();
            const auto r = renderVolumePathTraced(volume, tf, 256, glm::mat4(1.0f), lights, camera, width, height, o);
            const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            std::cout << (mode == VolumeScatteringMode::SingleScattering ? "single  " : "multiple") << " grid "
                      << grid << ": " << seconds << " s, " << r.paths << " paths (" << r.coveredPixels
                      << " covered pixels x " << o.samplesPerPixel << "), " << double(r.paths) / seconds / 1e6
                      << " M paths/s, relative standard error " << r.relativeRmseEstimate << ", collisions/path "
                      << r.meanCollisionsPerPath << ", lookups/path " << r.meanLookupsPerPath
                      << "; for 1 % relative error: "
                      << seconds * (r.relativeRmseEstimate / 0.01) * (r.relativeRmseEstimate / 0.01) << " s\n";
        }
}

TEST_CASE("the CPU path tracer and reference cut clipped matter out of the light unless it casts shadows",
          "[volume][path-tracer][clip]") {
    // A lit block (x in [2, 6)) behind a wall (x in [12, 14)) on the light's side; the plane keeps
    // data x <= 0.6, so the wall is cut and, by default, no longer shadows the block.
    const auto blockAndWall = [](bool wall) {
        std::vector<uint8_t> bytes(16 * 16 * 16, 0);
        for (int z = 3; z < 13; ++z)
            for (int y = 3; y < 13; ++y)
                for (int x = 0; x < 16; ++x)
                    if ((x >= 2 && x < 6) || (wall && x >= 12 && x < 14)) bytes[static_cast<size_t>((z * 16 + y) * 16 + x)] = 255;
        return Volume::fromData({16, 16, 16}, VoxelType::UInt8, std::move(bytes));
    };
    const TransferFunction dense({{0.0f, glm::vec3(0.9f), 0.0f}, {0.5f, glm::vec3(0.9f), 0.5f}, {1.0f, glm::vec3(0.9f), 0.9f}});
    const std::vector<Light> lights{DirectionalLight{.direction = {-1.0f, 0.0f, 0.0f}, .intensity = 10.0f}};
    Camera camera;
    camera.frame(blockAndWall(true).worldBounds());
    VolumeClip cut;
    cut.planes = {{{0.1f, 0.0f, 0.0f}, {-1.0f, 0.0f, 0.0f}}};
    VolumeClip shadowing = cut;
    shadowing.clippedMatterCastsShadows = true;
    const auto mean = [&](bool wall, const VolumeClip& clip) {
        VolumePathTracerOptions o;
        o.samplesPerPixel = 64;
        o.mode = VolumeScatteringMode::SingleScattering;
        o.clip = clip;
        const Image image = renderVolumePathTraced(blockAndWall(wall), dense, 256, glm::mat4(1.0f), lights, camera, 24, 18, o).image;
        double sum = 0.0;
        for (int y = 0; y < image.height(); ++y)
            for (int x = 0; x < image.width(); ++x) sum += image.at(x, y).r;
        return sum;
    };
    const double clipped = mean(true, cut), noWall = mean(false, {}), shadowed = mean(true, shadowing);
    INFO("block light: clipped " << clipped << ", no wall " << noWall << ", shadowed " << shadowed);
    CHECK(noWall > 0.0);
    CHECK(std::abs(clipped - noWall) <= 0.03 * noWall);
    CHECK(shadowed < 0.5 * clipped);

    VolumePathTracerOptions bad;
    bad.clip.planes.resize(7);
    REQUIRE_THROWS_WITH(renderVolumePathTraced(blockAndWall(true), dense, 256, glm::mat4(1.0f), lights, camera, 8, 8, bad),
                        Contains("VolumePathTracerOptions::clip: VolumeClip::planes holds at most 6 planes, got 7"));
    VolumeReferenceOptions badReference;
    badReference.clip.cropMin = glm::vec3(2.0f);
    REQUIRE_THROWS_WITH(VolumeReference(blockAndWall(true), dense, 256, glm::mat4(1.0f), lights, badReference),
                        Contains("VolumeReferenceOptions::clip: VolumeClip::cropMin must be below cropMax"));
}
