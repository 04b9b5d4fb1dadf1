// The CPU volume reference renderer on its own: analytic cases and the scattering model.
#include "sss/volume_reference.h"

#include "test_helpers.h"

#include <sss/procedural.h>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

using Catch::Contains;
using namespace sss;

namespace {

Volume uniformVolume(int n, uint8_t value) {
    return Volume::fromData({n, n, n}, VoxelType::UInt8, std::vector<uint8_t>(static_cast<size_t>(n * n * n), value));
}

TransferFunction constantTf(glm::vec3 color, float opacity) {
    return TransferFunction({{0.0f, color, opacity}, {1.0f, color, opacity}});
}

Camera orthoFront() {
    Camera camera;  // at (0,0,3) looking along -z
    camera.setProjectionType(Projection::Orthographic);
    camera.setOrthoHeight(2.0f);
    return camera;
}

// Model-space centre of voxel (i, j, k) of an n^3 volume in the unit box.
glm::dvec3 voxelCentre(int n, double i, double j, double k) { return (glm::dvec3(i, j, k) + 0.5) / double(n) - 0.5; }

// Pixel whose centre is nearest to the projection of a world point.
glm::ivec2 pixelOf(const Camera& camera, int width, int height, glm::vec3 world) {
    const glm::vec4 clip = camera.projection(float(width) / float(height)) * camera.view() * glm::vec4(world, 1.0f);
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    return {int(std::floor((ndc.x + 1.0f) * 0.5f * float(width))), int(std::floor((1.0f - ndc.y) * 0.5f * float(height)))};
}

}  // namespace

TEST_CASE("volume reference: a uniform slab gives exactly 1 - (1 - alpha)^L", "[cpu]") {
    // 16^3, TF opacity 0.1 per voxel, orthographic view straight through 16 voxels.
    const int n = 16;
    const Volume volume = uniformVolume(n, 200);
    const double expected = 1.0 - std::pow(0.9, n);
    for (double step : {1.0, 0.5, 0.3, 0.125}) {
        VolumeReferenceOptions options;
        options.stepVoxels = step;
        options.threads = 2;
        const Image image =
            renderVolumeReference(volume, constantTf({1, 1, 1}, 0.1f), 256, glm::mat4(1.0f), {}, orthoFront(), 16, 16, options);
        INFO("step " << step);
        const glm::vec4 centre = image.at(8, 8);
        CHECK(centre.a == Approx(expected).margin(1e-6));
        CHECK(centre.r == Approx(expected).margin(1e-6));
    }
    SECTION("composited over a background") {
        VolumeReferenceOptions options;
        options.background = {0.2, 0.4, 0.6, 0.5};
        const Image image = renderVolumeReference(volume, constantTf({1, 0, 0}, 0.1f), 256, glm::mat4(1.0f), {},
                                                  orthoFront(), 16, 16, options);
        const glm::vec4 c = image.at(8, 8);
        CHECK(c.r == Approx(expected + (1 - expected) * 0.2).margin(1e-6));
        CHECK(c.g == Approx((1 - expected) * 0.4).margin(1e-6));
        CHECK(c.b == Approx((1 - expected) * 0.6).margin(1e-6));
        CHECK(c.a == Approx(expected + (1 - expected) * 0.5).margin(1e-6));
        // The box spans the middle of the 2-unit-high view: the corner pixel misses it.
        CHECK(image.at(0, 0) == glm::vec4(0.2f, 0.4f, 0.6f, 0.5f));
    }
    SECTION("a scaled model matrix scales the path") {
        // Stretched 2x along z: the path is 32 voxels (opacity per model-space voxel length).
        const Image image = renderVolumeReference(volume, constantTf({1, 1, 1}, 0.1f), 256,
                                                  glm::scale(glm::mat4(1.0f), {1, 1, 2}), {}, orthoFront(), 16, 16);
        CHECK(image.at(8, 8).a == Approx(1.0 - std::pow(0.9, 16)).margin(1e-6));  // model units: still 16
    }
}

TEST_CASE("volume reference: an opaque volume shows the TF colour", "[cpu]") {
    const Volume volume = uniformVolume(8, 255);
    const Image image = renderVolumeReference(volume, constantTf({0.2f, 0.4f, 0.6f}, 1.0f), 256, glm::mat4(1.0f), {},
                                              orthoFront(), 16, 16);
    CHECK(image.at(8, 8).r == Approx(0.2).margin(1e-9));
    CHECK(image.at(8, 8).b == Approx(0.6).margin(1e-9));
    CHECK(image.at(8, 8).a == Approx(1.0).margin(1e-9));
}

TEST_CASE("volume reference: 16-bit volumes map their data range onto the TF as the GPU does", "[cpu]") {
    // 16-bit 3000 everywhere but one 1000 voxel must look exactly like 8-bit 255 with one 0.
    const int n = 8;
    std::vector<uint8_t> wideBytes(static_cast<size_t>(n * n * n) * 2), narrowBytes(static_cast<size_t>(n * n * n));
    for (size_t i = 0; i < narrowBytes.size(); ++i) {
        const uint16_t v = i == 0 ? 1000 : 3000;
        wideBytes[2 * i] = static_cast<uint8_t>(v & 0xFF);
        wideBytes[2 * i + 1] = static_cast<uint8_t>(v >> 8);
        narrowBytes[i] = i == 0 ? 0 : 255;
    }
    const Volume wide = Volume::fromData({n, n, n}, VoxelType::UInt16, std::move(wideBytes));
    const Volume narrow = Volume::fromData({n, n, n}, VoxelType::UInt8, std::move(narrowBytes));
    const TransferFunction tf({{0.0f, {0, 0, 0}, 0.0f}, {0.9f, {1, 0, 0}, 0.0f}, {1.0f, {1, 0, 0}, 1.0f}});
    Camera camera;
    camera.setYaw(20.0f);
    camera.setPitch(10.0f);
    VolumeReferenceOptions options;
    options.shading = ReferenceShading::Gradient;
    const std::vector<Light> lights{DirectionalLight{}};
    const Image a = renderVolumeReference(wide, tf, 256, glm::mat4(1.0f), lights, camera, 16, 16, options);
    const Image b = renderVolumeReference(narrow, tf, 256, glm::mat4(1.0f), lights, camera, 16, 16, options);
    CHECK(a.at(8, 8).r > 0.5f);
    for (size_t i = 0; i < a.data().size(); ++i) REQUIRE(a.data()[i] == Approx(b.data()[i]).margin(1e-6));
}

TEST_CASE("volume reference: a fully transparent TF leaves exactly the background", "[cpu]") {
    const Volume volume = makeBlobsVolume(16);
    Camera camera;
    camera.setYaw(30.0f);
    VolumeReferenceOptions options;
    options.background = {0.1, 0.1, 0.12, 1.0};
    for (ReferenceShading shading : {ReferenceShading::EmissionAbsorption, ReferenceShading::Gradient,
                                     ReferenceShading::Scattering, ReferenceShading::ScatteringGradient}) {
        options.shading = shading;
        const Image image = renderVolumeReference(volume, constantTf({1, 1, 1}, 0.0f), 256, glm::mat4(1.0f),
                                                  {DirectionalLight{}}, camera, 24, 16, options);
        INFO("shading " << int(shading));
        for (int y = 0; y < image.height(); ++y)
            for (int x = 0; x < image.width(); ++x) REQUIRE(image.at(x, y) == glm::vec4(0.1f, 0.1f, 0.12f, 1.0f));
    }
}

TEST_CASE("volume reference: light through a white medium stays white, a coloured one tints it", "[cpu]") {
    // Uniform 16^3 medium, TF opacity 0.1 per voxel; light from +z. From the centre to the +z face
    // is 8 voxels: l = 0.9^8 and c = C + (1 - C) 0.9^8 exactly (constant sigma_t and C).
    const int n = 16;
    const Volume volume = uniformVolume(n, 200);
    const std::vector<Light> lights{DirectionalLight{.direction = {0, 0, -1}, .color = {1, 1, 1}, .intensity = 2.0f}};
    const double l = std::pow(0.9, 8);
    const glm::dvec3 centre(0.0);
    {
        const VolumeReference white(volume, constantTf({1, 1, 1}, 0.1f), 256, glm::mat4(1.0f), lights);
        const ReferenceLightSample s = white.incidentLight(centre, 0);
        CHECK(s.transmittance == Approx(l).margin(1e-12));
        CHECK(glm::length(s.chromaticity - glm::dvec3(1.0)) < 1e-12);
        CHECK(glm::length(s.radiance - glm::dvec3(2.0)) < 1e-12);
        CHECK(white.extinction(centre) == Approx(-std::log(0.9) * n).epsilon(1e-6));  // per model unit
    }
    {
        VolumeReferenceOptions options;
        options.shadowStepVoxels = 0.3;  // any step: piecewise constant medium is integrated exactly
        const VolumeReference tinted(volume, constantTf({1, 0.5f, 0}, 0.1f), 256, glm::mat4(1.0f), lights, options);
        const ReferenceLightSample s = tinted.incidentLight(centre, 0);
        CHECK(s.transmittance == Approx(l).margin(1e-12));
        CHECK(s.chromaticity.r == Approx(1.0).margin(1e-12));
        CHECK(s.chromaticity.g == Approx(0.5 + 0.5 * l).margin(1e-12));
        CHECK(s.chromaticity.b == Approx(l).margin(1e-12));
        // Deeper in the medium the light is redder.
        const ReferenceLightSample deeper = tinted.incidentLight(voxelCentre(n, 8, 8, 1), 0);
        CHECK(deeper.chromaticity.b < s.chromaticity.b);
        CHECK(deeper.transmittance < s.transmittance);
    }
    SECTION("a point light inside the medium: the path ends at the light, E falls off with 1/r^2") {
        const std::vector<Light> point{PointLight{.position = {0, 0, 0.25f}, .color = {1, 1, 1}, .intensity = 1.0f}};
        const VolumeReference ref(volume, constantTf({1, 1, 1}, 0.1f), 256, glm::mat4(1.0f), point);
        const ReferenceLightSample s = ref.incidentLight(centre, 0);
        CHECK(s.transmittance == Approx(std::pow(0.9, 4)).margin(1e-12));  // 0.25 units = 4 voxels
        CHECK(s.radiance.x == Approx(16.0).margin(1e-9));
    }
}

TEST_CASE("volume reference: the light volume's cone gather blurs c across the light, not along it", "[cpu]") {
    // 16^3, light travelling along -z. chromaticityConeScale = 1 gathers c as a full-resolution
    // light volume does: at each of the 16 slice planes, from the crossing or a ring of radius
    // tan(47 deg) x 1 voxel at g = 0.5.
    const int n = 16;
    const std::vector<Light> lights{DirectionalLight{.direction = {0, 0, -1}}};
    VolumeReferenceOptions cone;
    cone.chromaticityConeScale = 1.0;
    cone.chromaticityWalks = 256;
    SECTION("a uniform medium: every walk crosses the same medium, so c is the straight ray's") {
        const Volume volume = uniformVolume(n, 200);
        const TransferFunction tf = constantTf({1, 0.5f, 0}, 0.1f);
        const VolumeReference straight(volume, tf, 256, glm::mat4(1.0f), lights);
        const VolumeReference gathered(volume, tf, 256, glm::mat4(1.0f), lights, cone);
        // (Near enough the lit face that no walk leaves by a side: there c would be white.)
        for (glm::dvec3 p : {glm::dvec3(0.0), voxelCentre(n, 8, 8, 11.3)}) {
            const ReferenceLightSample a = straight.incidentLight(p, 0), b = gathered.incidentLight(p, 0);
            CHECK(glm::length(a.chromaticity - b.chromaticity) < 1e-9);
            CHECK(a.transmittance == b.transmittance);
        }
    }
    SECTION("a red rod along the light tints the light beside it and gives up some of its red") {
        // Clear, except a rod 2 x 2 voxels wide over z >= 8 (towards the light) of red medium.
        std::vector<uint8_t> bytes(static_cast<size_t>(n * n * n), 0);
        for (int z = 8; z < n; ++z)
            for (int y = 7; y <= 8; ++y)
                for (int x = 7; x <= 8; ++x) bytes[static_cast<size_t>((z * n + y) * n + x)] = 255;
        const Volume volume = Volume::fromData({n, n, n}, VoxelType::UInt8, std::move(bytes));
        const TransferFunction tf({{0.0f, {1, 0, 0}, 0.0f}, {1.0f, {1, 0, 0}, 0.5f}});
        const VolumeReference straight(volume, tf, 256, glm::mat4(1.0f), lights);
        const VolumeReference gathered(volume, tf, 256, glm::mat4(1.0f), lights, cone);
        cone.chromaticityConeScale = 0.5;  // slices 2 voxels thick: a ring of 2 voxels, more blur
        const VolumeReference coarse(volume, tf, 256, glm::mat4(1.0f), lights, cone);
        const glm::dvec3 under = voxelCentre(n, 7.5, 7.5, 4), beside = voxelCentre(n, 11.5, 7.5, 4);
        // Straight: under the rod the light is red, beside it (3 voxels off) white.
        CHECK(straight.incidentLight(under, 0).chromaticity.g < 0.01);  // 0.5^8 = 0.004 and the rod's end
        CHECK(straight.incidentLight(beside, 0).chromaticity.g == Approx(1.0).margin(1e-12));
        const ReferenceLightSample u = gathered.incidentLight(under, 0), b = gathered.incidentLight(beside, 0);
        CHECK(u.chromaticity.g > 0.25);  // walks that wandered out of the rod (measured 0.51)
        CHECK(b.chromaticity.g < 0.97);  // walks that wandered into it (measured 0.938)
        CHECK(u.chromaticity.r == Approx(1.0).margin(1e-12));  // red stays red
        CHECK(b.transmittance == Approx(1.0).margin(1e-12));   // l is the straight ray's
        CHECK(coarse.incidentLight(beside, 0).chromaticity.g < b.chromaticity.g);
        // One estimate per point, whichever thread asks.
        CHECK(gathered.incidentLight(beside, 0).chromaticity == b.chromaticity);
    }
    SECTION("the physical model has no c to gather, and bad values are rejected") {
        cone.model = VolumeModel::Physical;
        const VolumeReference physical(uniformVolume(n, 200), constantTf({1, 0.5f, 0}, 0.1f), 256, glm::mat4(1.0f),
                                       lights, cone);
        CHECK(physical.incidentLight(glm::dvec3(0.0), 0).transmittance == Approx(std::pow(0.9, 8)).margin(1e-12));
        using K = ErrorKind;
        REQUIRE_SSS_ERROR(VolumeReference(uniformVolume(4, 0), TransferFunction(), 256, glm::mat4(1.0f), lights,
                                          {.chromaticityConeScale = 1.5}),
                          K::InvalidArgument, Contains("chromaticityConeScale must be 0 (straight) or in (0, 1]"));
        REQUIRE_SSS_ERROR(VolumeReference(uniformVolume(4, 0), TransferFunction(), 256, glm::mat4(1.0f), lights,
                                          {.chromaticityWalks = 0}),
                          K::InvalidArgument, Contains("chromaticityWalks must be >= 1"));
    }
}

TEST_CASE("volume reference: an opaque slab casts a hard shadow on a blob", "[cpu]") {
    // 32^3: an opaque slab (255) at z voxels 22..25 over the half x < 16, and a ball (128) of
    // radius 6 around voxel (16, 16, 10); light from +z. The ball's x < 16 half is in shadow.
    const int n = 32;
    std::vector<uint8_t> bytes(static_cast<size_t>(n * n * n), 0);
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                uint8_t v = 0;
                if (z >= 22 && z <= 25 && x < 16) v = 255;
                const glm::dvec3 d = glm::dvec3(x, y, z) - glm::dvec3(16, 16, 10);
                if (glm::length(d) <= 6.0) v = 128;
                bytes[static_cast<size_t>((z * n + y) * n + x)] = v;
            }
    const Volume volume = Volume::fromData({n, n, n}, VoxelType::UInt8, std::move(bytes));
    const TransferFunction tf({{0.0f, {0, 0, 0}, 0.0f}, {0.3f, {1, 1, 1}, 0.0f}, {0.5f, {1, 1, 1}, 0.3f},
                               {0.9f, {1, 1, 1}, 1.0f}});
    const std::vector<Light> lights{DirectionalLight{.direction = {0, 0, -1}}};
    VolumeReferenceOptions options;
    options.shading = ReferenceShading::Scattering;
    options.ambient = 0.2;
    options.diffuse = 1.0;
    const VolumeReference ref(volume, tf, 256, glm::mat4(1.0f), lights, options);

    // Behind the slab (between it and the ball, and in the ball's top): no light.
    CHECK(ref.incidentLight(voxelCentre(n, 8, 16, 18), 0).transmittance < 1e-9);
    CHECK(ref.incidentLight(voxelCentre(n, 12, 16, 15), 0).transmittance < 1e-9);
    // Beside the slab and in front of it (towards the light): all of it.
    CHECK(ref.incidentLight(voxelCentre(n, 24, 16, 18), 0).transmittance == Approx(1.0).margin(1e-12));
    CHECK(ref.incidentLight(voxelCentre(n, 8, 16, 28), 0).transmittance == Approx(1.0).margin(1e-12));
    // Inside the ball's lit half: only the ball itself (about 2.5 voxels of alpha 0.3) attenuates.
    const double litInside = ref.incidentLight(voxelCentre(n, 20, 16, 12), 0).transmittance;
    CHECK(litInside > 0.2);
    CHECK(litInside < 0.9);

    // The image, seen from below (-y) so that both halves of the ball show side by side.
    Camera camera;
    camera.setProjectionType(Projection::Orthographic);
    camera.setOrthoHeight(1.2f);
    camera.setPitch(-89.0f);
    const int w = 48, h = 48;
    const Image image = ref.render(camera, w, h);
    auto luminance = [&](int i, int j, int k) {
        const glm::ivec2 px = pixelOf(camera, w, h, glm::vec3(voxelCentre(n, i, j, k)));
        const glm::vec4 c = image.at(px.x, px.y);
        return (c.r + c.g + c.b) / 3.0f;
    };
    const float shadowed = luminance(12, 16, 13), lit = luminance(20, 16, 13);
    INFO("ball: shadowed half " << shadowed << ", lit half " << lit);
    CHECK(shadowed > 0.05f);        // ambient still shows it
    CHECK(lit > 2.5f * shadowed);   // k_a + k_d * l vs k_a alone
}

TEST_CASE("volume reference: converged rendering halves the step until it settles", "[cpu]") {
    const Volume volume = makeBlobsVolume(16);
    const TransferFunction tf({{0.0f, {0, 0, 0}, 0.0f}, {0.2f, {0.9f, 0.4f, 0.1f}, 0.0f},
                               {0.5f, {1.0f, 0.8f, 0.3f}, 0.15f}, {1.0f, {0.4f, 0.7f, 1.0f}, 0.6f}});
    Camera camera;
    camera.frame(volume.worldBounds());
    const ConvergedReference r =
        renderVolumeReferenceConverged(volume, tf, 256, glm::mat4(1.0f), {}, camera, 24, 16, {}, 1e-3, 1.0, 1.0 / 64);
    INFO("step " << r.stepVoxels << ", last change " << r.lastChange << ", renders " << r.renders);
    CHECK(r.converged);
    CHECK(r.lastChange < 1e-3);
    CHECK(r.renders >= 2);
    CHECK(r.stepVoxels == 1.0 / std::pow(2.0, r.renders - 1));
}

TEST_CASE("volume reference: bad inputs are rejected with the parameter's name", "[cpu]") {
    const Volume volume = makeBlobsVolume(8);
    const TransferFunction tf;
    const Camera camera;
    auto render = [&](const VolumeReferenceOptions& o, int w = 8, int h = 8) {
        return renderVolumeReference(volume, tf, 256, glm::mat4(1.0f), {}, camera, w, h, o);
    };
    using K = ErrorKind;
    REQUIRE_SSS_ERROR(render({}, 0, 8), K::InvalidArgument, Contains("width and height must be in 1..16384, got 0 x 8"));
    REQUIRE_SSS_ERROR(render({.stepVoxels = 0.0}), K::InvalidArgument,
                      Contains("VolumeReferenceOptions::stepVoxels must be finite and >= 1/1024"));
    REQUIRE_SSS_ERROR(render({.stepVoxels = -1.0}), K::InvalidArgument, Contains("stepVoxels"));
    REQUIRE_SSS_ERROR(render({.shadowStepVoxels = std::nan("")}), K::InvalidArgument, Contains("shadowStepVoxels"));
    REQUIRE_SSS_ERROR(render({.earlyTermination = 0.0}), K::InvalidArgument, Contains("earlyTermination"));
    REQUIRE_SSS_ERROR(render({.shininess = 0.0}), K::InvalidArgument, Contains("shininess"));
    REQUIRE_SSS_ERROR(render({.threads = -2}), K::InvalidArgument, Contains("threads"));
    REQUIRE_SSS_ERROR(renderVolumeReference(volume, tf, 1, glm::mat4(1.0f), {}, camera, 8, 8), K::InvalidArgument,
                      Contains("tfEntries must be in 2..65536, got 1"));
    REQUIRE_SSS_ERROR(renderVolumeReference(volume, tf, 256, glm::mat4(0.0f), {}, camera, 8, 8), K::InvalidArgument,
                      Contains("model matrix must be finite and invertible"));
    REQUIRE_SSS_ERROR(renderVolumeReference(volume, tf, 256, glm::mat4(1.0f), {DirectionalLight{.direction = {0, 0, 0}}},
                                            camera, 8, 8),
                      K::InvalidArgument, Contains("VolumeReference light 0") && Contains("direction"));
    REQUIRE_SSS_ERROR(renderVolumeReferenceConverged(volume, tf, 256, glm::mat4(1.0f), {}, camera, 8, 8, {}, 0.0),
                      K::InvalidArgument, Contains("tolerance must be finite and > 0"));
    REQUIRE_SSS_ERROR(renderVolumeReferenceConverged(volume, tf, 256, glm::mat4(1.0f), {}, camera, 8, 8, {}, 1e-3, 0.1, 0.5),
                      K::InvalidArgument, Contains("minStepVoxels <= startStepVoxels"));
    const VolumeReference ref(volume, tf, 256, glm::mat4(1.0f), {});
    REQUIRE_SSS_ERROR(ref.incidentLight(glm::dvec3(0), 0), K::InvalidArgument, Contains("light 0 is out of range"));
}

TEST_CASE("volume reference: the cubic B-spline keeps a linear ramp and spreads one voxel over its neighbours",
          "[cpu]") {
    // A TF whose opacity is its coordinate reads the field back through classify(). The cubic
    // B-spline reproduces linear data exactly (away from the clamped edges) and weights a voxel
    // 2/3 at its own centre and 1/6 at each neighbour's, per axis.
    const int n = 12;
    const TransferFunction identity({{0.0f, {1, 1, 1}, 0.0f}, {1.0f, {1, 1, 1}, 1.0f}});
    auto reference = [&](const Volume& volume, VolumeReconstruction r) {
        return VolumeReference(volume, identity, 4096, glm::mat4(1.0f), {DirectionalLight{}},
                               VolumeReferenceOptions{.reconstruction = r});
    };
    std::vector<uint8_t> ramp(static_cast<size_t>(n) * n * n), spike(ramp.size(), 0);
    for (size_t i = 0; i < ramp.size(); ++i) ramp[i] = static_cast<uint8_t>(20 * (i % n));
    spike[(static_cast<size_t>(6) * n + 6) * n + 6] = 216;
    const Volume rampVolume = Volume::fromData({n, n, n}, VoxelType::UInt8, std::move(ramp));
    const Volume spikeVolume = Volume::fromData({n, n, n}, VoxelType::UInt8, std::move(spike));
    const VolumeReference rampCubic = reference(rampVolume, VolumeReconstruction::CubicBSpline);
    const VolumeReference rampLinear = reference(rampVolume, VolumeReconstruction::Trilinear);
    for (double x : {2.0, 3.3, 5.5, 7.91, 8.5})
        CHECK(rampCubic.classify(voxelCentre(n, x, 4.2, 6.7)).a ==
              Approx(rampLinear.classify(voxelCentre(n, x, 4.2, 6.7)).a).margin(1e-3));
    const VolumeReference spikeCubic = reference(spikeVolume, VolumeReconstruction::CubicBSpline);
    const VolumeReference spikeLinear = reference(spikeVolume, VolumeReconstruction::Trilinear);
    const double peak = 216.0 / 255.0;
    CHECK(spikeLinear.classify(voxelCentre(n, 6, 6, 6)).a == Approx(peak).margin(1e-3));
    CHECK(spikeCubic.classify(voxelCentre(n, 6, 6, 6)).a == Approx(peak * 8.0 / 27.0).margin(1e-3));
    CHECK(spikeCubic.classify(voxelCentre(n, 7, 6, 6)).a == Approx(peak * 2.0 / 27.0).margin(1e-3));
    CHECK(spikeLinear.classify(voxelCentre(n, 7, 6, 6)).a == Approx(0.0).margin(1e-6));
    // Two voxels away the spike reaches neither.
    CHECK(spikeCubic.classify(voxelCentre(n, 8, 6, 6)).a == Approx(0.0).margin(1e-6));
}
