// detail::planLightSweeps for a directional light and a point light outside the box: one sweep
// along the axis the light travels most along, and a second one blended in only near the diagonal
// where that axis changes, with weights that change continuously as the light moves.
#include "volume/light_sweep_plan.h"

#include <catch2/catch.hpp>
#include <sss/light.h>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace sss;
using sss::detail::LightSweep;
using sss::detail::planLightSweeps;

namespace {
Bounds unitBox() {
    Bounds box;
    box.extend(glm::vec3(0.0f));
    box.extend(glm::vec3(1.0f));
    return box;
}

std::vector<LightSweep> sweepsFor(glm::vec3 direction, glm::ivec3 dims = glm::ivec3(64)) {
    return planLightSweeps(DirectionalLight{.direction = glm::normalize(direction)}, unitBox(), dims);
}

// Each axis's weight (0 where no sweep runs along it).
glm::vec3 axisWeights(const std::vector<LightSweep>& sweeps) {
    glm::vec3 weights(0.0f);
    for (const LightSweep& sweep : sweeps) weights[sweep.axis] += sweep.weight;
    return weights;
}
}  // namespace

TEST_CASE("a directional light away from a diagonal is swept once, along its main axis", "[lights]") {
    for (const glm::vec3 direction : {glm::vec3(0, -1, 0), glm::vec3(-0.3f, -1, -0.2f), glm::vec3(-0.5f, -1, -0.25f)}) {
        const std::vector<LightSweep> sweeps = sweepsFor(direction);
        REQUIRE(sweeps.size() == 1);
        CHECK(sweeps[0].axis == 1);
        CHECK(sweeps[0].reversed);
        CHECK(sweeps[0].weight == 1.0f);
    }
}

TEST_CASE("a directional light on a diagonal is swept along both axes, half each", "[lights]") {
    const std::vector<LightSweep> sweeps = sweepsFor({1, -1, 0.2f});
    REQUIRE(sweeps.size() == 2);
    CHECK(axisWeights(sweeps) == glm::vec3(0.5f, 0.5f, 0.0f));
    CHECK(sweeps[0].reversed != sweeps[1].reversed);  // +x, -y
}

TEST_CASE("the axes are ranked in voxels, so flat voxels change the main axis", "[lights]") {
    // Along (1, 0.8, 0) with voxels four times as long in x: 0.25 voxels in x per 0.8 in y.
    const std::vector<LightSweep> sweeps = sweepsFor({1, 0.8f, 0}, {16, 64, 64});
    REQUIRE(sweeps.size() == 1);
    CHECK(sweeps[0].axis == 1);
}

TEST_CASE("a directional light's sweep weights change continuously as it turns", "[lights]") {
    // Turn the light about z from the -y axis past the diagonal to the x axis, tilted out of the
    // plane so that all three axes take part: the blend's start and the diagonal are crossed.
    glm::vec3 previous = axisWeights(sweepsFor({0, -1, 0.3f}));
    float largestStep = 0.0f;
    for (float degrees = 0.05f; degrees <= 90.0f; degrees += 0.05f) {
        const float a = glm::radians(degrees);
        const std::vector<LightSweep> sweeps = sweepsFor({std::sin(a), -std::cos(a), 0.3f});
        const glm::vec3 weights = axisWeights(sweeps);
        CHECK(weights.x + weights.y + weights.z == Approx(1.0f));
        largestStep = std::max(largestStep, glm::length(weights - previous));
        previous = weights;
        // The second sweep starts where (a2 - 0.3) / (a1 + a2 - 0.6) = kSweepBlendStart (0.42):
        // 39.8 degrees from either axis.
        if (degrees < 39.0f || degrees > 51.0f) CHECK(sweeps.size() == 1);
        if (degrees > 40.5f && degrees < 49.5f) CHECK(sweeps.size() == 2);
    }
    CHECK(largestStep < 0.01f);
}

namespace {
// A point light at 0.5 + 0.5 r: r is the light's offset from the unit box's centre in half-extents.
std::vector<LightSweep> sweepsForPointAt(glm::vec3 r) {
    return planLightSweeps(PointLight{.position = glm::vec3(0.5f) + 0.5f * r}, unitBox(), glm::ivec3(64));
}
}  // namespace

TEST_CASE("a point light outside, away from a diagonal, is swept once, along its main axis", "[lights]") {
    // Beyond the +y face by 2 half-extents and the +x face by 0.5: a share of 0.2.
    for (const glm::vec3 r : {glm::vec3(1.5f, 3, 0.5f), glm::vec3(0.2f, 3, -0.9f), glm::vec3(-2, 4, 1.5f)}) {
        const std::vector<LightSweep> sweeps = sweepsForPointAt(r);
        REQUIRE(sweeps.size() == 1);
        CHECK(sweeps[0].axis == 1);
        CHECK(sweeps[0].reversed);  // the light is above, its light travels towards -y
        CHECK(sweeps[0].weight == 1.0f);
    }
    // A spot light outside is planned as a point light at its position.
    const std::vector<LightSweep> spot = planLightSweeps(
        SpotLight{.position = glm::vec3(0.5f) + 0.5f * glm::vec3(1.5f, 3, 0.5f), .direction = {0, -1, 0}}, unitBox(), glm::ivec3(64));
    REQUIRE(spot.size() == 1);
    CHECK(spot[0].axis == 1);
}

TEST_CASE("a point light beyond a box edge's diagonal is swept along both axes, half each", "[lights]") {
    const std::vector<LightSweep> sweeps = sweepsForPointAt({2.5f, -2.5f, 0.3f});
    REQUIRE(sweeps.size() == 2);
    CHECK(axisWeights(sweeps) == glm::vec3(0.5f, 0.5f, 0.0f));
    CHECK(sweeps[0].reversed != sweeps[1].reversed);  // beyond +x (travels -x) and -y (travels +y)
}

TEST_CASE("a point light's sweep weights change continuously as it moves around the box", "[lights]") {
    // Around the box at 3 half-extents from its centre in the xy plane, from above it to beside it.
    glm::vec3 previous = axisWeights(sweepsForPointAt({0, 3, 0.5f}));
    float largestStep = 0.0f;
    for (float degrees = 0.05f; degrees <= 90.0f; degrees += 0.05f) {
        const float a = glm::radians(degrees);
        const glm::vec3 r(3 * std::sin(a), 3 * std::cos(a), 0.5f);
        const std::vector<LightSweep> sweeps = sweepsForPointAt(r);
        const glm::vec3 weights = axisWeights(sweeps);
        CHECK(weights.x + weights.y + weights.z == Approx(1.0f));
        largestStep = std::max(largestStep, glm::length(weights - previous));
        previous = weights;
        // Two sweeps only where (r2 - 1) / (r1 + r2 - 2) > kSweepBlendStart, near 45 degrees.
        const float r1 = std::max(r.x, r.y), r2 = std::min(r.x, r.y);
        const float share = r2 > 1 ? (r2 - 1) / (r1 + r2 - 2) : 0.0f;
        if (share < sss::detail::kSweepBlendStart - 0.005f) CHECK(sweeps.size() == 1);
        if (share > sss::detail::kSweepBlendStart + 0.005f) CHECK(sweeps.size() == 2);
    }
    CHECK(largestStep < 0.01f);
}
