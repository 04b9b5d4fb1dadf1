#include "sss/camera.h"
#include "sss/error.h"
#include "sss/frame_accumulator.h"
#include "sss/light.h"

#include "test_helpers.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <cmath>
#include <limits>
#include <span>
#include <vector>

using Catch::Contains;
using sss::Camera;
using sss::Error;
using sss::FrameAccumulator;
using sss::Projection;
using sss::ErrorKind;

namespace {

glm::vec3 ndc(const glm::mat4& m, glm::vec3 p) {
    const glm::vec4 c = m * glm::vec4(p, 1.0f);
    return glm::vec3(c) / c.w;
}

void requireNear(glm::vec3 a, glm::vec3 b, float eps = 1e-4f) {
    INFO("a = (" << a.x << ", " << a.y << ", " << a.z << "), b = (" << b.x << ", " << b.y << ", " << b.z << ")");
    REQUIRE(glm::length(a - b) < eps);
}

const float kNaN = std::numeric_limits<float>::quiet_NaN();

}  // namespace

TEST_CASE("Default camera sits on +z looking at the origin", "[cpu]") {
    const Camera cam;
    CHECK(cam.distance() == 3.0f);
    CHECK(cam.fovY() == 45.0f);
    CHECK(cam.orthoHeight() == 2.0f);
    CHECK(cam.nearPlane() == 0.01f);
    CHECK(cam.farPlane() == 100.0f);
    CHECK(cam.projectionType() == sss::Projection::Perspective);
    requireNear(cam.position(), {0, 0, 3});
    requireNear(cam.forward(), {0, 0, -1});
    requireNear(cam.right(), {1, 0, 0});
    requireNear(cam.up(), {0, 1, 0});
    // The view matrix moves the eye to the origin and the target onto -z.
    requireNear(glm::vec3(cam.view() * glm::vec4(cam.position(), 1.0f)), {0, 0, 0});
    requireNear(glm::vec3(cam.view() * glm::vec4(cam.target(), 1.0f)), {0, 0, -3});
}

TEST_CASE("Camera orbit keeps the distance and follows yaw/pitch", "[cpu]") {
    Camera cam;
    cam.setTarget({1, 2, 3});
    cam.orbit(90.0f, 0.0f);
    requireNear(cam.position(), {4, 2, 3});  // yaw +90 turns the eye towards +x
    cam.orbit(-90.0f, 30.0f);
    CHECK(glm::length(cam.position() - cam.target()) == Approx(3.0f));
    CHECK(cam.position().y > 2.0f);  // positive pitch lifts the eye
    CHECK(cam.position().y - 2.0f == Approx(3.0f * std::sin(glm::radians(30.0f))));
    requireNear(glm::vec3(cam.view() * glm::vec4(cam.position(), 1.0f)), {0, 0, 0});

    cam.orbit(0.0f, 500.0f);
    CHECK(cam.pitch() == 89.0f);
    cam.orbit(0.0f, -1000.0f);
    CHECK(cam.pitch() == -89.0f);
    cam.orbit(725.0f, 0.0f);
    CHECK(cam.yaw() == Approx(5.0f));
    for (int i = 0; i < 37; ++i) cam.orbit(13.0f, 7.0f);
    CHECK(glm::length(cam.position() - cam.target()) == Approx(3.0f));
    REQUIRE_SSS_ERROR(cam.orbit(kNaN, 0.0f), ErrorKind::InvalidArgument, Contains("dYawDeg"));
}

TEST_CASE("Camera projections follow OpenGL clip conventions", "[cpu]") {
    Camera cam;
    cam.setClipPlanes(0.5f, 10.0f);
    const float aspect = 2.0f;

    SECTION("perspective") {
        const glm::mat4 p = cam.projection(aspect);
        CHECK(ndc(p, {0, 0, -0.5f}).z == Approx(-1.0f));
        CHECK(ndc(p, {0, 0, -10.0f}).z == Approx(1.0f));
        // Top of the frustum at depth d is d * tan(fov/2).
        const float t = std::tan(glm::radians(22.5f));
        CHECK(ndc(p, {0, 2.0f * t, -2.0f}).y == Approx(1.0f));
        CHECK(ndc(p, {2.0f * t * aspect, 0, -2.0f}).x == Approx(1.0f));
        // Farther points shrink towards the centre.
        CHECK(ndc(p, {1, 0, -4.0f}).x == Approx(0.5f * ndc(p, {1, 0, -2.0f}).x));
    }
    SECTION("orthographic") {
        cam.setProjectionType(sss::Projection::Orthographic);
        cam.setOrthoHeight(4.0f);
        const glm::mat4 p = cam.projection(aspect);
        CHECK(ndc(p, {0, 0, -0.5f}).z == Approx(-1.0f));
        CHECK(ndc(p, {0, 0, -10.0f}).z == Approx(1.0f));
        CHECK(ndc(p, {0, 2, -3}).y == Approx(1.0f));
        CHECK(ndc(p, {4, 0, -3}).x == Approx(1.0f));
        // No foreshortening.
        CHECK(ndc(p, {1, 0, -4.0f}).x == Approx(ndc(p, {1, 0, -2.0f}).x));
    }
    REQUIRE_SSS_ERROR(cam.projection(0.0f), ErrorKind::InvalidArgument, Contains("aspect") && Contains("> 0"));
    REQUIRE_SSS_ERROR(cam.projection(-1.0f), ErrorKind::InvalidArgument, Contains("aspect"));
    REQUIRE_SSS_ERROR(cam.projection(kNaN), ErrorKind::InvalidArgument, Contains("aspect"));
    REQUIRE_SSS_ERROR(cam.projection(std::numeric_limits<float>::infinity()), ErrorKind::InvalidArgument,
                      Contains("aspect"));
}

TEST_CASE("Camera zoom and pan", "[cpu]") {
    Camera cam;
    cam.zoom(0.5f);
    CHECK(cam.distance() == Approx(1.5f));
    CHECK(cam.orthoHeight() == Approx(1.0f));
    for (int i = 0; i < 200; ++i) cam.zoom(0.1f);
    CHECK(cam.distance() > 0.0f);
    REQUIRE_SSS_ERROR(cam.zoom(0.0f), ErrorKind::InvalidArgument, Contains("factor"));
    REQUIRE_SSS_ERROR(cam.zoom(-2.0f), ErrorKind::InvalidArgument, Contains("factor"));

    Camera p;
    p.orbit(90.0f, 0.0f);  // eye on +x, right is -z
    const glm::vec3 forwardBefore = p.forward();
    p.pan({0.5f, 0.25f});
    requireNear(p.target(), glm::vec3(0, 0.75f, -1.5f));
    requireNear(p.forward(), forwardBefore);
    CHECK(p.distance() == 3.0f);
}

TEST_CASE("Camera::frame fits the bounding sphere in the vertical fov", "[cpu]") {
    Camera cam;
    cam.orbit(30.0f, 20.0f);
    sss::Bounds b;
    b.extend({1, 2, 3});
    b.extend({3, 5, 4});
    cam.frame(b);
    requireNear(cam.target(), b.center());
    const float r = b.radius();
    CHECK(cam.distance() == Approx(r / std::sin(glm::radians(22.5f))));
    CHECK(cam.nearPlane() > 0.0f);
    CHECK(cam.nearPlane() < cam.distance() - r);
    CHECK(cam.farPlane() > cam.distance() + r);
    CHECK(cam.yaw() == Approx(30.0f));
    // Every corner of the box is inside the view volume.
    const glm::mat4 vp = cam.projection(1.0f) * cam.view();
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y, (i & 4) ? b.max.z : b.min.z);
        const glm::vec3 n = ndc(vp, corner);
        CHECK(std::abs(n.x) <= 1.0f);
        CHECK(std::abs(n.y) <= 1.0f);
        CHECK(std::abs(n.z) <= 1.0f);
    }
    // The sphere touches the top of the frustum: the tangent point lies on ndc y = 1.
    const float halfFov = glm::radians(22.5f);
    const glm::vec3 toTarget = cam.forward();
    const glm::vec3 tangentDir = std::cos(halfFov) * toTarget + std::sin(halfFov) * cam.up();
    const glm::vec3 tangent = cam.position() + tangentDir * (cam.distance() * std::cos(halfFov));
    CHECK(glm::length(tangent - b.center()) == Approx(r));
    CHECK(ndc(vp, tangent).y == Approx(1.0f));

    REQUIRE_SSS_ERROR(cam.frame(sss::Bounds{}), ErrorKind::InvalidArgument, Contains("Camera::frame") && Contains("empty"));
}

TEST_CASE("Camera::frameTight fills the view with the box's projection", "[cpu]") {
    sss::Bounds b;
    b.extend({-0.9f, 0.3f, -0.6f});
    b.extend({0.6f, 1.9f, 0.6f});  // a bunny-like box, taller than deep
    struct Case {
        float yaw, pitch, aspect, margin;
        sss::Projection projection;
    };
    for (const Case k : {Case{30, 20, 16.0f / 9.0f, 0.05f, sss::Projection::Perspective},
                         Case{-120, -35, 0.5f, 0.0f, sss::Projection::Perspective},
                         Case{0, 0, 1.0f, 0.1f, sss::Projection::Perspective},
                         Case{30, 20, 16.0f / 9.0f, 0.05f, sss::Projection::Orthographic},
                         Case{75, 60, 0.7f, 0.2f, sss::Projection::Orthographic}}) {
        INFO("yaw " << k.yaw << ", pitch " << k.pitch << ", aspect " << k.aspect << ", margin " << k.margin);
        Camera cam;
        cam.orbit(k.yaw, k.pitch);
        cam.setProjectionType(k.projection);
        cam.frameTight(b, k.aspect, k.margin);
        CHECK(cam.yaw() == Approx(k.yaw));
        CHECK(cam.pitch() == Approx(k.pitch));
        const glm::mat4 vp = cam.projection(k.aspect) * cam.view();
        glm::vec2 lo(1e9f), hi(-1e9f);
        for (int i = 0; i < 8; ++i) {
            const glm::vec3 corner((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y,
                                   (i & 4) ? b.max.z : b.min.z);
            const glm::vec3 n = ndc(vp, corner);
            CHECK(std::abs(n.z) < 1.0f);  // between near and far
            lo = glm::min(lo, glm::vec2(n));
            hi = glm::max(hi, glm::vec2(n));
        }
        const float limit = 1.0f - k.margin;
        // Inside the view with the margin, touching it on both sides of one axis.
        CHECK(lo.x >= -limit - 1e-4f);
        CHECK(lo.y >= -limit - 1e-4f);
        CHECK(hi.x <= limit + 1e-4f);
        CHECK(hi.y <= limit + 1e-4f);
        const bool fillsX = std::abs(hi.x - limit) < 1e-3f && std::abs(lo.x + limit) < 1e-3f;
        const bool fillsY = std::abs(hi.y - limit) < 1e-3f && std::abs(lo.y + limit) < 1e-3f;
        CHECK((fillsX || fillsY));
        // Roughly centred on the other axis too (exactly in orthographic projection).
        CHECK(std::abs(hi.x + lo.x) < 0.1f);
        CHECK(std::abs(hi.y + lo.y) < 0.1f);
    }

    // A wide subject (a dragon-like box) in a wide view: the sphere fit of frame() leaves most
    // of the image empty; frameTight() makes the box's projection over 1.5 times as large (here 1.85).
    sss::Bounds wide;
    wide.extend({-7.0f, 0.0f, -3.2f});
    wide.extend({7.0f, 9.9f, 3.2f});
    auto projectedArea = [&](const Camera& cam) {
        const glm::mat4 vp = cam.projection(16.0f / 9.0f) * cam.view();
        glm::vec2 lo(1e9f), hi(-1e9f);
        for (int i = 0; i < 8; ++i) {
            const glm::vec3 n = ndc(vp, glm::vec3((i & 1) ? wide.max.x : wide.min.x, (i & 2) ? wide.max.y : wide.min.y,
                                                  (i & 4) ? wide.max.z : wide.min.z));
            lo = glm::min(lo, glm::vec2(n));
            hi = glm::max(hi, glm::vec2(n));
        }
        return (hi.x - lo.x) * (hi.y - lo.y);
    };
    Camera loose, tight;
    loose.orbit(30, 20);
    tight.orbit(30, 20);
    loose.frame(wide);
    tight.frameTight(wide, 16.0f / 9.0f);
    CHECK(projectedArea(tight) > 1.5f * projectedArea(loose));

    // Points (a ring, like a torus's outline) rather than their box: the ring touches the view.
    std::vector<glm::vec3> ring;
    for (int i = 0; i < 64; ++i) {
        const float t = glm::radians(360.0f * float(i) / 64.0f);
        ring.push_back({std::cos(t), 0.3f * float(i % 2), std::sin(t)});
    }
    for (const sss::Projection projection : {sss::Projection::Perspective, sss::Projection::Orthographic}) {
        Camera cam;
        cam.orbit(30, 20);
        cam.setProjectionType(projection);
        cam.frameTight(std::span<const glm::vec3>(ring), 2.0f, 0.05f);
        const glm::mat4 vp = cam.projection(2.0f) * cam.view();
        glm::vec2 lo(1e9f), hi(-1e9f);
        for (const glm::vec3& p : ring) {
            const glm::vec3 n = ndc(vp, p);
            CHECK(std::abs(n.z) < 1.0f);
            lo = glm::min(lo, glm::vec2(n));
            hi = glm::max(hi, glm::vec2(n));
        }
        CHECK(std::max({hi.x, hi.y, -lo.x, -lo.y}) == Approx(0.95f).margin(1e-3));
        CHECK(std::min(hi.x - lo.x, hi.y - lo.y) > 0.5f);
    }

    Camera cam;
    cam.frameTight(b, 1.0f);
    REQUIRE_SSS_ERROR(cam.frameTight(std::span<const glm::vec3>(), 1.0f), ErrorKind::InvalidArgument,
                      Contains("no points"));
    const glm::vec3 line[2] = {{0, 0, -1}, {0, 0, 1}};  // along the default view axis
    cam.frameTight(std::span<const glm::vec3>(line), 1.0f);
    CHECK(cam.nearPlane() > 0.0f);
    CHECK(glm::dot(line[1] - cam.position(), cam.forward()) > cam.nearPlane());
    REQUIRE_SSS_ERROR(cam.frameTight(sss::Bounds{}, 1.0f), ErrorKind::InvalidArgument,
                      Contains("Camera::frameTight") && Contains("empty"));
    REQUIRE_SSS_ERROR(cam.frameTight(b, 0.0f), ErrorKind::InvalidArgument, Contains("aspect"));
    REQUIRE_SSS_ERROR(cam.frameTight(b, 1.0f, 0.7f), ErrorKind::InvalidArgument, Contains("margin"));
    sss::Bounds point;
    point.extend({1, 2, 3});
    cam.frameTight(point, 1.0f);  // a point-like box still gives a valid camera
    CHECK(cam.nearPlane() > 0.0f);
    CHECK(cam.nearPlane() < cam.distance());
}

TEST_CASE("Camera setters validate", "[cpu]") {
    Camera cam;
    REQUIRE_SSS_ERROR(cam.setDistance(0.0f), ErrorKind::InvalidArgument, Contains("distance") && Contains("> 0"));
    REQUIRE_SSS_ERROR(cam.setFovY(180.0f), ErrorKind::InvalidArgument, Contains("fovY") && Contains("(0, 180)"));
    REQUIRE_SSS_ERROR(cam.setFovY(0.0f), ErrorKind::InvalidArgument, Contains("fovY"));
    REQUIRE_SSS_ERROR(cam.setOrthoHeight(-1.0f), ErrorKind::InvalidArgument, Contains("orthoHeight"));
    REQUIRE_SSS_ERROR(cam.setClipPlanes(0.0f, 1.0f), ErrorKind::InvalidArgument, Contains("near"));
    REQUIRE_SSS_ERROR(cam.setClipPlanes(2.0f, 1.0f), ErrorKind::InvalidArgument,
                      Contains("far must be > near") && Contains("near 2") && Contains("far 1"));
    REQUIRE_SSS_ERROR(cam.setTarget({kNaN, 0, 0}), ErrorKind::InvalidArgument, Contains("target"));
    // Nothing changed after the failures.
    CHECK(cam.distance() == 3.0f);
    CHECK(cam.nearPlane() == 0.01f);
    CHECK(cam.farPlane() == 100.0f);
    cam.setPitch(120.0f);
    CHECK(cam.pitch() == 89.0f);
    cam.setYaw(270.0f);
    CHECK(cam.yaw() == Approx(-90.0f));
    requireNear(cam.position(), {0, 3.0f * std::sin(glm::radians(89.0f)), 0}, 0.1f);
}

TEST_CASE("validateLight rejects unusable lights", "[cpu]") {
    CHECK_NOTHROW(sss::validateLight(sss::DirectionalLight{}, "key"));
    CHECK_NOTHROW(sss::validateLight(sss::PointLight{}, "key"));
    sss::DirectionalLight d;
    d.direction = glm::vec3(0.0f);
    REQUIRE_SSS_ERROR(sss::validateLight(d, "Scene::light"), ErrorKind::InvalidArgument,
                      Contains("Scene::light") && Contains("direction") && Contains("non-zero"));
    d.direction = glm::vec3(kNaN, 0, 1);
    REQUIRE_SSS_ERROR(sss::validateLight(d, "Scene::light"), ErrorKind::InvalidArgument, Contains("direction"));
    d.direction = glm::vec3(0, 0, -5);
    d.color = glm::vec3(1, -0.1f, 1);
    REQUIRE_SSS_ERROR(sss::validateLight(d, "Scene::light"), ErrorKind::InvalidArgument,
                      Contains("Scene::light") && Contains("DirectionalLight::color"));
    sss::PointLight p;
    p.intensity = -1.0f;
    REQUIRE_SSS_ERROR(sss::validateLight(p, "fill"), ErrorKind::InvalidArgument,
                      Contains("fill") && Contains("PointLight::intensity") && Contains("-1"));
    p.intensity = std::numeric_limits<float>::infinity();
    REQUIRE_SSS_ERROR(sss::validateLight(p, "fill"), ErrorKind::InvalidArgument, Contains("intensity"));
    p.intensity = 1.0f;
    p.position.x = kNaN;
    REQUIRE_SSS_ERROR(sss::validateLight(p, "fill"), ErrorKind::InvalidArgument, Contains("PointLight::position"));
}

TEST_CASE("a sub-pixel offset shifts the image in NDC without moving the camera", "[camera][aa]") {
    for (Projection kind : {Projection::Perspective, Projection::Orthographic}) {
        Camera camera;
        camera.setProjectionType(kind);
        const glm::vec4 point(0.3f, -0.2f, 0.1f, 1.0f);
        const glm::vec4 a = camera.projection(1.5f) * camera.view() * point;
        camera.setSubpixelOffset({0.01f, -0.02f});
        const glm::vec4 b = camera.projection(1.5f) * camera.view() * point;
        CHECK(b.x / b.w - a.x / a.w == Approx(0.01f).margin(1e-6));
        CHECK(b.y / b.w - a.y / a.w == Approx(-0.02f).margin(1e-6));
        CHECK(b.z / b.w == Approx(a.z / a.w).margin(1e-7));
        CHECK(camera.position() == Camera().position());
    }
    Camera camera;
    CHECK_THROWS_AS(camera.setSubpixelOffset({std::nanf(""), 0.0f}), Error);
}

TEST_CASE("anti-aliasing offsets cover the pixel around its centre, frame 0 at the centre", "[camera][aa]") {
    CHECK(FrameAccumulator::subpixelOffset(0, 100, 50) == glm::vec2(0.0f));
    glm::vec2 mean(0.0f);
    for (int i = 0; i < 64; ++i) {
        const glm::vec2 o = FrameAccumulator::subpixelOffset(i, 100, 50) * glm::vec2(50.0f, 25.0f);  // in pixels
        CHECK(o.x >= -0.5f);
        CHECK(o.x < 0.5f);
        CHECK(o.y >= -0.5f);
        CHECK(o.y < 0.5f);
        mean += o / 64.0f;
    }
    // Low-discrepancy: the 64 offsets average out near the centre.
    CHECK(glm::length(mean) < 0.05f);
    CHECK(FrameAccumulator::subpixelOffset(1, 100, 50) != FrameAccumulator::subpixelOffset(2, 100, 50));
    CHECK_THROWS_AS(FrameAccumulator::subpixelOffset(-1, 100, 50), Error);
}
