// detail::planLightSweeps for a directional light: one sweep along the axis the light travels
// most along, and a second one blended in only near the diagonal where that axis changes, with
// weights that change continuously as the light turns.
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
