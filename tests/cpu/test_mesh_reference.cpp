// The CPU mesh reference renderer (Monte Carlo over the surface with shadow rays) and its BVH:
// brute-force ray checks, an analytic plane, translucency, convergence and light equivalence.
#include "sss/mesh_reference.h"

#include "reference/bvh.h"
#include "test_helpers.h"

#include <sss/image_compare.h>
#include <sss/materials.h>
#include <sss/procedural.h>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

using Catch::Contains;
using namespace sss;

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Axis-aligned box centred at the origin, each face an n x n grid of quads (flat normals,
// counter-clockwise seen from outside): the +z and -z faces use nz, the others nSide.
Mesh makeGridBox(glm::vec3 size, int nz, int nSide) {
    std::vector<glm::vec3> positions, normals;
    std::vector<uint32_t> indices;
    const glm::vec3 h = size * 0.5f;
    auto face = [&](glm::vec3 n, glm::vec3 u, glm::vec3 v, int cells) {
        // u x v = n; u, v, n unit axis vectors.
        const float su = glm::dot(glm::abs(u), h), sv = glm::dot(glm::abs(v), h), sn = glm::dot(glm::abs(n), h);
        const auto base = static_cast<uint32_t>(positions.size());
        for (int j = 0; j <= cells; ++j)
            for (int i = 0; i <= cells; ++i) {
                const float a = -1.0f + 2.0f * float(i) / float(cells), b = -1.0f + 2.0f * float(j) / float(cells);
                positions.push_back(n * sn + u * (a * su) + v * (b * sv));
                normals.push_back(n);
            }
        const auto row = static_cast<uint32_t>(cells + 1);
        for (uint32_t j = 0; j < uint32_t(cells); ++j)
            for (uint32_t i = 0; i < uint32_t(cells); ++i) {
                const uint32_t k = base + j * row + i;
                indices.insert(indices.end(), {k, k + 1, k + row + 1, k, k + row + 1, k + row});
            }
    };
    const glm::vec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
    face(z, x, y, nz);
    face(-z, y, x, nz);
    face(x, y, z, nSide);
    face(-x, z, y, nSide);
    face(y, z, x, nSide);
    face(-y, x, z, nSide);
    return Mesh::fromArrays(std::move(positions), std::move(indices), std::move(normals), "grid box");
}

// Camera at (0, 0, distance) looking down -z, orthographic with the given view height.
Camera orthoDown(float height, float distance = 3.0f) {
    Camera camera;
    camera.setDistance(distance);
    camera.setProjectionType(Projection::Orthographic);
    camera.setOrthoHeight(height);
    camera.setClipPlanes(0.01f, 10.0f * distance + 1000.0f);
    return camera;
}

glm::dvec3 meanRgb(const Image& image) {
    glm::dvec3 sum(0.0);
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) sum += glm::dvec3(glm::vec3(image.at(x, y)));
    return sum / double(image.width() * image.height());
}

// T(eta, 1)^2 * integral over a plane of S_d E at normal incidence, by a 10^5-interval trapezoid
// rule in r with the 2 pi r of the ring. x_o = 0 with n_o = +z. Front-lit (depth 0): x_i =
// (r, 0, 0), n_i = w_i = +z. Back-lit (depth > 0): the far face of a slab, x_i = (r, 0, -depth),
// n_i = w_i = -z.
glm::dvec3 planeIntegral(const DipoleConstants& c, double rMax, double depth = 0.0) {
    const glm::dvec3 n = depth > 0.0 ? glm::dvec3(0.0, 0.0, -1.0) : glm::dvec3(0.0, 0.0, 1.0);
    const int steps = 100000;
    const double h = rMax / steps;
    glm::dvec3 sum(0.0);
    for (int k = 0; k <= steps; ++k) {
        const double r = k * h;
        const glm::dvec3 sd = evaluateSd(c, glm::dvec3(r, 0.0, -depth), n, n, glm::dvec3(0.0), glm::dvec3(0, 0, 1));
        sum += (k == 0 || k == steps ? 0.5 : 1.0) * 2.0 * std::numbers::pi * r * sd;
    }
    const double t = fresnelTransmittance(c.eta, 1.0);
    return sum * h * t * t;
}

// A potato sphere of radius 1 at 150 mm per unit (sigma_tr * radius = 10.5 / 20.8 / 73.7), seen
// by the default perspective camera at (0, 0, 3). Lit pixels are about 0.1 to 0.5; the absolute
// error floor keeps deep-shadow pixels (1e-5 and far less in blue) from running to maxSamples.
struct SphereScene {
    Mesh mesh = makeUvSphere(32, 24, 1.0f);
    ScatteringMaterial material = materialPreset("potato");
    Camera camera;
    MeshReferenceOptions options;
    SphereScene() {
        options.millimetresPerUnit = 150.0;
        options.absoluteError = 1e-4;
        options.threads = 2;
    }
};

}  // namespace

TEST_CASE("mesh reference BVH: closest and any hit equal brute force", "[cpu]") {
    const auto start = std::chrono::steady_clock::now();
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> uni(-1.0, 1.0);
    int rays = 0, hits = 0, nodes = 0;
    for (const Mesh& mesh : {makeTorus(0.7f, 0.3f, 48, 24), makeUvSphere(32, 24, 0.8f)}) {
        std::vector<glm::dvec3> positions;
        for (const glm::vec3& p : mesh.positions()) positions.emplace_back(p);
        const detail::TriangleBvh bvh(positions, mesh.indices());
        REQUIRE(bvh.triangleCount() == mesh.triangleCount());
        nodes += int(bvh.nodeCount());
        const auto& idx = mesh.indices();
        for (int i = 0; i < 5000; ++i) {
            detail::BvhRay ray;
            ray.origin = glm::dvec3(uni(rng), uni(rng), uni(rng)) * 1.5;
            // Half the rays aim at a random vertex (sure hits), half go anywhere.
            const glm::dvec3 aim = i % 2 ? positions[rng() % positions.size()] : glm::dvec3(uni(rng), uni(rng), uni(rng));
            ray.direction = aim - ray.origin + glm::dvec3(uni(rng), uni(rng), uni(rng)) * 1e-3;
            ray.tMax = i % 3 ? std::numeric_limits<double>::infinity() : 0.5 + 0.5 * uni(rng);
            double bestT = ray.tMax;
            int64_t best = -1;
            for (size_t t = 0; t < mesh.triangleCount(); ++t) {
                double tt, u, v;
                if (detail::intersectTriangle(ray.origin, ray.direction, ray.tMin, bestT, positions[idx[3 * t]],
                                              positions[idx[3 * t + 1]], positions[idx[3 * t + 2]], tt, u, v)) {
                    bestT = tt;
                    best = int64_t(t);
                }
            }
            const auto hit = bvh.closestHit(ray);
            ++rays;
            INFO("ray " << i);
            REQUIRE(hit.has_value() == (best >= 0));
            REQUIRE(bvh.anyHit(ray) == (best >= 0));
            if (best < 0) continue;
            ++hits;
            REQUIRE(hit->t == bestT);  // same arithmetic, so bit-identical
            if (hit->triangle != uint32_t(best)) {
                // Only a tie on a shared edge may pick another triangle.
                double tt, u, v;
                REQUIRE(detail::intersectTriangle(ray.origin, ray.direction, ray.tMin, ray.tMax,
                                                  positions[idx[3 * hit->triangle]], positions[idx[3 * hit->triangle + 1]],
                                                  positions[idx[3 * hit->triangle + 2]], tt, u, v));
                REQUIRE(tt == bestT);
            }
        }
    }
    CHECK(hits > rays / 3);
    WARN("BVH vs brute force: " << rays << " rays, " << hits << " hits, " << nodes << " nodes, "
                                << secondsSince(start) << " s");
}

TEST_CASE("mesh reference: BVH edge cases", "[cpu]") {
    // A single triangle, rays exactly through a vertex and an edge, and parallel rays.
    const std::vector<glm::dvec3> p{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const detail::TriangleBvh bvh(p, {0, 1, 2});
    CHECK(bvh.depth() == 1);
    CHECK(bvh.closestHit({{0, 0, 1}, {0, 0, -1}})->t == 1.0);      // vertex
    CHECK(bvh.closestHit({{0.5, 0.5, 1}, {0, 0, -2}})->t == 0.5);  // hypotenuse
    CHECK_FALSE(bvh.closestHit({{0.6, 0.6, 1}, {0, 0, -1}}));
    CHECK_FALSE(bvh.anyHit({{0.2, 0.2, 1}, {1, 0, 0}}));          // parallel
    CHECK_FALSE(bvh.anyHit({{0.2, 0.2, 1}, {0, 0, -1}, 0.0, 1.0}));  // stops exactly at the plane: open interval
    CHECK(bvh.anyHit({{0.2, 0.2, 1}, {0, 0, -1}, 0.0, 1.0 + 1e-12}));
    // Many coincident triangles still build a bounded tree.
    std::vector<uint32_t> same;
    for (int i = 0; i < 1000; ++i) same.insert(same.end(), {0, 1, 2});
    const detail::TriangleBvh stacked(p, same);
    CHECK(stacked.depth() < 40);
    CHECK(stacked.closestHit({{0.2, 0.2, 1}, {0, 0, -1}})->t == 1.0);
}

TEST_CASE("mesh reference: input validation", "[cpu]") {
    const Mesh sphere = makeUvSphere(8, 6);
    const ScatteringMaterial potato;
    const std::vector<Light> lights{DirectionalLight{}};
    const Camera camera;
    REQUIRE_SSS_ERROR(renderMeshReference(sphere, glm::mat4(1.0f), potato, lights, camera, 0, 4),
                      ErrorKind::InvalidArgument, Contains("image size"));
    REQUIRE_SSS_ERROR(renderMeshReference(sphere, glm::mat4(1.0f), potato, lights, camera, 4, 20000),
                      ErrorKind::InvalidArgument, Contains("image size"));
    MeshReferenceOptions options;
    options.targetRelativeError = -0.1;
    REQUIRE_SSS_ERROR(renderMeshReference(sphere, glm::mat4(1.0f), potato, lights, camera, 4, 4, options),
                      ErrorKind::InvalidArgument, Contains("targetRelativeError"));
    options = {};
    options.maxSamples = 10;
    REQUIRE_SSS_ERROR(renderMeshReference(sphere, glm::mat4(1.0f), potato, lights, camera, 4, 4, options),
                      ErrorKind::InvalidArgument, Contains("maxSamples"));
    options = {};
    options.millimetresPerUnit = 0.0;
    REQUIRE_SSS_ERROR(renderMeshReference(sphere, glm::mat4(1.0f), potato, lights, camera, 4, 4, options),
                      ErrorKind::InvalidArgument, Contains("millimetresPerUnit"));
    options = {};
    options.threads = -1;
    REQUIRE_SSS_ERROR(renderMeshReference(sphere, glm::mat4(1.0f), potato, lights, camera, 4, 4, options),
                      ErrorKind::InvalidArgument, Contains("threads"));
    REQUIRE_SSS_ERROR(renderMeshReference(sphere, glm::mat4(0.0f), potato, lights, camera, 4, 4),
                      ErrorKind::InvalidArgument, Contains("singular"));
    ScatteringMaterial bad;
    bad.eta = 0.0;
    REQUIRE_SSS_ERROR(renderMeshReference(sphere, glm::mat4(1.0f), bad, lights, camera, 4, 4),
                      ErrorKind::InvalidArgument, Contains("eta"));
    DirectionalLight zero;
    zero.direction = glm::vec3(0.0f);
    REQUIRE_SSS_ERROR(renderMeshReference(sphere, glm::mat4(1.0f), potato, {zero}, camera, 4, 4),
                      ErrorKind::InvalidArgument, Contains("lights[0]"));
    const Mesh flat = Mesh::fromArrays({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {0, 1, 2}, {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
    REQUIRE_SSS_ERROR(renderMeshReference(flat, glm::mat4(1.0f), potato, lights, camera, 4, 4),
                      ErrorKind::InvalidArgument, Contains("zero surface area"));
}

TEST_CASE("mesh reference: a lit plane matches the radial integral of S_d", "[cpu]") {
    // Potato in millimetres on a 600 mm square (21 transport lengths of its widest channel to the
    // edge), lit and seen at normal incidence: every point of the top face sees the same
    // integral T(1) * integral T(1) S_d E dA over the plane.
    const auto start = std::chrono::steady_clock::now();
    const ScatteringMaterial potato = materialPreset("potato");
    const Mesh slab = makeGridBox({600.0f, 600.0f, 50.0f}, 48, 2);
    const glm::mat4 model = glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, -25.0f});  // top face at z = 0
    DirectionalLight sun;
    sun.direction = {0.0f, 0.0f, -1.0f};
    sun.intensity = 2.0f;
    MeshReferenceOptions options;
    options.millimetresPerUnit = 1.0;
    options.targetRelativeError = 0.005;
    options.threads = 2;
    options.profile = ScatteringProfile::Dipole;  // the quadrature below is the paper's dipole
    const MeshReferenceResult result =
        renderMeshReference(slab, model, potato, {sun}, orthoDown(8.0f, 10.0f), 4, 4, options);
    const glm::dvec3 expected = 2.0 * planeIntegral(deriveDipoleConstants(potato, 1.0), 300.0);
    const glm::dvec3 measured = meanRgb(result.image);
    const glm::dvec3 rel = measured / expected - 1.0;
    WARN("plane: reference " << measured.x << ' ' << measured.y << ' ' << measured.z << ", quadrature " << expected.x
                             << ' ' << expected.y << ' ' << expected.z << ", relative difference " << rel.x << ' '
                             << rel.y << ' ' << rel.z << "; max rel. std. error " << result.maxRelativeStandardError
                             << ", " << result.meanSamplesPerPixel << " samples/pixel, " << secondsSince(start)
                             << " s");
    CHECK(result.coveredPixels == 16);
    CHECK(result.unconvergedPixels == 0);
    for (int c = 0; c < 3; ++c) CHECK(std::abs(rel[c]) < 0.02);
}

TEST_CASE("mesh reference: back-lit slabs, thin translucent and thick opaque", "[cpu]") {
    // Light from below, viewer above: only the far face is lit, so the top sees
    // T(1) * integral T(1) S_d E dA over the bottom plane (the back-lit branch of S_d).
    const auto start = std::chrono::steady_clock::now();
    const ScatteringMaterial potato = materialPreset("potato");
    const DipoleConstants c = deriveDipoleConstants(potato, 1.0);
    DirectionalLight below;
    below.direction = {0.0f, 0.0f, 1.0f};
    MeshReferenceOptions options;
    options.millimetresPerUnit = 1.0;
    options.targetRelativeError = 0.01;
    options.threads = 2;
    options.profile = ScatteringProfile::Dipole;  // the quadrature below is the paper's dipole
    const float thin = 5.0f;
    const Mesh thinSlab = makeGridBox({300.0f, 300.0f, thin}, 48, 2);
    const glm::mat4 thinModel = glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, -thin / 2});
    const MeshReferenceResult thinResult =
        renderMeshReference(thinSlab, thinModel, potato, {below}, orthoDown(8.0f, 10.0f), 4, 4, options);
    const glm::dvec3 thinMeasured = meanRgb(thinResult.image);
    const glm::dvec3 thinExpected = planeIntegral(c, 150.0, thin);
    const glm::dvec3 frontLit = planeIntegral(c, 150.0);
    const glm::dvec3 rel = thinMeasured / thinExpected - 1.0;
    WARN("thin back-lit slab (5 mm): reference " << thinMeasured.x << ' ' << thinMeasured.y << ' ' << thinMeasured.z
                                                 << ", quadrature " << thinExpected.x << ' ' << thinExpected.y << ' '
                                                 << thinExpected.z << " (front-lit " << frontLit.x << ' '
                                                 << frontLit.y << ' ' << frontLit.z << "), relative difference "
                                                 << rel.x << ' ' << rel.y << ' ' << rel.z << ", "
                                                 << thinResult.meanSamplesPerPixel << " samples/pixel");
    for (int ch = 0; ch < 3; ++ch) {
        CHECK(thinMeasured[ch] > 0.01 * frontLit[ch]);
        CHECK(std::abs(rel[ch]) < 0.03);
    }
    CHECK(thinResult.unconvergedPixels == 0);

    // 300 mm thick: exp(-sigma_tr 300 mm) <= 7e-10, zero at any sensible precision.
    const Mesh thickSlab = makeGridBox({300.0f, 300.0f, 300.0f}, 48, 16);
    const glm::mat4 thickModel = glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, -150.0f});
    options.absoluteError = 1e-7 * frontLit.x;
    options.maxSamples = 4096;
    const MeshReferenceResult thick =
        renderMeshReference(thickSlab, thickModel, potato, {below}, orthoDown(8.0f, 10.0f), 4, 4, options);
    const glm::dvec3 thickMeasured = meanRgb(thick.image);
    WARN("thick back-lit slab (300 mm): " << thickMeasured.x << ' ' << thickMeasured.y << ' ' << thickMeasured.z
                                          << ", " << thick.meanSamplesPerPixel << " samples/pixel; both slabs "
                                          << secondsSince(start) << " s");
    for (int ch = 0; ch < 3; ++ch) CHECK(thickMeasured[ch] < 1e-6 * frontLit[ch]);
}

TEST_CASE("mesh reference: sphere image, coverage, thread independence", "[cpu]") {
    const auto start = std::chrono::steady_clock::now();
    SphereScene scene;
    DirectionalLight sun;
    sun.direction = glm::normalize(glm::vec3(1.0f, -0.5f, -1.0f));  // from the upper left, in front
    scene.options.targetRelativeError = 0.02;
    scene.options.background = {0.1, 0.2, 0.3};
    const MeshReferenceResult two = renderMeshReference(scene.mesh, glm::mat4(1.0f), scene.material, {sun},
                                                        scene.camera, 24, 16, scene.options);
    const double seconds = secondsSince(start);
    scene.options.threads = 1;
    const MeshReferenceResult one = renderMeshReference(scene.mesh, glm::mat4(1.0f), scene.material, {sun},
                                                        scene.camera, 24, 16, scene.options);
    WARN("sphere 24x16 at 2 %: " << seconds << " s (2 threads), " << two.meanSamplesPerPixel
                                 << " samples/pixel, max rel. std. error " << two.maxRelativeStandardError
                                 << ", relRmse estimate " << two.relativeRmseEstimate << ", " << two.coveredPixels
                                 << " covered, " << two.unconvergedPixels << " unconverged");
    CHECK(one.image.data() == two.image.data());
    CHECK(two.image.at(0, 0) == glm::vec4(0.1f, 0.2f, 0.3f, 0.0f));
    CHECK(two.image.at(12, 8).a == 1.0f);
    // Lit side brighter than the unlit side; the unlit limb still glows a little (translucency).
    const glm::vec4 lit = two.image.at(9, 6), unlit = two.image.at(16, 10);
    CHECK(lit.r > 3.0f * unlit.r);
    CHECK(unlit.r > 0.0f);
    // Potato: red scatters farthest, blue is absorbed most.
    CHECK(lit.r > lit.b);
    CHECK(two.relativeRmseEstimate < 0.02);
}

TEST_CASE("mesh reference: the error falls as 1 / sqrt(samples)", "[cpu]") {
    const auto start = std::chrono::steady_clock::now();
    SphereScene scene;
    DirectionalLight sun;
    sun.direction = glm::normalize(glm::vec3(1.0f, -0.5f, -1.0f));
    const int w = 16, h = 12;
    auto render = [&](int samples, uint64_t seed) {
        MeshReferenceOptions options = scene.options;
        options.targetRelativeError = 0.0;
        options.minSamples = options.maxSamples = samples;
        options.seed = seed;
        return renderMeshReference(scene.mesh, glm::mat4(1.0f), scene.material, {sun}, scene.camera, w, h, options);
    };
    const MeshReferenceResult truth = render(8192, 99);
    const MeshReferenceResult low = render(64, 1), high = render(256, 2);
    const double lowError = computeErrorMetrics(low.image, truth.image).relRmse;
    const double highError = computeErrorMetrics(high.image, truth.image).relRmse;
    WARN("convergence: estimated relRmse " << low.relativeRmseEstimate << " (64 spp), " << high.relativeRmseEstimate
                                           << " (256 spp), " << truth.relativeRmseEstimate
                                           << " (8192 spp); measured against 8192 spp " << lowError << ", "
                                           << highError << "; " << secondsSince(start) << " s");
    CHECK(low.relativeRmseEstimate / high.relativeRmseEstimate == Approx(2.0).epsilon(0.15));
    CHECK(lowError / highError == Approx(2.0).epsilon(0.3));
    // The estimate predicts the real error.
    CHECK(lowError / low.relativeRmseEstimate == Approx(1.0).epsilon(0.3));
    CHECK(highError / high.relativeRmseEstimate == Approx(1.0).epsilon(0.3));
}

TEST_CASE("mesh reference: a far point light equals a directional light of the same irradiance", "[cpu]") {
    const auto start = std::chrono::steady_clock::now();
    SphereScene scene;
    scene.options.targetRelativeError = 0.02;
    const glm::vec3 direction = glm::normalize(glm::vec3(-1.0f, -1.0f, -1.0f));
    DirectionalLight sun;
    sun.direction = direction;
    sun.color = {1.0f, 0.9f, 0.8f};
    sun.intensity = 1.5f;
    PointLight lamp;
    const float distance = 1000.0f;  // radius 1: irradiance within +-0.2 % over the sphere
    lamp.position = -direction * distance;
    lamp.color = sun.color;
    lamp.intensity = sun.intensity * distance * distance;
    const MeshReferenceResult a = renderMeshReference(scene.mesh, glm::mat4(1.0f), scene.material, {sun},
                                                      scene.camera, 24, 16, scene.options);
    const MeshReferenceResult b = renderMeshReference(scene.mesh, glm::mat4(1.0f), scene.material, {lamp},
                                                      scene.camera, 24, 16, scene.options);
    const ErrorMetrics m = computeErrorMetrics(b.image, a.image);
    WARN("point vs directional: relRmse " << m.relRmse << " (estimates " << a.relativeRmseEstimate << ", "
                                          << b.relativeRmseEstimate << "), " << secondsSince(start) << " s");
    CHECK(m.relRmse < 0.02);
}
