// What does not fit the GPU becomes an Error(GpuLimit) naming the object, the size and the
// limit (never a GL error and a blank picture), and light volumes fall back to a lower
// resolution when asked to. The memory budget makes "does not fit" reproducible on any device.
#include "cpu/test_helpers.h"
#include "support/gl_test.h"
#include "support/scenes.h"

#include <catch2/catch.hpp>
#include <sss/error.h>
#include <sss/gpu_memory.h>
#include <sss/image_compare.h>
#include <sss/log.h>
#include <sss/materials.h>
#include <sss/mesh_scattering_renderer.h>
#include <sss/procedural.h>
#include <sss/render_target.h>
#include <sss/volume_scattering_renderer.h>

#include "gl/buffer.h"
#include "gl/device.h"
#include "gl/texture.h"

#include <glm/mat4x4.hpp>

#include <string>
#include <vector>

using namespace sss;
using Catch::Matchers::Contains;

namespace {

// Restores the process-wide budget and log handler however the test ends.
struct BudgetScope {
    explicit BudgetScope(std::uint64_t bytes) { setGpuMemoryBudget(bytes); }
    ~BudgetScope() { setGpuMemoryBudget(0); }
};

struct LogCapture {
    std::vector<std::string> warnings;
    LogCapture() {
        setLogHandler([this](LogLevel level, std::string_view m) {
            if (level == LogLevel::Warning) warnings.emplace_back(m);
        });
    }
    ~LogCapture() { setLogHandler({}); }
};

}  // namespace

TEST_CASE("the implementation's limits are queried", "[gl][limits]") {
    test::GlTestScope gl;
    const GpuLimits limits = queryGpuLimits();
    CHECK(limits.maxTextureSize >= 1024);    // GL 4.5 minimums (Table 23.64)
    CHECK(limits.max3DTextureSize >= 256);
    CHECK(limits.maxArrayTextureLayers >= 256);
    CHECK(limits.availableMemoryBytes <= limits.totalMemoryBytes + (limits.totalMemoryBytes == 0 ? limits.availableMemoryBytes : 0));
    gl.requireNoErrors();
}

TEST_CASE("a texture over the size limit is an error naming it, its size and the limit", "[gl][limits]") {
    test::GlTestScope gl;
    const GpuLimits limits = queryGpuLimits();
    const std::uint64_t before = gpuMemoryInUse();
    const std::string side = std::to_string(limits.max3DTextureSize + 1);
    REQUIRE_SSS_ERROR(gl::Texture::create3D(GL_R8, {limits.max3DTextureSize + 1, 2, 2}, "test volume"),
                      ErrorKind::GpuLimit,
                      Contains("test volume") && Contains(side + "x2x2 R8") && Contains("GL_MAX_3D_TEXTURE_SIZE") &&
                          Contains(std::to_string(limits.max3DTextureSize)));
    REQUIRE_SSS_ERROR(gl::Texture::create2DArray(GL_RGBA8, 4, 4, limits.maxArrayTextureLayers + 1, "test layers"),
                      ErrorKind::GpuLimit, Contains("test layers") && Contains("GL_MAX_ARRAY_TEXTURE_LAYERS"));
    REQUIRE_SSS_ERROR(gl::Texture::create2D(GL_RGBA8, limits.maxTextureSize + 1, 1, "test image"),
                      ErrorKind::GpuLimit, Contains("test image") && Contains("GL_MAX_TEXTURE_SIZE"));
    CHECK(gpuMemoryInUse() == before);
    gl.requireNoErrors();
}

TEST_CASE("an allocation the driver cannot satisfy is an error, not a GL error", "[gl][limits]") {
    test::GlTestScope gl;
    const GpuLimits limits = queryGpuLimits();
    // Within every size limit, but terabytes: llvmpipe answers GL_OUT_OF_MEMORY, drivers that
    // tell their free memory are refused before the call.
    const int side = std::min(limits.maxTextureSize, 16384);
    const int layers = std::min(limits.maxArrayTextureLayers, 2048);
    const std::uint64_t before = gpuMemoryInUse();
    REQUIRE_SSS_ERROR(gl::Texture::create2DArray(GL_RGBA32F, side, side, layers, "huge test array"),
                      ErrorKind::GpuLimit, Contains("huge test array") && Contains("RGBA32F 2D array texture"));
    CHECK(gpuMemoryInUse() == before);
    // The out-of-memory answer was handled, so it is no GL error; the context still works.
    gl.requireNoErrors();
    RenderTarget target(8, 8);
    target.clear({1.0f, 0.5f, 0.25f, 1.0f});
    CHECK(target.readColor().at(3, 3).g == 0.5f);
    gl.requireNoErrors();
}

TEST_CASE("the memory budget refuses what would pass it and counts what libsss holds", "[gl][limits]") {
    test::GlTestScope gl;
    const std::uint64_t before = gpuMemoryInUse();
    {
        RenderTarget target(64, 32);  // RGBA32F colour + 32-bit depth
        CHECK(gpuMemoryInUse() - before == 64u * 32u * (16u + 4u));
    }
    CHECK(gpuMemoryInUse() == before);
    {
        BudgetScope budget(before + 64u * 1024u);
        REQUIRE_SSS_ERROR(RenderTarget(256, 256), ErrorKind::GpuLimit,
                          Contains("RenderTarget colour") && Contains("256x256 RGBA32F") && Contains("1 MiB") &&
                              Contains("budget"));
        CHECK(gpuMemoryInUse() == before);
        RenderTarget small(32, 32);  // 20 kiB fits
        CHECK(gpuMemoryInUse() > before);
    }
    gl.requireNoErrors();
}

TEST_CASE("a light volume that does not fit falls back to a lower resolution, or fails if asked",
          "[gl][limits][volume]") {
    test::GlTestScope gl;
    const Volume volume = makeBlobsVolume(64);
    const Camera camera = test::orbitCamera(volume.worldBounds(), 30.0f, 20.0f);
    auto render = [&](VolumeScatteringRenderer& renderer) {
        RenderTarget target(96, 64);
        target.clear({0, 0, 0, 1});
        renderer.render(camera, target);
        return target.readColor();
    };
    const VolumeRenderOptions options{.shading = VolumeShading::Scattering, .jitter = false};
    VolumeScatteringRenderer halfScale({.shading = VolumeShading::Scattering, .jitter = false, .lightVolumeScale = 0.5f});
    halfScale.setVolume(volume);
    halfScale.setTransferFunction(test::blobsTransferFunction());
    const Image expected = render(halfScale);

    VolumeScatteringRenderer renderer(options);
    renderer.setVolume(volume);
    renderer.setTransferFunction(test::blobsTransferFunction());
    // Room for everything but a full-resolution light volume (64^3 RGBA16F = 2 MiB); the
    // half-resolution one (256 kiB) and the frame's own textures fit.
    BudgetScope budget(gpuMemoryInUse() + 1024u * 1024u);
    LogCapture log;
    const Image image = render(renderer);
    CHECK(renderer.lightVolumeScaleInUse() == 0.5f);
    REQUIRE(log.warnings.size() == 1);
    CHECK_THAT(log.warnings[0], Contains("light volume") && Contains("64x64x64 RGBA16F") && Contains("budget") &&
                                    Contains("falls back to 32x32x32"));
    // The fallback renders exactly what lightVolumeScale 0.5 renders.
    REQUIRE(image.width() == expected.width());
    CHECK(image.data() == expected.data());

    VolumeScatteringRenderer strict({.shading = VolumeShading::Scattering, .jitter = false,
                                     .lightVolumeFallback = LightVolumeFallback::Fail});
    setGpuMemoryBudget(0);
    strict.setVolume(volume);
    strict.setTransferFunction(test::blobsTransferFunction());
    setGpuMemoryBudget(gpuMemoryInUse() + 1024u * 1024u);
    REQUIRE_SSS_ERROR(render(strict), ErrorKind::GpuLimit,
                      Contains("light volume") && Contains("64x64x64 RGBA16F") && Contains("budget"));
    gl.requireNoErrors();
}

TEST_CASE("a gradient volume that does not fit falls back to on-the-fly gradients with a warning", "[gl][limits]") {
    test::GlTestScope gl;
    const Volume volume = makeBlobsVolume(64);  // gradient volume: 2 MiB
    const Camera camera = test::orbitCamera(volume.worldBounds(), 30.0f, 20.0f);
    auto render = [&](VolumeScatteringRenderer& r) {
        r.setVolume(volume);
        r.setTransferFunction(test::blobsTransferFunction());
        RenderTarget target(64, 36);
        target.clear({0, 0, 0, 1});
        r.render(camera, target);
        return target.readColor();
    };
    VolumeScatteringRenderer onTheFly({.shading = VolumeShading::Gradient, .gradientVolume = false});
    const Image expected = render(onTheFly);
    LogCapture log;
    Image fallback(1, 1);
    VolumeScatteringRenderer renderer({.shading = VolumeShading::Gradient});
    {
        // The volume itself (256 KiB) and the pre-integration table (1 MiB) fit, its gradients
        // (2 MiB) do not.
        BudgetScope budget(gpuMemoryInUse() + 1792 * 1024);
        fallback = render(renderer);
    }
    CHECK(renderer.gradientVolumeBytes() == 0u);
    REQUIRE(log.warnings.size() == 1u);
    CHECK_THAT(log.warnings[0], Contains("gradient volume") && Contains("computed on the fly"));
    CHECK(computeErrorMetrics(fallback, expected).relRmse == 0.0);
    gl.requireNoErrors();
}

TEST_CASE("a buffer larger than one storage block is an error naming it, not a wrong picture", "[gl][limits]") {
    // Past GL_MAX_SHADER_STORAGE_BLOCK_SIZE a shader's reads and writes through the binding are
    // undefined (llvmpipe: 128 MiB, its offsets wrap past 2 GiB) and GL reports nothing.
    test::GlTestScope gl;
    {
        gl::StorageBlockLimitForTesting limit(4096);
        const gl::Buffer large = gl::Buffer::create(8192, nullptr, 0, "test storage");
        REQUIRE_SSS_ERROR(large.bindStorage(0), ErrorKind::GpuLimit,
                          Contains("test storage") && Contains("8 kiB") && Contains("4 kiB") &&
                              Contains("GL_MAX_SHADER_STORAGE_BLOCK_SIZE"));
        gl::Buffer::create(4096, nullptr, 0, "test storage at the limit").bindStorage(0);
    }
    gl::Buffer::create(8192, nullptr, 0, "test storage").bindStorage(0);  // within the device's own limit
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
    gl.requireNoErrors();
}

TEST_CASE("a mesh whose vertices do not fit one storage block fails to render with the limit named",
          "[gl][limits][mesh]") {
    test::GlTestScope gl;
    const Mesh mesh = makeUvSphere(48, 32);  // 1490 vertices of 32 bytes: 46.6 kiB
    MeshRenderOptions options;
    options.shading = MeshShading::Scattering;
    options.combine = MeshCombine::VertexEstimate;
    Camera camera;
    camera.setDistance(3.2f);
    RenderTarget target(48, 32);
    const auto render = [&] {
        MeshScatteringRenderer renderer(options);
        renderer.setMesh(mesh, glm::mat4(1.0f));
        renderer.setScatteringMaterial(materialPreset("potato"));
        renderer.setLights({DirectionalLight{.direction = {-0.6f, -0.5f, -1.0f}}});
        target.clear({0, 0, 0, 0});
        renderer.render(camera, target);
    };
    {
        gl::StorageBlockLimitForTesting limit(16 * 1024);
        REQUIRE_SSS_ERROR(render(), ErrorKind::GpuLimit,
                          Contains("mesh vertices: 46.6 kiB") && Contains("(16 kiB)") &&
                              Contains("GL_MAX_SHADER_STORAGE_BLOCK_SIZE"));
    }
    // Within the device's limit the same scene draws the sphere.
    render();
    CHECK(test::channelSums(target.readColor()).x > 0.0);
    gl.requireNoErrors();
}
