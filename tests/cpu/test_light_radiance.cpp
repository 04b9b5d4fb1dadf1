// detail::commonRadianceScale: when a change of the lights is one of radiance alone, which the
// renderers' caches (the multiple-scattering cache, the path tracer's running mean) scale instead
// of restarting.
#include "core/light_geometry.h"

#include <catch2/catch.hpp>
#include <sss/light.h>

#include <optional>
#include <vector>

using namespace sss;
using sss::detail::commonRadianceScale;

namespace {
DirectionalLight sun(glm::vec3 color, float intensity) {
    return {.direction = {0.0f, -1.0f, 0.0f}, .color = color, .intensity = intensity};
}
PointLight lamp(glm::vec3 color, float intensity) {
    return {.position = {1.0f, 2.0f, 3.0f}, .color = color, .intensity = intensity};
}
}  // namespace

TEST_CASE("a change of radiance common to all lights is one factor per channel", "[lights]") {
    const glm::vec3 white(1.0f);
    SECTION("one light's intensity and colour") {
        const auto scale = commonRadianceScale({sun(white, 2.0f)}, {sun({1.0f, 0.5f, 0.25f}, 6.0f)});
        REQUIRE(scale);
        CHECK(scale->x == Approx(3.0f));
        CHECK(scale->y == Approx(1.5f));
        CHECK(scale->z == Approx(0.75f));
    }
    SECTION("every light scaled alike, and nothing changed") {
        const auto both = commonRadianceScale({sun(white, 1.0f), lamp({0.5f, 1.0f, 1.0f}, 4.0f)},
                                              {sun({2.0f, 1.0f, 1.0f}, 1.0f), lamp({1.0f, 1.0f, 1.0f}, 4.0f)});
        REQUIRE(both);
        CHECK(both->x == Approx(2.0f));
        CHECK(both->y == Approx(1.0f));
        const auto same = commonRadianceScale({sun(white, 1.0f), lamp(white, 4.0f)}, {sun(white, 1.0f), lamp(white, 4.0f)});
        REQUIRE(same);
        CHECK(*same == glm::vec3(1.0f));
    }
    SECTION("darkened to nothing, and a channel dark in every light staying dark") {
        const auto off = commonRadianceScale({sun(white, 1.0f)}, {sun(white, 0.0f)});
        REQUIRE(off);
        CHECK(*off == glm::vec3(0.0f));
        CHECK(commonRadianceScale({sun({1.0f, 1.0f, 0.0f}, 1.0f)}, {sun({2.0f, 1.0f, 0.0f}, 1.0f)}));
    }
    SECTION("what no factor gives") {
        // A channel that was dark now lit: nothing was traced for it.
        CHECK_FALSE(commonRadianceScale({sun({1.0f, 1.0f, 0.0f}, 1.0f)}, {sun(white, 1.0f)}));
        CHECK_FALSE(commonRadianceScale({sun(white, 0.0f)}, {sun(white, 1.0f)}));
        // One of two lights brightened: their mix changes.
        CHECK_FALSE(commonRadianceScale({sun(white, 1.0f), lamp(white, 1.0f)}, {sun(white, 1.0f), lamp(white, 2.0f)}));
        // A light moved or turned, one added, or of another kind.
        PointLight moved = lamp(white, 1.0f);
        moved.position.x += 0.5f;
        CHECK_FALSE(commonRadianceScale({lamp(white, 1.0f)}, {moved}));
        CHECK_FALSE(commonRadianceScale({sun(white, 1.0f)}, {sun(white, 1.0f), lamp(white, 1.0f)}));
        CHECK_FALSE(commonRadianceScale({sun(white, 1.0f)}, {lamp(white, 1.0f)}));
    }
}

TEST_CASE("lights with unit radiance keep where their light goes", "[lights]") {
    SpotLight spot;
    spot.color = {0.2f, 0.4f, 0.6f};
    spot.intensity = 7.0f;
    spot.coneAngle = 20.0f;
    const std::vector<Light> unit = detail::withUnitRadiance({spot});
    const auto& s = std::get<SpotLight>(unit.front());
    CHECK(s.color == glm::vec3(1.0f));
    CHECK(s.intensity == 1.0f);
    CHECK(s.coneAngle == 20.0f);
    CHECK(s.position == spot.position);
    CHECK(s.direction == spot.direction);
}

TEST_CASE("a light volume's lights: unit radiance, a spot light as a point light where it stands", "[lights]") {
    SpotLight spot;
    spot.position = {1.0f, 2.0f, 3.0f};
    spot.color = {0.2f, 0.4f, 0.6f};
    spot.intensity = 7.0f;
    const DirectionalLight sun{.direction = {0.0f, -1.0f, 0.5f}, .color = {1.0f, 0.5f, 0.25f}, .intensity = 3.0f};
    const std::vector<Light> swept = detail::asLightVolumeLights({spot, sun});
    REQUIRE(swept.size() == 2);
    CHECK(swept[0] == Light{PointLight{.position = spot.position}});
    CHECK(swept[1] == Light{DirectionalLight{.direction = sun.direction}});
    // Aimed elsewhere or narrowed, the spot keeps its light volume's lights; moved, it does not.
    SpotLight aimed = spot;
    aimed.direction = {1.0f, 0.0f, 0.0f};
    aimed.coneAngle = 5.0f;
    aimed.falloff = 0.0f;
    CHECK(detail::asLightVolumeLights({aimed}) == detail::asLightVolumeLights({spot}));
    SpotLight moved = spot;
    moved.position.y += 0.25f;
    CHECK(detail::asLightVolumeLights({moved}) != detail::asLightVolumeLights({spot}));
}
