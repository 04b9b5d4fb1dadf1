// Spot lights on the GPU: the GLSL cone factor against the C++ one, an analytic Blinn-Phong plane
// under a spot, the volume renderers (light volume and path tracer) lighting only the cone, the
// translucent mesh renderer, and the hybrid shadow maps from a spot.
#include "support/gl_test.h"

#include "gl/buffer.h"
#include "gl/program.h"
#include "core/light_geometry.h"
#include "lighting/light_uniforms.h"

#include <catch2/catch.hpp>
#include <sss/hybrid_compositor.h>
#include <sss/materials.h>
#include <sss/mesh_scattering_renderer.h>
#include <sss/procedural.h>
#include <sss/volume_scattering_renderer.h>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

using namespace sss;

namespace {

constexpr const char* kTwinPath = "test/spot_twin.comp";

// Test-only shader: lights.glsl as every mesh and volume shader includes it, fed by
// setLightUniforms(). Per query: the radiance lightDirectionAt() gives at a point, and the bare
// spotConeFactor() of a given cosine with the light's uploaded cosines.
constexpr const char* kTwinSource = R"(
#include "common/lights.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Queries { vec4 queries[]; };  // xyz point, w light; then (cos, light)
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };
uniform uint queryCount;
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= queryCount) return;
    vec4 q = queries[2u * i], c = queries[2u * i + 1u];
    vec3 radiance;
    lightDirectionAt(int(q.w), q.xyz, radiance);
    results[i] = vec4(radiance, spotConeFactor(lightSpotCosines[int(c.y)], c.x));
}
)";

std::string loadTwinShader(std::string_view path) {
    if (path == kTwinPath) return kTwinSource;
    return detail::loadShaderFile(path);
}

SpotLight spotAt(glm::vec3 position, glm::vec3 target, float coneAngle, float falloff, float intensity = 1.0f) {
    SpotLight s;
    s.position = position;
    s.direction = target - position;
    s.coneAngle = coneAngle;
    s.falloff = falloff;
    s.intensity = intensity;
    return s;
}
PointLight pointOf(const SpotLight& s) { return PointLight{s.position, s.color, s.intensity}; }

double maxRgb(const Image& image, int x, int y) {
    const glm::vec4 p = image.at(x, y);
    return std::max({double(p.r), double(p.g), double(p.b)});
}

// The cone factor seen from a world point (C++ side).
float coneFactorAt(const SpotLight& s, glm::vec3 point) {
    return spotConeFactor(s, glm::dot(glm::normalize(point - s.position), glm::normalize(s.direction)));
}

}  // namespace

TEST_CASE("the GLSL spot cone factor and lightDirectionAt equal the C++ spotConeFactor", "[gl][spot]") {
    test::GlTestScope gl;
    const std::vector<Light> lights{
        spotAt({0.0f, 2.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, 30.0f, 0.2f, 2.0f),
        spotAt({1.0f, 0.5f, -1.0f}, {0.0f, 0.0f, 0.0f}, 10.0f, 0.0f),  // hard edge
        spotAt({-1.0f, 0.0f, 0.5f}, {0.0f, 1.0f, 0.0f}, 90.0f, 1.0f),  // a hemisphere, fading from the axis
        spotAt({0.3f, -1.0f, 0.2f}, {0.3f, 1.0f, 0.0f}, 60.0f, 0.5f),
        spotAt({0.0f, 0.0f, 2.0f}, {0.1f, 0.0f, 0.0f}, 5.0f, 1.0f),
        spotAt({2.0f, 2.0f, 2.0f}, {0.0f, 0.0f, 0.0f}, 45.0f, 0.05f),  // a narrow band
        PointLight{{0.5f, 1.5f, 0.5f}, {1.0f, 0.5f, 0.25f}, 3.0f},
        SpotLight{.position = {0.0f, 1.0f, 0.0f}, .direction = {0.0f, -3.0f, 0.0f}},  // an axis to normalize
    };
    const int perLight = 4000;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> coord(-1.5f, 1.5f);
    std::vector<glm::vec4> queries;
    for (int l = 0; l < int(lights.size()); ++l)
        for (int k = 0; k < perLight; ++k) {
            queries.emplace_back(coord(rng), coord(rng), coord(rng), float(l));
            queries.emplace_back(-1.0f + 2.0f * float(k) / float(perLight - 1), float(l), 0.0f, 0.0f);
        }
    const GLuint count = GLuint(queries.size() / 2);

    const gl::Program program = gl::Program::link({{GL_COMPUTE_SHADER, kTwinPath}}, {}, &loadTwinShader);
    detail::setLightUniforms(program, lights);
    program.set("queryCount", unsigned(count));
    const gl::Buffer queryBuffer = gl::Buffer::create(queries.size() * sizeof(glm::vec4), queries.data(), 0, "queries");
    const gl::Buffer resultBuffer = gl::Buffer::create(count * sizeof(glm::vec4), nullptr, 0, "results");
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, queryBuffer.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, resultBuffer.id());
    program.use();
    glDispatchCompute((count + 63) / 64, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::vec4> results(count);
    glGetNamedBufferSubData(resultBuffer.id(), 0, GLsizeiptr(results.size() * sizeof(glm::vec4)), results.data());
    glUseProgram(0);
    for (GLuint b = 0; b < 2; ++b) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, 0);

    // Radiance relative to the point light's I / d^2 (the cone factor is what differs); points
    // within 1e-5 of a cone's cosine are left out, where float rounding of the cosine may put
    // them on the other side of a hard edge.
    double worstFactor = 0.0, worstRadiance = 0.0;
    int compared = 0, band = 0, dark = 0;
    for (GLuint i = 0; i < count; ++i) {
        const int l = int(queries[2 * i].w);
        const glm::vec3 point(queries[2 * i]);
        const float cosine = queries[2 * i + 1].x;
        const auto* spot = std::get_if<SpotLight>(&lights[l]);
        const float factor = spot ? spotConeFactor(*spot, cosine) : 1.0f;
        INFO("light " << l << ", cosine " << cosine);
        worstFactor = std::max(worstFactor, std::abs(double(results[i].w) - factor));
        const glm::vec3 position = spot ? spot->position : std::get<PointLight>(lights[l]).position;
        const glm::vec3 radiance = spot ? spot->color * spot->intensity : glm::vec3(1.0f, 0.5f, 0.25f) * 3.0f;
        const float d2 = glm::dot(point - position, point - position);
        if (spot) {
            const glm::vec2 cosines = detail::spotConeCosines(*spot);
            const float c = glm::dot(glm::normalize(point - position), glm::normalize(spot->direction));
            if (std::abs(c - cosines.x) < 1e-5f || std::abs(c - cosines.y) < 1e-5f) continue;
        }
        const float expected = spot ? coneFactorAt(*spot, point) : 1.0f;
        band += expected > 0.0f && expected < 1.0f;
        dark += expected == 0.0f;
        ++compared;
        for (int c = 0; c < 3; ++c)
            worstRadiance = std::max(worstRadiance, std::abs(double(results[i][c]) * d2 / radiance[c] - expected));
    }
    std::printf("spot cone GLSL vs C++: %u cosines, worst |factor difference| %.3g; %d points (%d in a fall-off band, "
                "%d dark), worst |radiance * d^2 / I - factor| %.3g\n",
                count, worstFactor, compared, band, dark, worstRadiance);
    CHECK(compared > 30000);
    CHECK(band > 1000);
    CHECK(dark > 10000);
    // Measured on llvmpipe: factors equal (0 apart), radiance 4.7e-5 (the GPU's cosine from
    // inversesqrt, in the 45-degree light's narrow band where the factor's slope is 55).
    CHECK(worstFactor <= 1e-6);
    CHECK(worstRadiance <= 1e-4);
    gl.requireNoErrors();
}

TEST_CASE("Spot-light falloff: an analytic check on a plane", "[gl][spot][mesh][analytic]") {
    // A Lambertian plane (Blinn-Phong with no specular and no ambient) at z = 0.1, a spot h = 1
    // above its middle aimed straight down, an orthographic view from +z: a pixel at distance r
    // from the middle must read albedo * I * spotConeFactor(cos theta) * cos theta / d^2, with
    // d^2 = r^2 + h^2 and cos theta = h / d (the angle to the axis is the angle of incidence).
    test::GlTestScope gl;
    MeshScatteringRenderer renderer;
    const float top = 0.1f, h = 1.0f, albedo = 0.6f, intensity = 2.0f;
    renderer.setMesh(makeSlab({2.4f, 2.4f, 2.0f * top}));
    renderer.setMaterial({.diffuse = glm::vec3(albedo), .specular = glm::vec3(0.0f), .ambient = glm::vec3(0.0f)});
    const SpotLight spot = spotAt({0.0f, 0.0f, top + h}, {0.0f, 0.0f, 0.0f}, 30.0f, 0.5f, intensity);  // inner 15 deg
    renderer.setLights({spot});
    const int size = 101;
    RenderTarget target(size, size);
    target.clear({0, 0, 0, 1});
    Camera camera;  // at (0, 0, 3) looking along -z
    camera.setProjectionType(Projection::Orthographic);
    camera.setOrthoHeight(2.0f);  // the image is the square [-1, 1]^2 of the plane
    renderer.render(camera, target);
    const Image image = target.readColor();
    const float pixel = 2.0f / float(size);
    int inside = 0, band = 0, outside = 0;
    double worst = 0.0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            // Rows may run either way: the expected image is symmetric about the middle.
            const glm::vec3 p((float(x) + 0.5f) * pixel - 1.0f, (float(y) + 0.5f) * pixel - 1.0f, top);
            const float d2 = p.x * p.x + p.y * p.y + h * h;
            const float cosTheta = h / std::sqrt(d2);
            const float factor = spotConeFactor(spot, cosTheta);
            const float expected = albedo * intensity * factor * cosTheta / d2;
            inside += factor == 1.0f;
            band += factor > 0.0f && factor < 1.0f;
            outside += factor == 0.0f;
            INFO("pixel (" << x << ", " << y << "), cone factor " << factor);
            if (factor == 0.0f) {
                REQUIRE(image.at(x, y).g == 0.0f);  // outside the cone: exactly dark
            } else {
                worst = std::max(worst, std::abs(double(image.at(x, y).g) - expected) / (albedo * intensity / (h * h)));
            }
        }
    std::printf("spot over a plane: %d pixels in the inner cone, %d in the fall-off, %d outside; worst error %.3g of "
                "the peak\n",
                inside, band, outside, worst);
    CHECK(inside > 500);
    CHECK(band > 2000);
    CHECK(outside > 2000);
    // Measured: 1.6e-6 of the peak on llvmpipe, 5.1e-5 on an NVIDIA H200 (float rounding of the
    // interpolated position and the cosine; NVIDIA's faster transcendentals).
    CHECK(worst <= 1e-4);
    gl.requireNoErrors();
}

TEST_CASE("a spot light on a volume lights only its cone, and inside it, the point light's image", "[gl][spot][volume]") {
    // A uniform box seen head-on (orthographic, from +z), the spot at the camera's position aimed
    // along the view: a view ray at distance r from the axis meets the box at angles to the cone
    // axis between atan(r / 3.5) and atan(r / 2.5). Pixels whose every sample is in the inner
    // cone must be the point light's exactly (the light volume ignores the cone, and the factor
    // is exactly 1); those whose every sample is outside the outer cone get no light (ambient 0,
    // black background). Light volume (ray caster) and path tracer (single scattering: multiple
    // scattering would carry light out of the cone) alike.
    test::GlTestScope gl;
    const int n = 16;
    const Volume volume =
        Volume::fromData({n, n, n}, VoxelType::UInt8, std::vector<uint8_t>(static_cast<size_t>(n * n * n), 200));
    const glm::vec3 colour(0.9f, 0.8f, 0.6f);
    const TransferFunction tf({{0.0f, colour, 0.03f}, {1.0f, colour, 0.03f}});
    const SpotLight spot = spotAt({0.0f, 0.0f, 3.0f}, {0.0f, 0.0f, 0.0f}, 6.0f, 0.5f, 9.0f);  // inner cone 3 degrees
    Camera camera;
    camera.setProjectionType(Projection::Orthographic);
    camera.setOrthoHeight(1.2f);
    const int size = 64;
    for (const bool pathTraced : {false, true}) {
        VolumeRenderOptions options;
        options.shading = VolumeShading::Scattering;
        options.ambient = 0.0f;
        if (pathTraced) {
            options.model = VolumeModel::Physical;
            options.multipleScattering = true;
            options.maxBounces = 1;
            options.samplesPerFrame = 4;
        }
        const auto render = [&](const Light& light) {
            VolumeScatteringRenderer renderer(options);
            renderer.setVolume(volume);
            renderer.setTransferFunction(tf);
            renderer.setLights({light});
            RenderTarget target(size, size);
            target.clear(glm::vec4(0.0f));
            renderer.render(camera, target);
            return target.readColor();
        };
        const Image withSpot = render(spot), withPoint = render(pointOf(spot));
        int inside = 0, outside = 0;
        double worstInside = 0.0, brightestOutside = 0.0, pointOutside = 0.0;
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const float r = glm::length((glm::vec2(float(x), float(y)) + 0.5f) * (1.2f / float(size)) - 0.6f);
                if (withPoint.at(x, y).a <= 0.0f) continue;
                if (glm::degrees(std::atan(r / 2.5f)) < 2.9f) {
                    ++inside;
                    for (int c = 0; c < 3; ++c)
                        worstInside = std::max(worstInside, double(std::abs(withSpot.at(x, y)[c] - withPoint.at(x, y)[c])));
                } else if (glm::degrees(std::atan(r / 3.5f)) > 6.1f) {
                    ++outside;
                    brightestOutside = std::max(brightestOutside, maxRgb(withSpot, x, y));
                    pointOutside = std::max(pointOutside, maxRgb(withPoint, x, y));
                }
            }
        std::printf("spot on a volume (%s): %d pixels inside, largest difference from the point light %.3g; %d outside, "
                    "brightest %.3g (point light there: %.3g)\n",
                    pathTraced ? "path tracer" : "light volume", inside, worstInside, outside, brightestOutside,
                    pointOutside);
        INFO((pathTraced ? "path tracer" : "light volume"));
        CHECK(inside >= 20);
        CHECK(outside >= 200);
        CHECK(pointOutside > 0.01);  // the point light does light those pixels
        CHECK(worstInside == 0.0);
        CHECK(brightestOutside == 0.0);
    }
    gl.requireNoErrors();
}

TEST_CASE("a spot light on a translucent mesh lights its cone like the point light, and little beyond",
          "[gl][spot][mesh][scattering]") {
    // The scattering-map path (light buffer, disk samples, combine). The spot sits at the camera,
    // aimed at the sphere's centre with a hard 8-degree edge, so a pixel's angle to the cone axis
    // is its view ray's. Potato at 1000 mm per unit scatters over about 0.015 units (1 / sigma_tr,
    // red); 4 degrees of the cone span 0.14 units at the sphere's front. 16 maps: with 4, points
    // no map sees take radiosity filled in from the surface around them, which carried light up
    // to 8 degrees past the edge (measured: 0.11 of the point light's outside; the same with the
    // dipole profile and at 5000 mm per unit, so it is the fill, not the cone).
    test::GlTestScope gl;
    MeshRenderOptions options;
    options.shading = MeshShading::Scattering;
    options.cameras = 16;
    options.samples = 16;
    options.mapResolution = options.lightMapResolution = 256;
    options.accumulationFrames = 4;
    options.millimetresPerUnit = 1000.0;
    options.specular = 0.0f;
    const Camera camera;
    const SpotLight spot = spotAt(camera.position(), camera.target(), 8.0f, 0.0f, 9.0f);
    const int size = 64;
    const auto render = [&](const Light& light) {
        MeshScatteringRenderer renderer(options);
        renderer.setMesh(makeUvSphere(48, 32));
        renderer.setScatteringMaterial(materialPreset("potato"));
        renderer.setLights({light});
        RenderTarget target(size, size);
        do {
            target.clear(glm::vec4(0.0f));
            renderer.render(camera, target);
        } while (!renderer.converged());
        return target.readColor();
    };
    const Image withSpot = render(spot), withPoint = render(pointOf(spot));
    const double tanHalfFov = std::tan(glm::radians(camera.fovY()) / 2.0);
    double insideSpot = 0.0, insidePoint = 0.0, outsideSpot = 0.0, outsidePoint = 0.0;
    int inside = 0, outside = 0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            if (withPoint.at(x, y).a <= 0.0f) continue;
            const glm::dvec2 ndc((x + 0.5) / size * 2.0 - 1.0, (y + 0.5) / size * 2.0 - 1.0);
            const double angle = glm::degrees(std::atan(glm::length(ndc) * tanHalfFov));
            const double s = withSpot.at(x, y).r + withSpot.at(x, y).g + withSpot.at(x, y).b,
                         p = withPoint.at(x, y).r + withPoint.at(x, y).g + withPoint.at(x, y).b;
            if (angle < 4.0) {
                insideSpot += s;
                insidePoint += p;
                ++inside;
            } else if (angle > 12.0 && angle < 18.0) {
                outsideSpot += s;
                outsidePoint += p;
                ++outside;
            }
        }
    const double insideRatio = insideSpot / insidePoint, outsideRatio = outsideSpot / outsidePoint;
    std::printf("spot on a translucent sphere: %d pixels inside the cone, spot / point %.5f; %d outside, spot / point "
                "%.3g\n",
                inside, insideRatio, outside, outsideRatio);
    CHECK(inside >= 20);
    CHECK(outside >= 300);
    // Measured: inside 0.9999 (what the point light sends beyond the edge scatters in a little),
    // outside 8.6e-7.
    CHECK(insideRatio == Approx(1.0).margin(0.01));
    CHECK(outsideRatio < 1e-4);
    gl.requireNoErrors();
}

TEST_CASE("a spot light in a hybrid scene: shadow maps from the spot, nothing outside its cone", "[gl][spot][hybrid]") {
    // A slab hangs above a Blinn-Phong floor; the spot straight above aims down with a 25-degree
    // cone (inner 20). Under the slab: its shadow. Beside it, inside the inner cone: what the
    // point light gives. At the floor's corner, outside the cone: only the ambient term, what
    // the scene gives with the light off.
    test::GlTestScope gl;
    const SpotLight spot = spotAt({0.0f, 2.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, 25.0f, 0.2f, 9.0f);
    Camera camera;
    camera.setTarget({0.0f, -1.0f, 0.0f});
    camera.setDistance(7.0f);
    camera.setPitch(60.0f);
    const int width = 96, height = 96;
    const auto render = [&](const Light& light) {
        HybridCompositor scene({.meshShadowsOnMeshes = true});
        scene.setLights({light});
        MeshRenderOptions floor;
        floor.specular = 0.0f;
        scene.addMesh(makeSlab({3.0f, 0.2f, 3.0f}), glm::translate(glm::mat4(1.0f), {0, -1.1f, 0}), floor);
        scene.addMesh(makeSlab({0.8f, 0.1f, 0.8f}), glm::translate(glm::mat4(1.0f), {0, 0.3f, 0}));
        RenderTarget target(width, height);
        scene.render(camera, target);
        return target.readColor();
    };
    const auto pixelOf = [&](glm::vec3 world) {
        const glm::vec4 clip = camera.projection(1.0f) * camera.view() * glm::vec4(world, 1.0f);
        const glm::vec2 ndc = glm::vec2(clip) / clip.w;
        return glm::ivec2(int((ndc.x + 1.0f) * 0.5f * width), int((1.0f - ndc.y) * 0.5f * height));
    };
    const Image withSpot = render(spot), withPoint = render(pointOf(spot));
    SpotLight off = spot;
    off.intensity = 0.0f;
    const Image dark = render(off);
    const glm::ivec2 under = pixelOf({0.0f, -0.99f, 0.0f}), aside = pixelOf({0.9f, -0.99f, 0.0f}),
                     corner = pixelOf({1.3f, -0.99f, 1.3f});
    const auto g = [](const Image& image, glm::ivec2 p) { return image.at(p.x, p.y).g; };
    std::printf("spot in a hybrid scene: under the slab %.4g, beside it %.4g (point light %.4g), corner %.4g (point "
                "light %.4g, light off %.4g)\n",
                g(withSpot, under), g(withSpot, aside), g(withPoint, aside), g(withSpot, corner), g(withPoint, corner),
                g(dark, corner));
    // The aside point is 16.7 degrees off the axis, the corner 31.5 (coneFactorAt says so too).
    REQUIRE(coneFactorAt(spot, {0.9f, -1.0f, 0.0f}) == 1.0f);
    REQUIRE(coneFactorAt(spot, {1.3f, -1.0f, 1.3f}) == 0.0f);
    CHECK(g(withSpot, aside) > 0.1f);
    CHECK(g(withSpot, under) < 0.25f * g(withSpot, aside));
    CHECK(g(withSpot, aside) == g(withPoint, aside));
    CHECK(g(withPoint, corner) > g(dark, corner) + 0.05f);
    CHECK(g(withSpot, corner) == g(dark, corner));
    gl.requireNoErrors();
}
