#include "sss/transfer_function.h"

#include "test_helpers.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

using Catch::Contains;
using sss::ControlPoint;
using sss::ErrorKind;
using sss::TransferFunction;

namespace {

void requireNear(glm::vec4 a, glm::vec4 b, float eps = 1e-5f) {
    INFO("a = (" << a.x << ", " << a.y << ", " << a.z << ", " << a.w << "), b = (" << b.x << ", " << b.y << ", "
                 << b.z << ", " << b.w << ")");
    REQUIRE(glm::length(a - b) < eps);
}

// 0.2 red transparent, 0.6 green half opaque, 0.8 blue opaque.
TransferFunction threePoints() {
    return TransferFunction({{0.2f, {1, 0, 0}, 0.0f}, {0.6f, {0, 1, 0}, 0.5f}, {0.8f, {0, 0, 1}, 1.0f}});
}

const float kNaN = std::numeric_limits<float>::quiet_NaN();

}  // namespace

TEST_CASE("Default transfer function is a black-to-white ramp", "[cpu]") {
    const TransferFunction tf;
    REQUIRE(tf.points().size() == 2);
    requireNear(tf.evaluate(0.0f), {0, 0, 0, 0});
    requireNear(tf.evaluate(1.0f), {1, 1, 1, 1});
    requireNear(tf.evaluate(0.25f), {0.25f, 0.25f, 0.25f, 0.25f});
    requireNear(tf.evaluate(-3.0f), {0, 0, 0, 0});
    requireNear(tf.evaluate(7.0f), {1, 1, 1, 1});
}

TEST_CASE("TransferFunction::evaluate at, between and beyond points", "[cpu]") {
    const TransferFunction tf = threePoints();
    requireNear(tf.evaluate(0.2f), {1, 0, 0, 0});
    requireNear(tf.evaluate(0.6f), {0, 1, 0, 0.5f});
    requireNear(tf.evaluate(0.8f), {0, 0, 1, 1});
    requireNear(tf.evaluate(0.4f), {0.5f, 0.5f, 0, 0.25f});
    requireNear(tf.evaluate(0.75f), {0, 0.25f, 0.75f, 0.875f});
    requireNear(tf.evaluate(0.0f), {1, 0, 0, 0});  // constant below the first point
    requireNear(tf.evaluate(1.0f), {0, 0, 1, 1});  // constant above the last point
    REQUIRE_SSS_ERROR(tf.evaluate(kNaN), ErrorKind::InvalidArgument, Contains("NaN"));

    const TransferFunction single({{0.5f, {0.1f, 0.2f, 0.3f}, 0.4f}});
    requireNear(single.evaluate(0.0f), {0.1f, 0.2f, 0.3f, 0.4f});
    requireNear(single.evaluate(1.0f), {0.1f, 0.2f, 0.3f, 0.4f});
}

TEST_CASE("TransferFunction::table samples 0..1 inclusive", "[cpu]") {
    const TransferFunction tf = threePoints();
    const auto t = tf.table();
    REQUIRE(t.size() == 256);
    requireNear(t.front(), tf.evaluate(0.0f));
    requireNear(t.back(), tf.evaluate(1.0f));
    requireNear(t[51], tf.evaluate(0.2f));  // 51/255 = 0.2
    const auto five = tf.table(5);
    REQUIRE(five.size() == 5);
    requireNear(five[2], tf.evaluate(0.5f));
    requireNear(five[3], tf.evaluate(0.75f));
    CHECK(tf.table(2).size() == 2);
    REQUIRE_SSS_ERROR(tf.table(1), ErrorKind::InvalidArgument, Contains("entries") && Contains("got 1"));
}

TEST_CASE("TransferFunction editing keeps points sorted and bumps the revision", "[cpu]") {
    TransferFunction tf = threePoints();
    uint64_t rev = tf.revision();

    SECTION("addPoint inserts in order or replaces") {
        CHECK(tf.addPoint({0.7f, {1, 1, 1}, 0.2f}) == 2);
        REQUIRE(tf.points().size() == 4);
        CHECK(tf.points()[2].value == 0.7f);
        CHECK(tf.revision() > rev);
        rev = tf.revision();
        CHECK(tf.addPoint({0.0f, {0, 0, 0}, 0.0f}) == 0);
        CHECK(tf.revision() > rev);
        rev = tf.revision();
        // Same value: replaces colour/opacity, no new point.
        CHECK(tf.addPoint({0.6f, {0.3f, 0.3f, 0.3f}, 0.9f}) == 2);
        CHECK(tf.points().size() == 5);
        requireNear(tf.evaluate(0.6f), {0.3f, 0.3f, 0.3f, 0.9f});
        CHECK(tf.revision() > rev);
        REQUIRE_SSS_ERROR(tf.addPoint({1.5f, {0, 0, 0}, 0}), ErrorKind::InvalidArgument,
                          Contains("addPoint") && Contains("value") && Contains("1.5"));
    }
    SECTION("movePoint re-sorts and clamps") {
        CHECK(tf.movePoint(0, 0.7f) == 1);  // red moves past green
        CHECK(tf.points()[1].color == glm::vec3(1, 0, 0));
        CHECK(tf.points()[1].value == 0.7f);
        CHECK(tf.revision() > rev);
        CHECK(tf.movePoint(1, 5.0f) == 2);  // clamped to 1
        CHECK(tf.points()[2].value == 1.0f);
        CHECK(tf.movePoint(2, -1.0f) == 0);
        CHECK(tf.points()[0].value == 0.0f);
        REQUIRE_SSS_ERROR(tf.movePoint(3, 0.5f), ErrorKind::InvalidArgument,
                          Contains("movePoint") && Contains("index 3") && Contains("3 points"));
        REQUIRE_SSS_ERROR(tf.movePoint(0, kNaN), ErrorKind::InvalidArgument, Contains("NaN"));
    }
    SECTION("movePoint onto another point nudges back towards where it came from") {
        // Green (0.6) dragged onto blue (0.8) from below: ends just below 0.8.
        const std::size_t i = tf.movePoint(1, 0.8f);
        CHECK(i == 1);
        CHECK(tf.points()[1].value < 0.8f);
        CHECK(tf.points()[1].value == std::nextafter(0.8f, 0.0f));
        CHECK(tf.points()[2].value == 0.8f);
        // Red (0.2) dragged onto blue (0.8): 0.8 and the float below it are taken, so it lands
        // two floats below 0.8, i.e. first again, before green and blue.
        CHECK(tf.movePoint(0, 0.8f) == 0);
        CHECK(tf.points()[0].value == std::nextafter(std::nextafter(0.8f, 0.0f), 0.0f));
        CHECK(tf.points()[0].color == glm::vec3(1, 0, 0));
        const auto& p = tf.points();
        for (std::size_t k = 1; k < p.size(); ++k) CHECK(p[k].value > p[k - 1].value);
        // Blue dragged down onto the value it already has: no change.
        CHECK(tf.movePoint(2, 0.8f) == 2);
    }
    SECTION("setPoint and removePoint") {
        tf.setPoint(1, {0.5f, 0.5f, 0.5f}, 0.1f);
        requireNear(tf.evaluate(0.6f), {0.5f, 0.5f, 0.5f, 0.1f});
        CHECK(tf.revision() > rev);
        REQUIRE_SSS_ERROR(tf.setPoint(1, {0, 2, 0}, 0.1f), ErrorKind::InvalidArgument,
                          Contains("setPoint") && Contains("color"));
        REQUIRE_SSS_ERROR(tf.setPoint(1, {0, 0, 0}, kNaN), ErrorKind::InvalidArgument,
                          Contains("setPoint") && Contains("opacity"));
        REQUIRE_SSS_ERROR(tf.setPoint(9, {0, 0, 0}, 0), ErrorKind::InvalidArgument, Contains("index 9"));
        rev = tf.revision();
        tf.removePoint(1);
        CHECK(tf.points().size() == 2);
        CHECK(tf.revision() > rev);
        requireNear(tf.evaluate(0.5f), {0.5f, 0, 0.5f, 0.5f});
        tf.removePoint(0);
        REQUIRE_SSS_ERROR(tf.removePoint(0), ErrorKind::InvalidArgument, Contains("last remaining"));
        REQUIRE_SSS_ERROR(tf.removePoint(1), ErrorKind::InvalidArgument, Contains("index 1"));
        CHECK(tf.points().size() == 1);
    }
}

TEST_CASE("TransferFunction revisions differ between distinct functions", "[cpu]") {
    const TransferFunction a, b;
    CHECK(a.revision() != b.revision());
    TransferFunction c = a;
    CHECK(c.revision() == a.revision());  // same contents, same revision
    c.setPoint(0, {0, 0, 0}, 0.0f);
    CHECK(c.revision() != a.revision());
}

TEST_CASE("TransferFunction rejects bad control points", "[cpu]") {
    REQUIRE_SSS_ERROR(TransferFunction(std::vector<ControlPoint>{}), ErrorKind::InvalidArgument,
                      Contains("TransferFunction") && Contains("at least one"));
    REQUIRE_SSS_ERROR(TransferFunction({{0.0f, {0, 0, 0}, 0}, {0.5f, {0, 0, 0}, 0}, {0.4f, {0, 0, 0}, 0}}),
                      ErrorKind::InvalidArgument, Contains("point 2") && Contains("out of order"));
    REQUIRE_SSS_ERROR(TransferFunction({{0.5f, {0, 0, 0}, 0}, {0.5f, {0, 0, 0}, 0}}), ErrorKind::InvalidArgument,
                      Contains("point 1") && Contains("strictly increasing"));
    REQUIRE_SSS_ERROR(TransferFunction({{1.2f, {0, 0, 0}, 0}}), ErrorKind::InvalidArgument,
                      Contains("point 0") && Contains("value") && Contains("[0,1]"));
    REQUIRE_SSS_ERROR(TransferFunction({{0.0f, {0, 0, 0}, 0}, {0.5f, {0, -1, 0}, 0}}), ErrorKind::InvalidArgument,
                      Contains("point 1") && Contains("color"));
    REQUIRE_SSS_ERROR(TransferFunction({{0.0f, {0, 0, 0}, kNaN}}), ErrorKind::InvalidArgument,
                      Contains("point 0") && Contains("opacity"));
    REQUIRE_SSS_ERROR(TransferFunction({{kNaN, {0, 0, 0}, 0}}), ErrorKind::InvalidArgument,
                      Contains("point 0") && Contains("value"));
}

TEST_CASE("TransferFunction presets", "[cpu]") {
    const auto names = TransferFunction::presetNames();
    for (const char* required : {"ramp", "bucky", "bonsai", "ct-bone", "ct-skin", "engine"})
        CHECK(std::find(names.begin(), names.end(), required) != names.end());
    for (const std::string& name : names) {
        INFO(name);
        const TransferFunction tf = TransferFunction::preset(name);
        CHECK(tf.evaluate(0.0f).a == 0.0f);  // background / air is invisible
        float maxOpacity = 0.0f;
        for (const glm::vec4& e : tf.table()) maxOpacity = std::max(maxOpacity, e.a);
        CHECK(maxOpacity > 0.5f);
    }
    // 8-bit CT, floor((HU+1024)/16)/255: soft tissue (~40 HU) ~0.26, cortical bone (~1000 HU) ~0.5.
    const float softTissue = std::floor((40.0f + 1024.0f) / 16.0f) / 255.0f;
    const float bone = std::floor((1000.0f + 1024.0f) / 16.0f) / 255.0f;
    const float air = std::floor((-1000.0f + 1024.0f) / 16.0f) / 255.0f;
    const TransferFunction ctBone = TransferFunction::preset("ct-bone");
    CHECK(ctBone.evaluate(air).a == 0.0f);
    CHECK(ctBone.evaluate(softTissue).a == 0.0f);
    CHECK(ctBone.evaluate(bone).a > 0.5f);
    const TransferFunction ctSkin = TransferFunction::preset("ct-skin");
    CHECK(ctSkin.evaluate(air).a == 0.0f);
    CHECK(ctSkin.evaluate(softTissue).a > 0.2f);
    CHECK(ctSkin.evaluate(softTissue).r > ctSkin.evaluate(softTissue).b);  // skin is warm

    REQUIRE_SSS_ERROR(TransferFunction::preset("bunny"), ErrorKind::InvalidArgument,
                      Contains("\"bunny\"") && Contains("ramp") && Contains("ct-bone") && Contains("engine"));
}
