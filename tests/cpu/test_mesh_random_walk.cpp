// The random walk inside a triangle mesh (renderMeshRandomWalk, sss/random_walk.h) against exact
// results. A box 40 mean free paths wide and 20 deep, seen head-on in its middle, is a half-space
// for the light that comes back: its pixels must give the exact radiance of
// isotropicHalfSpaceReflectance() (the H-function and the adding method) and the closed-form
// single scattering, for normal and oblique, directional and point light, eta = 1 and 1.3; with
// Henyey-Greenstein scattering, where no exact total exists, simulateSlab()'s. Bounds are 4
// combined standard errors (the renders are seeded, so a pass is reproducible; the bound only has
// to survive a change of the random streams); measured standard errors are about 0.3 % of the
// value for the box, and each check resolves a change of the albedo by 0.01. Plus thread-count
// independence, the distance grid changing nothing, transmission through thin and thick slabs,
// and input validation.
#include "cpu/test_helpers.h"

#include <catch2/catch.hpp>
#include <sss/materials.h>
#include <sss/procedural.h>
#include <sss/random_walk.h>

#include <glm/gtc/matrix_transform.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

using namespace sss;
using Catch::Matchers::Contains;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kSigmas = 4.0;  // bound on |walk - exact| in combined standard errors

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

// The box scene: makeSlab 1 x 1 x `depth` units at 40 mm per unit (40 x 40 x 40 depth mean free
// paths for sigma_t = 1 mm^-1), top face z = depth / 2 facing the orthographic camera on +z; its
// 4 x 4 pixels cover the middle 4 x 4 mm, where the sides are 18 mean free paths away.
constexpr double kMillimetresPerUnit = 40.0;

Camera headOnCamera() {
    Camera camera;  // at (0, 0, 3) looking along -z
    camera.setProjectionType(Projection::Orthographic);
    camera.setOrthoHeight(0.1f);
    return camera;
}

MeshRandomWalkResult renderBox(const ScatteringMaterial& material, const Light& light, int paths, uint64_t seed,
                               float depth = 0.5f) {
    MeshRandomWalkOptions options;
    options.pathsPerPixel = paths;
    options.seed = seed;
    options.millimetresPerUnit = kMillimetresPerUnit;
    return renderMeshRandomWalk(makeSlab({1.0f, 1.0f, depth}), glm::mat4(1.0f), material, {light}, headOnCamera(), 4,
                                4, options);
}

// Mean over all pixels of one channel and its standard error (the pixels are independent).
struct PixelMean {
    double value = 0.0;
    double standardError = 0.0;
};
PixelMean meanOf(const Image& image, const Image& standardError, int channel) {
    double sum = 0.0, variance = 0.0;
    const int n = image.width() * image.height();
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            sum += image.at(x, y)[channel];
            variance += std::pow(double(standardError.at(x, y)[channel]), 2);
        }
    return {sum / n, std::sqrt(variance) / n};
}

void checkAgainst(const PixelMean& walk, double exact, double otherStandardError, double maxRelativeError,
                  const std::string& what) {
    const double se = std::hypot(walk.standardError, otherStandardError);
    INFO(what << ": walk " << walk.value << " +- " << walk.standardError << ", reference " << exact << " +- "
              << otherStandardError << ", " << (walk.value - exact) / se << " standard errors");
    CHECK(walk.standardError > 0.0);
    CHECK(walk.standardError <= maxRelativeError * exact);
    CHECK(std::abs(walk.value - exact) <= kSigmas * se);
}

// Single scattering of the half-space seen along the normal, per unit irradiance normal to a
// beam at incidence theta_i: albedo p(-mu_i') T_i T_o cos(theta_i) / (eta^2 (mu_i' + 1)), mu_i'
// the refracted beam's cosine inside (the beam enters at depth z with exp(-sigma_t z / mu_i'),
// the view ray goes straight down; integrating the product over depth gives 1 / (mu_i' + 1)).
double exactSingle(double albedo, double eta, double g, double incidenceDeg) {
    const double theta = incidenceDeg * kPi / 180.0;
    const double sinIn = std::sin(theta) / eta;
    const double muIn = std::sqrt(1.0 - sinIn * sinIn);
    const double hg = (1.0 - g * g) / (4.0 * kPi * std::pow(1.0 + g * g + 2.0 * g * muIn, 1.5));  // cos = -mu_i'
    return albedo * hg * fresnelTransmittance(eta, std::cos(theta)) * fresnelTransmittance(eta, 1.0) * std::cos(theta) /
           (eta * eta * (muIn + 1.0));
}

DirectionalLight beamAt(double incidenceDeg) {
    const double theta = incidenceDeg * kPi / 180.0;
    DirectionalLight light;
    light.direction = glm::vec3(float(std::sin(theta)), 0.0f, float(-std::cos(theta)));
    return light;
}

bool sameImage(const Image& a, const Image& b) { return a.data() == b.data(); }

}  // namespace

TEST_CASE("mesh random walk: a large box seen head-on gives the exact half-space radiance",
          "[mesh-random-walk][cpu]") {
    // Albedos 0.5, 0.8, 0.9 (mean 7 to 9 scattering events); 5000 paths per pixel and channel,
    // 80000 per channel over the 16 pixels: measured standard errors 0.25 to 0.45 % of the value.
    const struct {
        double eta, incidence;
        bool point;
    } cases[] = {{1.3, 0.0, false}, {1.3, 45.0, false}, {1.0, 0.0, false}, {1.0, 45.0, false}, {1.3, 30.0, true}};
    uint64_t seed = 1;
    for (const auto& k : cases) {
        const ScatteringMaterial material = withAlbedos(0.5, 0.8, 0.9, k.eta);
        Light light = beamAt(k.incidence);
        if (k.point) {
            // A point light 30 units away in the beam's direction, as bright at the box's middle
            // as the unit beam: over the few mm that matter its direction and falloff change by
            // less than 1e-4.
            const double theta = k.incidence * kPi / 180.0;
            const double distance = 30.0;
            PointLight point;
            point.position = glm::vec3(float(-distance * std::sin(theta)), 0.0f, float(0.25 + distance * std::cos(theta)));
            point.intensity = float(distance * distance);
            light = point;
        }
        const MeshRandomWalkResult walk = renderBox(material, light, 5000, seed++);
        INFO("eta " << k.eta << ", incidence " << k.incidence << (k.point ? ", point light" : ", directional light"));
        CHECK(walk.coveredPixels == 16);
        CHECK(walk.truncatedPaths == 0);
        CHECK(walk.escapedPaths == 0);
        const double cosI = std::cos(k.incidence * kPi / 180.0);
        for (int c = 0; c < 3; ++c) {
            const double albedo = material.sigmaS[c];
            INFO("albedo " << albedo);
            // Radiance along the normal: the exact cone radiance of a 0.5 degree cone (within
            // 1e-5 of the normal's), per unit irradiance on the surface = cos(theta_i) per unit
            // irradiance normal to the beam.
            const double exact = cosI * isotropicHalfSpaceReflectance(albedo, k.eta, k.incidence, 0.5).coneRadiance;
            const PixelMean total = meanOf(walk.image, walk.standardError, c);
            checkAgainst(total, exact, 0.0, 0.006, "total radiance");
            // It resolves the albedo: +-0.01 moves the exact value by more than 4 standard errors.
            for (double other : {albedo - 0.01, albedo + 0.01})
                CHECK(std::abs(cosI * isotropicHalfSpaceReflectance(other, k.eta, k.incidence, 0.5).coneRadiance -
                               total.value) > kSigmas * total.standardError);
            const PixelMean single = meanOf(walk.singleScattering, walk.singleStandardError, c);
            checkAgainst(single, exactSingle(albedo, k.eta, 0.0, k.incidence), 0.0, 0.006, "single scattering");
        }
    }
}

TEST_CASE("mesh random walk: Henyey-Greenstein scattering in the box matches the slab walk", "[mesh-random-walk][cpu]") {
    // No exact total exists for g != 0: simulateSlab's radiance within 10 degrees of the normal
    // is the reference (its cone average differs from the normal's value by 0.13 to 0.3 % for
    // isotropic scattering, well inside its standard error of 0.8 to 1.5 %; the walk's is 0.5 to
    // 0.9 %). Single scattering is exact.
    for (double g : {0.6, -0.3}) {
        const ScatteringMaterial material = withAlbedos(0.8, 0.9, 0.95, 1.4, g);
        const MeshRandomWalkResult walk = renderBox(material, beamAt(20.0), 2000, 40);
        SlabRandomWalkOptions slabOptions;
        slabOptions.paths = 2'000'000;
        slabOptions.coneHalfAngleDeg = 10.0;
        slabOptions.seed = 41;
        const SlabRandomWalkResult slab = simulateSlab(material, 20.0, slabOptions);
        const double cosI = std::cos(20.0 * kPi / 180.0);
        for (int c = 0; c < 3; ++c) {
            INFO("g " << g << ", albedo " << material.sigmaS[c]);
            const Estimate& cone = slab.channels[c].coneRadiance;
            CHECK(cone.standardError <= 0.02 * cone.value);
            checkAgainst(meanOf(walk.image, walk.standardError, c), cosI * cone.value, cosI * cone.standardError, 0.01,
                         "total radiance");
            checkAgainst(meanOf(walk.singleScattering, walk.singleStandardError, c),
                         exactSingle(material.sigmaS[c], material.eta, g, 20.0), 0.0, 0.01, "single scattering");
        }
    }
}

TEST_CASE("mesh random walk: the image depends on the seed, not on the threads or the distance grid",
          "[mesh-random-walk][cpu]") {
    const Mesh sphere = makeUvSphere(16, 12, 0.5f);
    ScatteringMaterial material = withAlbedos(0.7, 0.9, 0.97, 1.3, 0.4);
    Camera camera;
    camera.setDistance(2.0f);
    camera.setYaw(20.0f);
    DirectionalLight sun;
    sun.direction = {0.5f, -0.3f, -1.0f};
    PointLight lamp;
    lamp.position = {-1.0f, 1.0f, 1.5f};
    lamp.color = {1.0f, 0.5f, 0.2f};
    const std::vector<Light> lights{sun, lamp};
    MeshRandomWalkOptions options;
    options.pathsPerPixel = 24;
    options.millimetresPerUnit = 10.0;  // radius 5 mean free paths
    auto render = [&](int threads, uint64_t seed, int gridCells = 1 << 20, bool roulette = true) {
        MeshRandomWalkOptions o = options;
        o.threads = threads;
        o.seed = seed;
        o.distanceGridCells = gridCells;
        o.neeRoulette = roulette;
        return renderMeshRandomWalk(sphere, glm::rotate(glm::mat4(1.0f), 0.3f, glm::vec3(0, 1, 0)), material, lights,
                                    camera, 12, 10, o);
    };
    auto sameImages = [](const MeshRandomWalkResult& a, const MeshRandomWalkResult& b) {
        return sameImage(a.image, b.image) && sameImage(a.standardError, b.standardError) &&
               sameImage(a.singleScattering, b.singleScattering) &&
               sameImage(a.singleStandardError, b.singleStandardError) && a.paths == b.paths &&
               a.meanEventsPerPath == b.meanEventsPerPath;
    };
    auto same = [&](const MeshRandomWalkResult& a, const MeshRandomWalkResult& b) {
        return sameImages(a, b) && a.meanRayQueriesPerPath == b.meanRayQueriesPerPath &&
               a.meanNextEventsPerPath == b.meanNextEventsPerPath;
    };
    const MeshRandomWalkResult one = render(1, 3);
    CHECK(one.coveredPixels > 20);
    CHECK(one.coveredPixels < 80);
    CHECK(one.escapedPaths == 0);  // closed
    CHECK(one.paths == 3 * 24 * one.coveredPixels);
    CHECK(one.relativeRmseEstimate > 0.0);
    CHECK(same(one, render(2, 3)));
    CHECK(same(one, render(3, 3)));
    const MeshRandomWalkResult other = render(2, 4);
    CHECK_FALSE(same(one, other));
    // The grid only skips ray queries that cannot hit (its bounds are conservative): without the
    // roulette that also uses it, the images are bit-identical with and without it, and with a
    // coarse one; only the number of queries differs.
    const MeshRandomWalkResult noRoulette = render(2, 3, 1 << 20, false);
    const MeshRandomWalkResult noGrid = render(2, 3, 0, false);
    const MeshRandomWalkResult coarse = render(1, 3, 4096, false);
    CHECK(sameImages(noRoulette, noGrid));
    CHECK(sameImages(noRoulette, coarse));
    CHECK(noGrid.distanceGridCellSize == 0.0);
    CHECK(noRoulette.meanNextEventsPerPath == noRoulette.meanEventsPerPath);  // one per collision
    CHECK(noGrid.meanRayQueriesPerPath > coarse.meanRayQueriesPerPath);
    CHECK(coarse.meanRayQueriesPerPath > noRoulette.meanRayQueriesPerPath);
    CHECK(noRoulette.meanRayQueriesPerPath > one.meanRayQueriesPerPath);
    CHECK(one.meanNextEventsPerPath < one.meanEventsPerPath);
    // Background pixels are alpha 0 and exactly the background colour.
    options.background = glm::dvec3(0.25, 0.5, 0.75);
    const MeshRandomWalkResult bg = render(2, 3);
    CHECK(bg.image.at(0, 0) == glm::vec4(0.25f, 0.5f, 0.75f, 0.0f));
    CHECK(bg.standardError.at(0, 0) == glm::vec4(0.0f));
    CHECK(bg.image.at(6, 5).a == 1.0f);
    CHECK(bg.standardError.at(6, 5).a == 24.0f);
}

TEST_CASE("mesh random walk: a thin back-lit slab transmits, a thick one does not", "[mesh-random-walk][cpu]") {
    // Light from behind (travelling towards +z, the camera side). 1 mm = 1 mean free path thin:
    // much comes through; 20 mm with albedo 0.8 (diffusion length 1.3 mm): exp(-15), nothing.
    const ScatteringMaterial material = withAlbedos(0.8, 0.8, 0.8, 1.3);
    DirectionalLight back;
    back.direction = {0.0f, 0.0f, 1.0f};
    const MeshRandomWalkResult thin = renderBox(material, back, 400, 9, 0.025f);
    const MeshRandomWalkResult thick = renderBox(material, back, 400, 9, 0.5f);
    const PixelMean t = meanOf(thin.image, thin.standardError, 1);
    const PixelMean k = meanOf(thick.image, thick.standardError, 1);
    INFO("thin " << t.value << " +- " << t.standardError << ", thick " << k.value << " +- " << k.standardError);
    CHECK(t.value > 20.0 * t.standardError);
    CHECK(t.value > 0.01);
    CHECK(k.value < 1e-4 * t.value);
    // Seen from the lit side the thick slab reflects (the head-on box test's value for albedo 0.8).
    DirectionalLight front;
    const MeshRandomWalkResult lit = renderBox(material, front, 400, 9, 0.5f);
    CHECK(meanOf(lit.image, lit.standardError, 1).value > 0.04);
    // No light: black, covered.
    const MeshRandomWalkResult dark = renderMeshRandomWalk(makeSlab(), glm::mat4(1.0f), material, {}, headOnCamera(), 4,
                                                           4, MeshRandomWalkOptions{});
    CHECK(dark.coveredPixels == 16);
    CHECK(dark.image.at(1, 1) == glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
}

TEST_CASE("mesh random walk: a thin back-lit slab transmits what the finite slab walk transmits",
          "[mesh-random-walk][cpu]") {
    // Two independent ground truths of the same physics: 2 mm of skin1 lit from behind, the mesh
    // walk's radiance along the normal against simulateSlab's (finite thickness) transmitted
    // radiance within 10 degrees of the normal. Measured: R 0.0871 / 0.0874, G 0.0441 / 0.0439,
    // B 0.0149 / 0.0153 (differences within one standard error). Bound: 4 combined standard
    // errors plus 2 % for the cone's average against the normal value.
    const ScatteringMaterial skin = materialPreset("skin1");
    DirectionalLight back;
    back.direction = {0.0f, 0.0f, 1.0f};
    const MeshRandomWalkResult mesh = renderBox(skin, back, 2048, 21, float(2.0 / kMillimetresPerUnit));
    SlabRandomWalkOptions o;
    o.thickness = 2.0;
    o.paths = 400000;
    o.coneHalfAngleDeg = 10.0;
    o.seed = 22;
    const SlabRandomWalkResult slab = simulateSlab(skin, 0.0, o);
    for (int c = 0; c < 3; ++c) {
        const PixelMean m = meanOf(mesh.image, mesh.standardError, c);
        const Estimate& s = slab.channels[c].transmittedConeRadiance;
        INFO("channel " << c << ": mesh walk " << m.value << " +- " << m.standardError << ", slab walk " << s.value
                        << " +- " << s.standardError);
        CHECK(std::abs(m.value - s.value) <=
              4.0 * std::hypot(m.standardError, s.standardError) + 0.02 * s.value);
    }
}

TEST_CASE("mesh random walk: bad input is rejected with a message naming it", "[mesh-random-walk][cpu]") {
    const Mesh box = makeSlab();
    const ScatteringMaterial ok = withAlbedos(0.5, 0.5, 0.5, 1.3);
    const std::vector<Light> lights{DirectionalLight{}};
    const Camera camera = headOnCamera();
    MeshRandomWalkOptions o;
    o.pathsPerPixel = 1;
    const auto kind = ErrorKind::InvalidArgument;
    auto withOption = [&](auto set) {
        MeshRandomWalkOptions x = o;
        set(x);
        return x;
    };
    auto render = [&](const MeshRandomWalkOptions& x) {
        return renderMeshRandomWalk(box, glm::mat4(1.0f), ok, lights, camera, 2, 2, x);
    };
    REQUIRE_SSS_ERROR(render(withOption([](auto& x) { x.pathsPerPixel = 0; })), kind,
                      Contains("renderMeshRandomWalk: MeshRandomWalkOptions::pathsPerPixel must be >= 1, got 0"));
    REQUIRE_SSS_ERROR(render(withOption([](auto& x) { x.threads = -1; })), kind,
                      Contains("MeshRandomWalkOptions::threads"));
    REQUIRE_SSS_ERROR(render(withOption([](auto& x) { x.maxEvents = 0; })), kind,
                      Contains("MeshRandomWalkOptions::maxEvents"));
    REQUIRE_SSS_ERROR(render(withOption([](auto& x) { x.millimetresPerUnit = 0.0; })), kind,
                      Contains("MeshRandomWalkOptions::millimetresPerUnit"));
    REQUIRE_SSS_ERROR(render(withOption([](auto& x) { x.millimetresPerUnit = NAN; })), kind,
                      Contains("MeshRandomWalkOptions::millimetresPerUnit"));
    REQUIRE_SSS_ERROR(render(withOption([](auto& x) { x.background.y = INFINITY; })), kind,
                      Contains("MeshRandomWalkOptions::background"));
    REQUIRE_SSS_ERROR(render(withOption([](auto& x) { x.distanceGridCells = -1; })), kind,
                      Contains("MeshRandomWalkOptions::distanceGridCells"));
    REQUIRE_SSS_ERROR(render(withOption([](auto& x) { x.distanceGridCells = (1 << 26) + 1; })), kind,
                      Contains("MeshRandomWalkOptions::distanceGridCells"));
    REQUIRE_SSS_ERROR(renderMeshRandomWalk(box, glm::mat4(1.0f), ok, lights, camera, 0, 2, o), kind,
                      Contains("image size"));
    ScatteringMaterial bad = ok;
    bad.eta = 3.0;
    REQUIRE_SSS_ERROR(renderMeshRandomWalk(box, glm::mat4(1.0f), bad, lights, camera, 2, 2, o), kind,
                      Contains("eta"));
    DirectionalLight dark;
    dark.direction = glm::vec3(0.0f);
    REQUIRE_SSS_ERROR(renderMeshRandomWalk(box, glm::mat4(1.0f), ok, {DirectionalLight{}, dark}, camera, 2, 2, o), kind,
                      Contains("renderMeshRandomWalk: lights[1]"));
    REQUIRE_SSS_ERROR(renderMeshRandomWalk(box, glm::mat4(0.0f), ok, lights, camera, 2, 2, o), kind,
                      Contains("singular"));
    glm::mat4 nan(1.0f);
    nan[3][0] = NAN;
    REQUIRE_SSS_ERROR(renderMeshRandomWalk(box, nan, ok, lights, camera, 2, 2, o), kind, Contains("finite"));
    // A mesh whose triangles have no area has no inside. (A mesh without triangles cannot be
    // made: Mesh's factories reject it.)
    const Mesh flat = Mesh::fromArrays({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {0, 1, 2}, {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}},
                                       "needle");
    REQUIRE_SSS_ERROR(renderMeshRandomWalk(flat, glm::mat4(1.0f), ok, lights, camera, 2, 2, o), kind,
                      Contains("the mesh \"needle\" has zero surface area"));
}

// Not a test: a report of the cost (hidden; run with "[mesh-random-walk-report]"). Renders the
// Stanford bunny ($SSS_DATA_DIR or ../shared/data, meshes/stanford-bunny.obj; a UV sphere if
// absent) in marble at 64 x 48, lit from the front left, with and without the distance grid, and
// prints the time, paths, events and ray queries per path and the relative standard error.
// SSS_WALK_PATHS sets the paths per pixel and channel (default 16).
TEST_CASE("mesh random walk: report of the cost on the bunny in marble", "[.][mesh-random-walk-report]") {
    std::filesystem::path dir = "../shared/data";
    if (const char* env = std::getenv("SSS_DATA_DIR"); env && *env) dir = env;
    const std::filesystem::path file = dir / "meshes" / "stanford-bunny.obj";
    std::error_code ec;
    const bool real = std::filesystem::is_regular_file(file, ec);
    const Mesh mesh = real ? Mesh::load(file) : makeUvSphere(256, 128, 0.08f);
    const int width = 64, height = 48;
    Camera camera;
    camera.frameTight(mesh.positions(), float(width) / float(height));
    DirectionalLight light;
    light.direction = {-0.3f, -0.4f, -1.0f};
    const ScatteringMaterial marble = materialPreset("marble");
    int paths = 16;
    if (const char* env = std::getenv("SSS_WALK_PATHS"); env && *env) paths = std::max(1, std::atoi(env));
    std::printf("%s, %zu triangles, marble, %d x %d, %d paths per pixel and channel\n",
                real ? file.string().c_str() : "UV sphere (no bunny found)", mesh.triangleCount(), width, height, paths);
    for (const int cells : {1 << 20, 0}) {
        MeshRandomWalkOptions options;
        options.pathsPerPixel = paths;
        options.distanceGridCells = cells;
        const auto start = std::chrono::steady_clock::now();
        const MeshRandomWalkResult r = renderMeshRandomWalk(mesh, glm::mat4(1.0f), marble, {light}, camera, width, height,
                                                            options);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::printf("grid %8d cells (%.3g mm): %.2f s, %d covered pixels, %lld paths (%.0f per s), %.1f events, "
                    "%.1f ray queries and %.1f next-event estimations per path, %lld escaped, %lld truncated; "
                    "relative standard error (rms) %.4f\n",
                    cells, r.distanceGridCellSize * options.millimetresPerUnit, seconds, r.coveredPixels,
                    static_cast<long long>(r.paths), double(r.paths) / seconds, r.meanEventsPerPath, r.meanRayQueriesPerPath,
                    r.meanNextEventsPerPath, static_cast<long long>(r.escapedPaths),
                    static_cast<long long>(r.truncatedPaths), r.relativeRmseEstimate);
        CHECK(r.coveredPixels > 0);
    }
}
