#include "sss/image.h"
#include "sss/image_compare.h"

#include "test_helpers.h"

#include <cmath>
#include <limits>

using Catch::Contains;
using sss::ErrorKind;
using sss::Image;
using sss::Image8;

TEST_CASE("Image stores RGBA floats row by row from the top", "[cpu]") {
    Image img(3, 2, {0.1f, 0.2f, 0.3f, 0.4f});
    CHECK(img.width() == 3);
    CHECK(img.height() == 2);
    REQUIRE(img.data().size() == 24);
    CHECK(img.at(2, 1) == glm::vec4(0.1f, 0.2f, 0.3f, 0.4f));
    img.at(1, 0) = {1, 2, 3, 4};
    CHECK(img.data()[4] == 1.0f);
    CHECK(img.data()[7] == 4.0f);
    img.at(0, 1).g = 9.0f;
    CHECK(img.data()[3 * 4 + 1] == 9.0f);
    const Image& c = img;
    CHECK(c.at(1, 0).z == 3.0f);

    const Image flipped = img.flippedVertically();
    CHECK(flipped.at(1, 1) == glm::vec4(1, 2, 3, 4));
    CHECK(flipped.at(0, 0).g == 9.0f);
    CHECK(flipped.at(1, 0) == glm::vec4(0.1f, 0.2f, 0.3f, 0.4f));

    REQUIRE_SSS_ERROR(img.at(3, 0), ErrorKind::InvalidArgument, Contains("(3, 0)") && Contains("3x2"));
    REQUIRE_SSS_ERROR(img.at(0, -1), ErrorKind::InvalidArgument, Contains("outside"));
}

TEST_CASE("Image constructors validate the size", "[cpu]") {
    REQUIRE_SSS_ERROR(Image(0, 4), ErrorKind::InvalidArgument, Contains("Image") && Contains("0x4"));
    REQUIRE_SSS_ERROR(Image(4, 16385), ErrorKind::InvalidArgument, Contains("16384") && Contains("4x16385"));
    REQUIRE_SSS_ERROR(Image8(-1, 4), ErrorKind::InvalidArgument, Contains("Image8") && Contains("-1x4"));
    CHECK_NOTHROW(Image8(16384, 1));
}

TEST_CASE("Image <-> Image8 conversion clamps and rounds without gamma", "[cpu]") {
    Image img(2, 1);
    img.at(0, 0) = {-0.5f, 0.5f, 1.2f, std::numeric_limits<float>::quiet_NaN()};
    img.at(1, 0) = {0.2f, 1.0f / 255.0f, 0.499f / 255.0f, 254.6f / 255.0f};
    const Image8 b = img.toRgba8();
    CHECK(b.at(0, 0) == glm::u8vec4(0, 128, 255, 0));
    CHECK(b.at(1, 0) == glm::u8vec4(51, 1, 0, 255));

    Image8 e(2, 2, {10, 20, 30, 40});
    e.at(1, 1) = {255, 0, 128, 255};
    const Image f = e.toFloat();
    CHECK(f.at(0, 0).r == Approx(10.0f / 255.0f));
    CHECK(f.at(1, 1) == glm::vec4(1.0f, 0.0f, 128.0f / 255.0f, 1.0f));
    CHECK(f.toRgba8().data() == e.data());  // exact round trip
    CHECK(e.flippedVertically().at(1, 0) == glm::u8vec4(255, 0, 128, 255));
    CHECK(e.data()[1 * 2 * 4 + 1 * 4 + 2] == 128);  // row 1, column 1, blue
}

TEST_CASE("PNG save/load round trip is exact", "[cpu]") {
    sss::test::TempDir dir;
    Image8 img(7, 5);
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 7; ++x)
            img.at(x, y) = glm::u8vec4(x * 36, y * 60, (x * 7 + y * 13) % 256, 255 - x * y * 5);
    const auto path = dir.path() / "round.png";
    img.savePng(path);
    const Image8 back = Image8::loadPng(path);
    CHECK(back.width() == 7);
    CHECK(back.height() == 5);
    CHECK(back.data() == img.data());

    // Float images go through toRgba8.
    Image f(2, 2, {0.5f, 0.25f, 1.0f, 1.0f});
    f.savePng(dir.path() / "float.png");
    CHECK(Image8::loadPng(dir.path() / "float.png").at(1, 1) == glm::u8vec4(128, 64, 255, 255));
}

TEST_CASE("PNG errors name the file", "[cpu]") {
    sss::test::TempDir dir;
    const auto missing = dir.path() / "missing.png";
    REQUIRE_SSS_ERROR(Image8::loadPng(missing), ErrorKind::Io, Contains(missing.string()) && Contains("does not exist"));
    const auto garbage = dir.write("garbage.png", "this is not a png");
    REQUIRE_SSS_ERROR(Image8::loadPng(garbage), ErrorKind::Parse,
                      Contains(garbage.string()) && Contains("cannot decode image: "));
    const auto noDir = dir.path() / "no" / "such" / "dir" / "out.png";
    REQUIRE_SSS_ERROR(Image8(2, 2).savePng(noDir), ErrorKind::Io, Contains(noDir.string()) && Contains("does not exist"));
    REQUIRE_SSS_ERROR(Image(2, 2).savePng(noDir), ErrorKind::Io, Contains(noDir.string()));
}

TEST_CASE("compareImages on hand-made images", "[cpu]") {
    Image8 expected(2, 2, {100, 100, 100, 255});
    Image8 actual = expected;
    auto same = sss::compareImages(actual, expected);
    CHECK(same.maxChannelDelta == 0);
    CHECK(same.differingFraction == 0.0);
    CHECK(same.meanAbsDelta == 0.0);
    CHECK(same.width == 2);
    CHECK(same.height == 2);

    actual.at(0, 0).g = 110;  // delta 10
    actual.at(1, 1).a = 254;  // delta 1: within the default threshold
    auto d = sss::compareImages(actual, expected);
    CHECK(d.maxChannelDelta == 10);
    CHECK(d.differingFraction == 0.25);
    CHECK(d.meanAbsDelta == Approx(11.0 / 16.0));
    auto strict = sss::compareImages(actual, expected, 0);
    CHECK(strict.differingFraction == 0.5);
    auto loose = sss::compareImages(actual, expected, 10);
    CHECK(loose.differingFraction == 0.0);
    CHECK(loose.maxChannelDelta == 10);

    REQUIRE_SSS_ERROR(sss::compareImages(Image8(3, 2), expected), ErrorKind::InvalidArgument,
                      Contains("3x2") && Contains("2x2"));
    REQUIRE_SSS_ERROR(sss::compareImages(actual, expected, -1), ErrorKind::InvalidArgument,
                      Contains("perPixelThreshold"));

    const Image8 diff = sss::diffImage(actual, expected);
    CHECK(diff.width() == 2);
    CHECK(diff.at(0, 0) == glm::u8vec4(255, 0, 0, 255));  // the largest delta is full red
    CHECK(diff.at(1, 0) == glm::u8vec4(60, 60, 60, 255));  // 0.6 * luminance 100
    CHECK(diff.at(1, 1) == glm::u8vec4(60, 60, 60, 255));  // within threshold
    REQUIRE_SSS_ERROR(sss::diffImage(actual, Image8(1, 1)), ErrorKind::InvalidArgument, Contains("1x1"));
}

TEST_CASE("computeErrorMetrics over RGB", "[cpu]") {
    Image ref(1, 1, {0.5f, 0.5f, 0.5f, 1.0f});
    Image test(1, 1, {0.5f, 0.5f, 0.8f, 0.0f});  // alpha differs but is ignored
    const auto m = sss::computeErrorMetrics(test, ref);
    CHECK(m.relRmse == Approx(std::sqrt(0.09 / 0.75)).epsilon(1e-5));
    CHECK(m.psnr == Approx(10.0 * std::log10(0.25 / 0.03)).epsilon(1e-5));
    CHECK(m.maxAbsError == Approx(0.3).epsilon(1e-5));

    const auto same = sss::computeErrorMetrics(ref, ref);
    CHECK(same.relRmse == 0.0);
    CHECK(std::isinf(same.psnr));
    CHECK(same.maxAbsError == 0.0);

    Image wide(2, 1, {1.0f, 1.0f, 1.0f, 1.0f});
    Image wideTest = wide;
    wideTest.at(1, 0).r = 0.0f;
    const auto w = sss::computeErrorMetrics(wideTest, wide);
    CHECK(w.relRmse == Approx(std::sqrt(1.0 / 6.0)));
    CHECK(w.psnr == Approx(10.0 * std::log10(6.0)));

    REQUIRE_SSS_ERROR(sss::computeErrorMetrics(Image(1, 2), ref), ErrorKind::InvalidArgument,
                      Contains("1x2") && Contains("1x1"));
}

TEST_CASE("computeErrorMetrics: specks, and those bright enough to see", "[cpu]") {
    // 100 covered pixels: 90 lit at 1, 10 in deep shadow at 1e-3 (0.1 % of the 99th percentile).
    // The test is dark (below half the reference) at 3 lit and 6 shadowed pixels; the background
    // pixel and a pixel whose reference is black never count.
    Image ref(102, 1, {1.0f, 1.0f, 1.0f, 1.0f});
    for (int x = 90; x < 100; ++x) ref.at(x, 0) = {1e-3f, 1e-3f, 1e-3f, 1.0f};
    ref.at(100, 0) = {0.0f, 0.0f, 0.0f, 1.0f};
    ref.at(101, 0) = {1.0f, 1.0f, 1.0f, 0.0f};
    Image test = ref;
    for (int x : {0, 1, 2, 90, 91, 92, 93, 94, 95}) test.at(x, 0) *= glm::vec4(0.4f, 0.4f, 0.4f, 1.0f);
    test.at(3, 0) *= glm::vec4(0.6f, 0.6f, 0.6f, 1.0f);  // above half: no speck
    test.at(101, 0) = {0.0f, 0.0f, 0.0f, 0.0f};
    const auto m = sss::computeErrorMetrics(test, ref);
    CHECK(m.speckShare == Approx(9.0 / 100.0));
    CHECK(m.visibleSpeckShare == Approx(3.0 / 90.0));
    const auto same = sss::computeErrorMetrics(ref, ref);
    CHECK(same.speckShare == 0.0);
    CHECK(same.visibleSpeckShare == 0.0);
}

TEST_CASE("resolvedSpeckShare: only pixels the reference knows to four standard errors", "[cpu]") {
    // 10 covered pixels, all dark in the test (0.4x). The reference's standard error is a fifth
    // of its value at 4 pixels (resolved), a third at 3 (not), and a fifth in one channel only
    // but larger in another at 1 (luminance-weighted: not); 2 have a black reference or none.
    Image ref(10, 1, {1.0f, 1.0f, 1.0f, 1.0f});
    ref.at(8, 0) = {0.0f, 0.0f, 0.0f, 1.0f};
    ref.at(9, 0) = {1.0f, 1.0f, 1.0f, 0.0f};
    Image error(10, 1, {0.2f, 0.2f, 0.2f, 0.0f});
    for (int x : {4, 5, 6}) error.at(x, 0) = {0.34f, 0.34f, 0.34f, 0.0f};
    error.at(7, 0) = {0.2f, 0.4f, 0.2f, 0.0f};  // green dominates the luminance
    Image test = ref;
    for (int x = 0; x < 10; ++x) test.at(x, 0) *= glm::vec4(0.4f, 0.4f, 0.4f, 1.0f);
    test.at(0, 0) = ref.at(0, 0);  // one resolved pixel that is right
    CHECK(sss::resolvedSpeckShare(test, ref, error) == Approx(3.0 / 4.0));
    CHECK(sss::resolvedSpeckShare(ref, ref, error) == 0.0);
    REQUIRE_SSS_ERROR(sss::resolvedSpeckShare(test, ref, Image(2, 1)), ErrorKind::InvalidArgument,
                      Contains("referenceStandardError") && Contains("2x1"));
}
