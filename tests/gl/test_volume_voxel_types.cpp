// Int16 and Float32 volumes render as the equivalent UInt16 volume under the same value window:
// the three hold the same field up to an affine map of the values, and the windows are mapped
// alike, so every TF coordinate agrees (up to float rounding in the GPU's s * a + b).
#include "support/gl_test.h"
#include "support/scenes.h"

#include <catch2/catch.hpp>
#include <sss/image_compare.h>
#include <sss/procedural.h>
#include <sss/volume_reference.h>
#include <sss/volume_scattering_renderer.h>

#include <cstring>

using namespace sss;
using sss::test::orbitCamera;

namespace {

constexpr int kWidth = 160, kHeight = 96;

// raw value of the uint16 volume -> the int16 and float32 volumes' values.
double toInt16(double u) { return u - 20000.0; }
double toFloat32(double u) { return u * 0.25 - 300.5; }

struct Equivalents {
    Volume u16, i16, f32;
};

// Blobs (uint8) spread over 1000..26500 in uint16, and the same field in the other types.
Equivalents makeEquivalents() {
    const Volume blobs = makeBlobsVolume(32);
    const std::size_t n = blobs.voxelCount();
    std::vector<uint8_t> u(2 * n), i(2 * n), f(4 * n);
    for (std::size_t k = 0; k < n; ++k) {
        const double value = 1000.0 + 100.0 * blobs.bytes()[k];
        const auto u16 = static_cast<uint16_t>(value);
        const auto i16 = static_cast<uint16_t>(static_cast<int16_t>(toInt16(value)));
        const auto f32 = static_cast<float>(toFloat32(value));
        std::memcpy(&u[2 * k], &u16, 2);
        std::memcpy(&i[2 * k], &i16, 2);
        std::memcpy(&f[4 * k], &f32, 4);
    }
    return {Volume::fromData(blobs.dims(), VoxelType::UInt16, std::move(u)),
            Volume::fromData(blobs.dims(), VoxelType::Int16, std::move(i)),
            Volume::fromData(blobs.dims(), VoxelType::Float32, std::move(f))};
}

Image8 render(const Volume& volume, VolumeShading shading) {
    VolumeScatteringRenderer renderer({.shading = shading});
    renderer.setVolume(volume);
    renderer.setTransferFunction(test::blobsTransferFunction());
    renderer.setLights({DirectionalLight{.direction = {-1.0f, -1.0f, -0.6f}}});
    RenderTarget target(kWidth, kHeight);
    target.clear({0.1f, 0.1f, 0.12f, 1.0f});
    renderer.render(orbitCamera(volume.worldBounds(), 30.0f, 20.0f), target);
    return target.readColor().toRgba8();
}

}  // namespace

TEST_CASE("int16 and float32 volumes render as the equivalent uint16 volume under the same window",
          "[gl][volume][voxel-types]") {
    test::GlTestScope gl;
    Equivalents v = makeEquivalents();
    const std::pair<double, double> window(1000.0 + 100.0 * 40, 1000.0 + 100.0 * 220);  // a narrower window
    v.u16.setValueWindow(window);
    v.i16.setValueWindow(std::pair(toInt16(window.first), toInt16(window.second)));
    v.f32.setValueWindow(std::pair(toFloat32(window.first), toFloat32(window.second)));
    for (VolumeShading shading : {VolumeShading::EmissionAbsorption, VolumeShading::ScatteringGradient}) {
        CAPTURE(static_cast<int>(shading));
        const Image8 expected = render(v.u16, shading);
        for (const Volume* other : {&v.i16, &v.f32}) {
            CAPTURE(voxelTypeName(other->type()));
            const ImageDifference d = compareImages(render(*other, shading), expected);
            CHECK(d.maxChannelDelta <= 2);  // float rounding of s * a + b on the GPU
            CHECK(d.differingFraction < 0.002);
        }
        // The window matters: without it the int16 volume spans its data range instead.
        Volume unwindowed = v.i16;
        unwindowed.setValueWindow(std::nullopt);
        CHECK(compareImages(render(unwindowed, shading), expected).maxChannelDelta > 20);
    }
    gl.requireNoErrors();
}

TEST_CASE("the CPU reference classifies int16 and float32 volumes as the equivalent uint16 volume",
          "[gl][volume][voxel-types]") {
    // No GL needed, but here beside its GPU counterpart.
    Equivalents v = makeEquivalents();
    const std::pair<double, double> window(1000.0 + 100.0 * 40, 1000.0 + 100.0 * 220);
    v.u16.setValueWindow(window);
    v.i16.setValueWindow(std::pair(toInt16(window.first), toInt16(window.second)));
    v.f32.setValueWindow(std::pair(toFloat32(window.first), toFloat32(window.second)));
    auto renderCpu = [&](const Volume& volume) {
        const std::vector<Light> lights{DirectionalLight{.direction = {-1.0f, -1.0f, -0.6f}}};
        return renderVolumeReference(volume, test::blobsTransferFunction(), 256, glm::mat4(1.0f), lights,
                                     orbitCamera(volume.worldBounds(), 30.0f, 20.0f), 48, 32)
            .toRgba8();
    };
    const Image8 expected = renderCpu(v.u16);
    CHECK(compareImages(renderCpu(v.i16), expected).maxChannelDelta <= 1);
    CHECK(compareImages(renderCpu(v.f32), expected).maxChannelDelta <= 1);
}
