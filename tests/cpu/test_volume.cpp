#include "sss/volume.h"

#include "test_helpers.h"

#include <cmath>
#include <limits>
#include <numeric>

using Catch::Contains;
using sss::ErrorKind;
using sss::RawLoadOptions;
using sss::Volume;
using sss::VoxelType;

TEST_CASE("parseRawVolumeName reads dims and type from file names", "[cpu]") {
    auto bonsai = sss::parseRawVolumeName("bonsai_256x256x256_uint8.raw");
    REQUIRE(bonsai);
    CHECK(bonsai->dims == glm::ivec3(256, 256, 256));
    CHECK(bonsai->type == VoxelType::UInt8);
    CHECK(bonsai->spacing == glm::vec3(1.0f));

    auto ct = sss::parseRawVolumeName("invesalius_cthead_256x256x108_uint16.raw");
    REQUIRE(ct);
    CHECK(ct->dims == glm::ivec3(256, 256, 108));
    CHECK(ct->type == VoxelType::UInt16);

    auto dimsOnly = sss::parseRawVolumeName("foot_64x32x16.raw");
    REQUIRE(dimsOnly);
    CHECK(dimsOnly->dims == glm::ivec3(64, 32, 16));
    CHECK(dimsOnly->type == VoxelType::UInt8);

    // Directories are ignored, even if they look like tokens.
    auto withDir = Volume::parseRawVolumeName("/data/9x9x9_uint16/engine_4x5x6_UINT16.raw");
    REQUIRE(withDir);
    CHECK(withDir->dims == glm::ivec3(4, 5, 6));
    CHECK(withDir->type == VoxelType::UInt16);

    CHECK_FALSE(sss::parseRawVolumeName("bucky.raw"));
    CHECK_FALSE(sss::parseRawVolumeName("bucky_32x32_uint8.raw"));
    CHECK_FALSE(sss::parseRawVolumeName("bucky_32x-2x4_uint8.raw"));
    CHECK_FALSE(sss::parseRawVolumeName("bucky_32x32x32x_uint8.raw"));
    CHECK_FALSE(sss::parseRawVolumeName(""));
}

TEST_CASE("Volume::loadRaw loads 8-bit data with x fastest", "[cpu]") {
    sss::test::TempDir dir;
    std::vector<uint8_t> bytes(4 * 3 * 2);
    std::iota(bytes.begin(), bytes.end(), uint8_t(10));
    const auto path = sss::test::writeBytes(dir, "t_4x3x2_uint8.raw", bytes);
    const Volume v = Volume::loadRaw(path);
    CHECK(v.dims() == glm::ivec3(4, 3, 2));
    CHECK(v.type() == VoxelType::UInt8);
    CHECK(v.voxelCount() == 24);
    CHECK(v.bytes() == bytes);
    CHECK(v.valueAt(0, 0, 0) == 10);
    CHECK(v.valueAt(1, 0, 0) == 11);
    CHECK(v.valueAt(0, 1, 0) == 14);
    CHECK(v.valueAt(0, 0, 1) == 22);
    CHECK(v.valueAt(3, 2, 1) == 33);
    CHECK(v.normalizedAt(3, 2, 1) == Approx(33.0f / 255.0f));
    CHECK(v.valueRange() == std::pair<double, double>(10, 33));
    const auto h = v.histogram();
    REQUIRE(h.size() == 256);
    CHECK(h[9] == 0);
    CHECK(h[10] == 1);
    CHECK(h[33] == 1);
    CHECK(std::accumulate(h.begin(), h.end(), 0u) == 24u);
    const auto h4 = v.histogram(4);  // bins of 64 values: all of 10..33 fall in bin 0
    CHECK(h4 == std::vector<uint32_t>{24, 0, 0, 0});
    REQUIRE_SSS_ERROR(v.histogram(0), ErrorKind::InvalidArgument, Contains("bins") && Contains("got 0"));
    REQUIRE_SSS_ERROR(v.valueAt(4, 0, 0), ErrorKind::InvalidArgument, Contains("(4, 0, 0)") && Contains("4x3x2"));
    REQUIRE_SSS_ERROR(v.normalizedAt(0, -1, 0), ErrorKind::InvalidArgument, Contains("outside"));
}

TEST_CASE("Volume::loadRaw loads 16-bit little-endian data", "[cpu]") {
    sss::test::TempDir dir;
    // 2x2x1 voxels: 0x1234, 0x0001, 0xFFFF, 0x0100.
    const std::vector<uint8_t> bytes = {0x34, 0x12, 0x01, 0x00, 0xFF, 0xFF, 0x00, 0x01};
    const Volume v = Volume::loadRaw(sss::test::writeBytes(dir, "ct_2x2x1_uint16.raw", bytes));
    CHECK(v.type() == VoxelType::UInt16);
    CHECK(v.valueAt(0, 0, 0) == 0x1234);
    CHECK(v.valueAt(1, 0, 0) == 1);
    CHECK(v.valueAt(0, 1, 0) == 0xFFFF);
    CHECK(v.valueAt(1, 1, 0) == 0x0100);
    CHECK(v.normalizedAt(0, 0, 0) == Approx(4660.0f / 65535.0f));
    CHECK(v.normalizedAt(0, 1, 0) == 1.0f);
    CHECK(v.valueRange() == std::pair<double, double>(1, 0xFFFF));
    const auto h = v.histogram(256);  // 256 values per bin
    CHECK(h[0] == 1);     // 1
    CHECK(h[1] == 1);     // 0x0100
    CHECK(h[0x12] == 1);  // 0x1234
    CHECK(h[255] == 1);   // 0xFFFF
}

TEST_CASE("Volume::transferFunctionRange: 0..255 for 8-bit data, the data's min..max for 16-bit data", "[cpu]") {
    const std::vector<uint8_t> bytes8 = {10, 20, 30, 40};
    CHECK(Volume::fromData({4, 1, 1}, VoxelType::UInt8, bytes8).transferFunctionRange() ==
          std::pair<double, double>(0.0, 255.0));
    // 1000, 4000
    const std::vector<uint8_t> bytes16 = {0xe8, 0x03, 0xa0, 0x0f};
    CHECK(Volume::fromData({2, 1, 1}, VoxelType::UInt16, bytes16).transferFunctionRange() ==
          std::pair<double, double>(1000.0, 4000.0));
    // All voxels equal: the range is one value wide, also at the top of the type.
    const std::vector<uint8_t> flat = {0xff, 0xff, 0xff, 0xff};
    CHECK(Volume::fromData({2, 1, 1}, VoxelType::UInt16, flat).transferFunctionRange() ==
          std::pair<double, double>(65535.0, 65536.0));
}

TEST_CASE("Volume::histogram over a range bins only the values inside it", "[cpu]") {
    // 16-bit values 1000..4000, one voxel each.
    std::vector<uint8_t> bytes;
    for (int v = 1000; v <= 4000; ++v) {
        bytes.push_back(static_cast<uint8_t>(v & 0xff));
        bytes.push_back(static_cast<uint8_t>(v >> 8));
    }
    const Volume v = Volume::fromData({3001, 1, 1}, VoxelType::UInt16, bytes);
    // Over 0..8000 in 8 bins of 1000: 1000..1999, 2000..2999, 3000..3999 and 4000 alone.
    CHECK(v.histogram(8, {0.0, 8000.0}) == std::vector<uint32_t>{0, 1000, 1000, 1000, 1, 0, 0, 0});
    // Over the data's own range every bin is filled; hi falls in the last bin.
    CHECK(v.histogram(3, {1000.0, 4000.0}) == std::vector<uint32_t>{1000, 1000, 1001});
    // Values outside are left out, on both sides.
    CHECK(v.histogram(2, {2000.0, 2999.0}) == std::vector<uint32_t>{500, 500});
    // Over the whole type range (histogram(bins)) they crowd into the first bins.
    const auto whole = v.histogram(16);  // bins of 4096 values: everything in bin 0
    CHECK(whole[0] == 3001);

    const Volume v8 = Volume::fromData({4, 1, 1}, VoxelType::UInt8, std::vector<uint8_t>{0, 100, 200, 255});
    CHECK(v8.histogram(2, v8.transferFunctionRange()) == std::vector<uint32_t>{2, 2});

    REQUIRE_SSS_ERROR(v.histogram(0, {0.0, 1.0}), ErrorKind::InvalidArgument, Contains("got 0"));
    REQUIRE_SSS_ERROR(v.histogram(4, {5.0, 5.0}), ErrorKind::InvalidArgument, Contains("lo < hi") && Contains("(5, 5)"));
    REQUIRE_SSS_ERROR(v.histogram(4, {0.0, std::numeric_limits<double>::infinity()}), ErrorKind::InvalidArgument,
                      Contains("finite"));
}

TEST_CASE("RawLoadOptions override the file name", "[cpu]") {
    sss::test::TempDir dir;
    const std::vector<uint8_t> bytes(8 * 2 * 1, 7);
    // The name says 4x4x1 uint8 (16 bytes): options reinterpret the same 16 bytes.
    const auto path = sss::test::writeBytes(dir, "v_4x4x1_uint8.raw", bytes);
    RawLoadOptions opt;
    opt.dims = glm::ivec3(4, 2, 1);
    opt.type = VoxelType::UInt16;
    opt.spacing = glm::vec3(1.0f, 2.0f, 4.0f);
    const Volume v = Volume::loadRaw(path, opt);
    CHECK(v.dims() == glm::ivec3(4, 2, 1));
    CHECK(v.type() == VoxelType::UInt16);
    CHECK(v.valueAt(0, 0, 0) == 0x0707);
    CHECK(v.spacing() == glm::vec3(1, 2, 4));
    // Extent 4 x 4 x 4 -> a unit cube.
    CHECK(v.worldBounds().min == glm::vec3(-0.5f));
    CHECK(v.worldBounds().max == glm::vec3(0.5f));

    // No name token: options alone are enough.
    const auto plain = sss::test::writeBytes(dir, "plain.raw", bytes);
    RawLoadOptions dimsOnly;
    dimsOnly.dims = glm::ivec3(16, 1, 1);
    CHECK(Volume::loadRaw(plain, dimsOnly).type() == VoxelType::UInt8);
}

TEST_CASE("Volume::worldBounds: largest side 1, centred, proportional", "[cpu]") {
    const Volume v = Volume::fromData({4, 2, 1}, VoxelType::UInt8, std::vector<uint8_t>(8, 0));
    const sss::Bounds b = v.worldBounds();
    CHECK(b.center() == glm::vec3(0.0f));
    CHECK(b.size() == glm::vec3(1.0f, 0.5f, 0.25f));
    const Volume s = Volume::fromData({4, 2, 1}, VoxelType::UInt8, std::vector<uint8_t>(8, 0), {1, 4, 2});
    CHECK(s.worldBounds().size() == glm::vec3(0.5f, 1.0f, 0.25f));
}

TEST_CASE("Volume::loadRaw reports bad input with the file and the problem", "[cpu]") {
    sss::test::TempDir dir;
    const auto shortFile = sss::test::writeBytes(dir, "x_4x4x4_uint8.raw", std::vector<uint8_t>(60, 1));
    REQUIRE_SSS_ERROR(Volume::loadRaw(shortFile), ErrorKind::Parse,
                      Contains("Volume::loadRaw") && Contains(shortFile.string()) && Contains("file has 60 bytes") &&
                          Contains("expected 64 for 4x4x4 uint8"));

    const auto shortFile16 = sss::test::writeBytes(dir, "x_4x4x4_uint16.raw", std::vector<uint8_t>(64, 1));
    REQUIRE_SSS_ERROR(Volume::loadRaw(shortFile16), ErrorKind::Parse,
                      Contains("x_4x4x4_uint16.raw") && Contains("expected 128 for 4x4x4 uint16"));

    const auto missing = dir.path() / "gone_4x4x4_uint8.raw";
    REQUIRE_SSS_ERROR(Volume::loadRaw(missing), ErrorKind::Io, Contains(missing.string()) && Contains("does not exist"));

    const auto noDims = sss::test::writeBytes(dir, "nodims.raw", std::vector<uint8_t>(8, 1));
    REQUIRE_SSS_ERROR(Volume::loadRaw(noDims), ErrorKind::InvalidArgument,
                      Contains("nodims.raw") && Contains("dimensions unknown") && Contains("RawLoadOptions::dims"));

    const auto zero = sss::test::writeBytes(dir, "z_0x4x4_uint8.raw", {});
    REQUIRE_SSS_ERROR(Volume::loadRaw(zero), ErrorKind::InvalidArgument,
                      Contains("z_0x4x4_uint8.raw") && Contains("dims must be positive") && Contains("0x4x4"));

    RawLoadOptions negative;
    negative.dims = glm::ivec3(2, -2, 2);
    REQUIRE_SSS_ERROR(Volume::loadRaw(noDims, negative), ErrorKind::InvalidArgument,
                      Contains("nodims.raw") && Contains("2x-2x2"));

    const auto huge = sss::test::writeBytes(dir, "h_9000x4x4_uint8.raw", {});
    REQUIRE_SSS_ERROR(Volume::loadRaw(huge), ErrorKind::InvalidArgument,
                      Contains("h_9000x4x4_uint8.raw") && Contains("too large") && Contains("8192"));

    const auto tooMuch = sss::test::writeBytes(dir, "h_8192x8192x8192_uint16.raw", {});
    REQUIRE_SSS_ERROR(Volume::loadRaw(tooMuch), ErrorKind::InvalidArgument,
                      Contains("h_8192x8192x8192_uint16.raw") && Contains("1024 GiB") && Contains("4 GiB limit"));

    const auto ok = sss::test::writeBytes(dir, "ok_2x2x2_uint8.raw", std::vector<uint8_t>(8, 1));
    RawLoadOptions badSpacing;
    badSpacing.spacing = glm::vec3(1.0f, 0.0f, 1.0f);
    REQUIRE_SSS_ERROR(Volume::loadRaw(ok, badSpacing), ErrorKind::InvalidArgument,
                      Contains("ok_2x2x2_uint8.raw") && Contains("spacing must be finite and > 0"));
    badSpacing.spacing = glm::vec3(1.0f, std::numeric_limits<float>::quiet_NaN(), 1.0f);
    REQUIRE_SSS_ERROR(Volume::loadRaw(ok, badSpacing), ErrorKind::InvalidArgument, Contains("spacing"));
    // Found by fuzzing (tests/fuzz): sides 1e7 apart made worldBounds() degenerate, and a
    // spacing near FLT_MAX made it NaN.
    badSpacing.spacing = glm::vec3(1.0f, 1.0f, 3e38f);
    REQUIRE_SSS_ERROR(Volume::loadRaw(ok, badSpacing), ErrorKind::InvalidArgument,
                      Contains("ok_2x2x2_uint8.raw") && Contains("differ by a factor of 3e+38") && Contains("1e6"));
    badSpacing.spacing = glm::vec3(1e-7f, 1.0f, 1.0f);
    REQUIRE_SSS_ERROR(Volume::loadRaw(ok, badSpacing), ErrorKind::InvalidArgument, Contains("at most 1e6"));
    for (const glm::vec3 spacing : {glm::vec3(3e38f), glm::vec3(1e-30f, 1e-30f, 1e-25f)}) {
        RawLoadOptions scaled;
        scaled.spacing = spacing;
        const sss::Bounds b = Volume::loadRaw(ok, scaled).worldBounds();
        INFO("spacing " << spacing.x << ", " << spacing.y << ", " << spacing.z);
        REQUIRE(std::isfinite(b.radius()));
        REQUIRE(b.size().x > 0.0f);
        REQUIRE(std::max({b.size().x, b.size().y, b.size().z}) == 1.0f);
    }
}

TEST_CASE("Volume::fromData validates its arguments", "[cpu]") {
    REQUIRE_SSS_ERROR(Volume::fromData({2, 2, 2}, VoxelType::UInt16, std::vector<uint8_t>(8)),
                      ErrorKind::InvalidArgument,
                      Contains("Volume::fromData") && Contains("8 bytes") && Contains("expected 16 for 2x2x2 uint16"));
    REQUIRE_SSS_ERROR(Volume::fromData({0, 2, 2}, VoxelType::UInt8, {}), ErrorKind::InvalidArgument,
                      Contains("Volume::fromData") && Contains("dims must be positive"));
    REQUIRE_SSS_ERROR(Volume::fromData({1, 1, 1}, VoxelType::UInt8, {0}, {-1, 1, 1}), ErrorKind::InvalidArgument,
                      Contains("Volume::fromData") && Contains("spacing") && Contains("-1"));
    const Volume v = Volume::fromData({1, 1, 1}, VoxelType::UInt8, {200});
    CHECK(v.valueRange() == std::pair<double, double>(200, 200));
}
