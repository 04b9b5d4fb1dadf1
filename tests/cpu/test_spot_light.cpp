// Spot lights on the CPU: validation of their fields, the cone's fall-off, and the CPU renderers
// (mesh reference, mesh random walk, volume reference, volume path tracer), where a spot light
// must act as the point light at its position inside its cone and send nothing outside it.
#include "test_helpers.h"

#include <sss/light.h>
#include <sss/materials.h>
#include <sss/mesh_reference.h>
#include <sss/procedural.h>
#include <sss/random_walk.h>
#include <sss/volume_path_tracer.h>
#include <sss/volume_reference.h>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <vector>

using Catch::Contains;
using namespace sss;

namespace {

// A spot light at `position` aimed at `target`, and the point light it must equal in its cone.
SpotLight spotAt(glm::vec3 position, glm::vec3 target, float coneAngle, float falloff) {
    SpotLight s;
    s.position = position;
    s.direction = target - position;
    s.coneAngle = coneAngle;
    s.falloff = falloff;
    s.color = {1.0f, 0.9f, 0.8f};
    s.intensity = 4.0f;
    return s;
}
PointLight pointOf(const SpotLight& s) { return PointLight{s.position, s.color, s.intensity}; }

bool sameImage(const Image& a, const Image& b) { return a.data() == b.data(); }

double maxRgb(const Image& image) {
    double m = 0.0;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) m = std::max({m, double(image.at(x, y).r), double(image.at(x, y).g),
                                                              double(image.at(x, y).b)});
    return m;
}

}  // namespace

TEST_CASE("validateLight rejects bad spot-light fields, naming the field", "[cpu][spot]") {
    CHECK_NOTHROW(validateLight(SpotLight{}, "key"));
    CHECK_NOTHROW(validateLight(SpotLight{.coneAngle = 90.0f, .falloff = 1.0f}, "key"));
    CHECK_NOTHROW(validateLight(SpotLight{.falloff = 0.0f}, "key"));
    REQUIRE_SSS_ERROR(validateLight(SpotLight{.coneAngle = 0.0f}, "spot"), ErrorKind::InvalidArgument,
                      Contains("spot") && Contains("SpotLight::coneAngle") && Contains("got 0"));
    REQUIRE_SSS_ERROR(validateLight(SpotLight{.coneAngle = 95.0f}, "spot"), ErrorKind::InvalidArgument,
                      Contains("SpotLight::coneAngle") && Contains("95"));
    REQUIRE_SSS_ERROR(validateLight(SpotLight{.coneAngle = std::numeric_limits<float>::quiet_NaN()}, "spot"),
                      ErrorKind::InvalidArgument, Contains("SpotLight::coneAngle"));
    REQUIRE_SSS_ERROR(validateLight(SpotLight{.falloff = -0.1f}, "spot"), ErrorKind::InvalidArgument,
                      Contains("SpotLight::falloff") && Contains("-0.1"));
    REQUIRE_SSS_ERROR(validateLight(SpotLight{.falloff = 1.5f}, "spot"), ErrorKind::InvalidArgument,
                      Contains("SpotLight::falloff"));
    REQUIRE_SSS_ERROR(validateLight(SpotLight{.direction = glm::vec3(0.0f)}, "spot"), ErrorKind::InvalidArgument,
                      Contains("SpotLight::direction") && Contains("non-zero"));
    REQUIRE_SSS_ERROR(validateLight(SpotLight{.position = glm::vec3(std::numeric_limits<float>::infinity())}, "spot"),
                      ErrorKind::InvalidArgument, Contains("SpotLight::position"));
    REQUIRE_SSS_ERROR(validateLight(SpotLight{.intensity = -1.0f}, "spot"), ErrorKind::InvalidArgument,
                      Contains("SpotLight::intensity"));
}

TEST_CASE("spotConeFactor: 1 in the inner cone, 0 outside the outer one, smooth between", "[cpu][spot]") {
    const SpotLight s{.coneAngle = 40.0f, .falloff = 0.5f};  // inner cone 20 degrees
    const auto at = [&](float degrees) { return spotConeFactor(s, std::cos(glm::radians(degrees))); };
    CHECK(at(0.0f) == 1.0f);
    CHECK(at(19.9f) == 1.0f);
    CHECK(at(40.1f) == 0.0f);
    CHECK(at(120.0f) == 0.0f);
    // In the band: strictly between, falling with the angle; smoothstep in the cosine is 1/2
    // where the cosine is halfway between the cones' cosines.
    float previous = 1.0f;
    for (float a = 21.0f; a < 40.0f; a += 1.0f) {
        const float f = at(a);
        CHECK(f > 0.0f);
        CHECK(f < previous);
        previous = f;
    }
    const float halfway = 0.5f * (std::cos(glm::radians(40.0f)) + std::cos(glm::radians(20.0f)));
    CHECK(spotConeFactor(s, halfway) == Approx(0.5f).margin(1e-6f));
    // falloff 0: a hard edge at the cone.
    const SpotLight hard{.coneAngle = 30.0f, .falloff = 0.0f};
    CHECK(spotConeFactor(hard, std::cos(glm::radians(29.9f))) == 1.0f);
    CHECK(spotConeFactor(hard, std::cos(glm::radians(30.1f))) == 0.0f);
}

TEST_CASE("volume reference: a spot light's incident light is the point light's times its cone factor",
          "[cpu][spot]") {
    // A uniform, absorbing box; the spot above it aims straight down. Transmittance and
    // chromaticity do not depend on the cone; the radiance is the point light's times
    // spotConeFactor at the angle to the axis (both are double computations of the same thing,
    // so they agree to rounding: 1e-12 relative).
    const int n = 16;
    const Volume volume =
        Volume::fromData({n, n, n}, VoxelType::UInt8, std::vector<uint8_t>(static_cast<size_t>(n * n * n), 128));
    const TransferFunction tf({{0.0f, {0.9f, 0.7f, 0.5f}, 0.05f}, {1.0f, {0.9f, 0.7f, 0.5f}, 0.05f}});
    const SpotLight spot = spotAt({0.0f, 0.0f, 3.0f}, {0.0f, 0.0f, 0.0f}, 10.0f, 0.5f);  // inner cone 5 degrees
    const VolumeReference withSpot(volume, tf, 256, glm::mat4(1.0f), {spot});
    const VolumeReference withPoint(volume, tf, 256, glm::mat4(1.0f), {pointOf(spot)});
    int inside = 0, band = 0, outside = 0;
    for (const glm::dvec3 p : {glm::dvec3(0.0, 0.0, 0.5), glm::dvec3(0.1, 0.0, 0.5), glm::dvec3(0.3, 0.0, 0.5),
                               glm::dvec3(0.4, 0.0, 0.5), glm::dvec3(0.48, 0.0, 0.5), glm::dvec3(0.3, 0.3, 0.0),
                               glm::dvec3(0.45, 0.45, -0.4), glm::dvec3(-0.05, 0.1, -0.45)}) {
        const ReferenceLightSample a = withSpot.incidentLight(p, 0), b = withPoint.incidentLight(p, 0);
        const glm::dvec3 fromLight = glm::normalize(p - glm::dvec3(spot.position));
        const double f = spotConeFactor(spot, static_cast<float>(-fromLight.z));
        INFO("point (" << p.x << ", " << p.y << ", " << p.z << "), cone factor " << f);
        inside += f == 1.0;
        outside += f == 0.0;
        band += f > 0.0 && f < 1.0;
        CHECK(a.transmittance == b.transmittance);
        CHECK(a.chromaticity == b.chromaticity);
        for (int c = 0; c < 3; ++c) CHECK(a.radiance[c] == Approx(b.radiance[c] * f).epsilon(1e-12).margin(0.0));
    }
    CHECK(inside == 3);
    CHECK(band == 3);
    CHECK(outside == 2);
}

TEST_CASE("volume path tracer: a spot light holding the box in its inner cone is its point light, and aimed away, black",
          "[cpu][spot]") {
    const Volume volume = makeBlobsVolume(16);
    const glm::vec3 white(1.0f);
    const TransferFunction tf({{0.0f, white, 0.0f}, {0.15f, white, 0.02f}, {1.0f, white, 0.5f}});
    Camera camera;
    camera.frameTight(volume.worldBounds(), 1.0f, 0.02f);
    VolumePathTracerOptions options;
    options.samplesPerPixel = 16;
    options.threads = 2;
    // The box (half-diagonal 0.87) seen from 4 units away fills 12.5 degrees: inside 20.
    const SpotLight wide = spotAt({1.0f, 2.0f, 3.0f}, {0.0f, 0.0f, 0.0f}, 40.0f, 0.5f);
    const auto render = [&](const Light& light) {
        return renderVolumePathTraced(volume, tf, 256, glm::mat4(1.0f), {light}, camera, 12, 12, options).image;
    };
    const Image point = render(pointOf(wide));
    REQUIRE(maxRgb(point) > 0.0);
    // Same seed, same paths; every cone factor is exactly 1.
    CHECK(sameImage(render(wide), point));
    SpotLight away = wide;
    away.direction = -away.direction;
    const Image dark = render(away);
    CHECK(maxRgb(dark) == 0.0);
}

TEST_CASE("mesh random walk: a spot light holding the box in its inner cone is its point light, and aimed away, black",
          "[cpu][spot]") {
    ScatteringMaterial m;
    m.sigmaS = {0.9, 0.8, 0.7};
    m.sigmaA = {0.1, 0.2, 0.3};
    m.eta = 1.3;
    m.name = "test";
    Camera camera;  // at (0, 0, 3) looking along -z, at the middle of the slab's top face
    camera.setProjectionType(Projection::Orthographic);
    camera.setOrthoHeight(0.1f);
    MeshRandomWalkOptions options;
    options.pathsPerPixel = 64;
    options.millimetresPerUnit = 40.0;
    options.threads = 2;
    const Mesh slab = makeSlab({1.0f, 1.0f, 0.5f});
    const auto render = [&](const Light& light) {
        return renderMeshRandomWalk(slab, glm::mat4(1.0f), m, {light}, camera, 4, 4, options).image;
    };
    const SpotLight wide = spotAt({0.2f, 0.1f, 2.0f}, {0.0f, 0.0f, 0.0f}, 60.0f, 0.2f);  // the face is within 25 degrees
    const Image point = render(pointOf(wide));
    REQUIRE(maxRgb(point) > 0.0);
    CHECK(sameImage(render(wide), point));
    SpotLight away = wide;
    away.direction = -away.direction;
    CHECK(maxRgb(render(away)) == 0.0);
}

TEST_CASE("mesh reference: a spot light lights a sphere like its point light inside its cone, not outside",
          "[cpu][spot]") {
    // The spot sits at the camera, (0, 0, 3), aimed at the unit sphere's centre with a hard
    // 8-degree edge, so each pixel's angle to the cone axis is its view ray's. Potato at
    // 1000 mm per unit scatters over about 0.015 units (1 / sigma_tr, red); 4 degrees from the
    // edge is 0.14 units of surface, about 10 of those lengths.
    const Mesh sphere = makeUvSphere(32, 24, 1.0f);
    const ScatteringMaterial material = materialPreset("potato");
    const Camera camera;
    MeshReferenceOptions options;
    options.millimetresPerUnit = 1000.0;
    options.absoluteError = 1e-4;
    options.targetRelativeError = 0.05;
    options.threads = 2;
    const SpotLight spot = spotAt(camera.position(), camera.target(), 8.0f, 0.0f);
    const int size = 32;
    const MeshReferenceResult s =
        renderMeshReference(sphere, glm::mat4(1.0f), material, {spot}, camera, size, size, options);
    const MeshReferenceResult p =
        renderMeshReference(sphere, glm::mat4(1.0f), material, {pointOf(spot)}, camera, size, size, options);
    const double tanHalfFov = std::tan(glm::radians(camera.fovY()) / 2.0);
    int inside = 0, outside = 0;
    double worstInside = 0.0, worstOutside = 0.0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            if (p.image.at(x, y).a < 1.0f) continue;
            const glm::dvec2 ndc((x + 0.5) / size * 2.0 - 1.0, 1.0 - (y + 0.5) / size * 2.0);
            const double angle = glm::degrees(std::atan(glm::length(ndc) * tanHalfFov));
            for (int c = 0; c < 3; ++c) {
                const double vs = s.image.at(x, y)[c], vp = p.image.at(x, y)[c];
                if (angle < 4.0) {
                    // Both estimates take the same samples; they differ by what lands outside the cone.
                    const double se = std::hypot(double(s.standardError.at(x, y)[c]), double(p.standardError.at(x, y)[c]));
                    worstInside = std::max(worstInside, std::abs(vs - vp) / std::max(se, 1e-12));
                    inside += c == 0;
                } else if (angle > 12.0) {
                    worstOutside = std::max(worstOutside, vs / std::max(vp, 1e-12));
                    outside += c == 0;
                }
            }
        }
    std::printf("mesh reference spot vs point: %d pixels inside (worst |difference| %.3g standard errors), "
                "%d outside (worst spot / point %.3g)\n",
                inside, worstInside, outside, worstOutside);
    CHECK(inside >= 8);
    CHECK(outside >= 50);
    // Measured: inside 1.1e-5 standard errors apart, outside 1.4e-12 of the point light.
    CHECK(worstInside <= 4.0);
    CHECK(worstOutside <= 1e-6);
}
