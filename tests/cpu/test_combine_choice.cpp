// What MeshCombine::Automatic decides from (src/mesh/combine_choice.h): the mesh's edge length
// against the material's diffusion length.
#include "mesh/combine_choice.h"

#include <catch2/catch.hpp>
#include <sss/bssrdf.h>
#include <sss/materials.h>
#include <sss/procedural.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

using namespace sss;

TEST_CASE("the surface edge length is the longest edge of the triangles holding 90 % of the area", "[mesh][combine]") {
    // A 2 x 2 x 1 box: every face is two right triangles whose longest edge is the diagonal. The
    // 2 x 2 faces (sqrt 8) hold 8 of the 16 units of area, the 2 x 1 faces (sqrt 5) the rest,
    // so the 90th percentile lies among the big faces.
    CHECK(detail::surfaceEdgeLength(makeSlab({2.0f, 2.0f, 1.0f})) == Approx(std::sqrt(8.0)).epsilon(1e-5));
    CHECK(detail::surfaceEdgeLength(makeSlab({2.0f, 2.0f, 2.0f})) == Approx(std::sqrt(8.0)).epsilon(1e-5));
    // A finer sphere has shorter edges, about in proportion to its segments.
    const float coarse = detail::surfaceEdgeLength(makeUvSphere(24, 16));
    const float fine = detail::surfaceEdgeLength(makeUvSphere(48, 32));
    CHECK(fine == Approx(coarse / 2.0f).epsilon(0.1));
    CHECK(fine < 2.0f * 3.14159f / 48.0f * 1.5f);
}

TEST_CASE("the largest scale of a model transform", "[mesh][combine]") {
    CHECK(detail::largestScale(glm::mat4(1.0f)) == Approx(1.0f));
    const glm::mat4 m = glm::rotate(glm::scale(glm::mat4(1.0f), {0.5f, 3.0f, 2.0f}), 0.7f, glm::vec3(0, 0, 1));
    CHECK(detail::largestScale(m) == Approx(3.0f).epsilon(1e-5));
}

TEST_CASE("the edge is measured against the narrowest profile among the channels that reflect light", "[mesh][combine]") {
    // Marble: all three channels reflect, blue has the largest sigma_tr.
    const ScatteringMaterial marble = materialPreset("marble");
    const DipoleConstants m = deriveDipoleConstants(marble, 10.0, ScatteringProfile::Dipole);
    CHECK(detail::edgeToDiffusionLength(0.5f, marble, 10.0) == Approx(0.5 * m.sigmaTr.z));
    // Ketchup: green and blue are absorbed (reflectance below a tenth of red's), so red's much
    // wider profile sets the length.
    const ScatteringMaterial ketchup = materialPreset("ketchup");
    const DipoleConstants k = deriveDipoleConstants(ketchup, 10.0, ScatteringProfile::Dipole);
    REQUIRE(k.sigmaTr.y > 5.0 * k.sigmaTr.x);
    CHECK(detail::edgeToDiffusionLength(0.5f, ketchup, 10.0) == Approx(0.5 * k.sigmaTr.x));
    // Scale: twice the millimetres per unit, twice the ratio.
    CHECK(detail::edgeToDiffusionLength(0.5f, marble, 20.0) == Approx(2.0 * detail::edgeToDiffusionLength(0.5f, marble, 10.0)));
}

TEST_CASE("Automatic takes the vertex estimate with a near field on meshes that follow their shape, else resolves by "
          "the threshold; explicit choices stay",
          "[mesh][combine]") {
    const double followsShape = detail::kVertexEstimateMaxEdgeOverRadius, coarseShape = 2.0;
    // With the near field (the default): the estimate at every edge length on a mesh that
    // follows its shape; on one that does not, the maps above the threshold.
    for (const double ratio : {0.0, 0.5, 2.0, 8.0, 100.0})
        CHECK(detail::resolveCombine(MeshCombine::Automatic, ratio, 1.0f, followsShape) == MeshCombine::VertexEstimate);
    CHECK(detail::resolveCombine(MeshCombine::Automatic, 0.5, 1.0f, coarseShape) == MeshCombine::VertexEstimate);
    CHECK(detail::resolveCombine(MeshCombine::Automatic, 8.0, 1.0f, coarseShape) == MeshCombine::PerPixel);
    // Without it: the estimate up to the threshold, the maps above.
    CHECK(detail::resolveCombine(MeshCombine::Automatic, 0.5, 0.0f, 0.1) == MeshCombine::VertexEstimate);
    CHECK(detail::resolveCombine(MeshCombine::Automatic, detail::kVertexEstimateMaxEdgeRatio, 0.0f, 0.1) ==
          MeshCombine::VertexEstimate);
    CHECK(detail::resolveCombine(MeshCombine::Automatic, detail::kVertexEstimateMaxEdgeRatio * 1.01, 0.0f, 0.1) ==
          MeshCombine::PerPixel);
    CHECK(detail::resolveCombine(MeshCombine::PerVertex, 100.0, 1.0f, 0.1) == MeshCombine::PerVertex);
    CHECK(detail::resolveCombine(MeshCombine::VertexEstimate, 100.0, 0.0f, coarseShape) == MeshCombine::VertexEstimate);
    CHECK(detail::resolveCombine(MeshCombine::PerPixel, 0.0, 1.0f, 0.1) == MeshCombine::PerPixel);
}
