// The colour pipeline's CPU half: the display transform (include/sss/display.h) and OpenEXR I/O.
#include "sss/display.h"
#include "sss/image.h"
#include "test_helpers.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <random>

using namespace sss;
using Catch::Matchers::Contains;

TEST_CASE("display transform: linear mid-grey 0.18 becomes sRGB code 118, once", "[cpu][display]") {
    // sRGB(0.18) = 1.055 * 0.18^(1/2.4) - 0.055 = 0.46136 -> 117.65 -> 118. Encoding twice would
    // give 183 (sRGB(0.46136) = 0.7174), not encoding at all 46: both fail here.
    Image grey(4, 2, glm::vec4(0.18f, 0.18f, 0.18f, 1.0f));
    const Image8 out = toDisplay(grey);
    REQUIRE(out.at(1, 1) == glm::u8vec4(118, 118, 118, 255));
    CHECK(std::abs(applyDisplayTransform(glm::vec3(0.18f)).x - 0.461356f) < 1e-5f);
    // The linear segment near black and the ends.
    CHECK(std::abs(applyDisplayTransform(glm::vec3(0.002f)).x - 12.92f * 0.002f) < 1e-7f);
    CHECK(applyDisplayTransform(glm::vec3(0.0f)).x == 0.0f);
    CHECK(applyDisplayTransform(glm::vec3(1.0f)).x == 1.0f);
    CHECK(applyDisplayTransform(glm::vec3(-1.0f, 7.0f, std::nanf(""))) == glm::vec3(0.0f, 1.0f, 0.0f));
}

TEST_CASE("display transform: exposure scales by 2^stops, sRGB can be turned off", "[cpu][display]") {
    const DisplayTransform plusOne{.exposure = 1.0f};
    CHECK(applyDisplayTransform(glm::vec3(0.09f), plusOne).x == applyDisplayTransform(glm::vec3(0.18f)).x);
    const DisplayTransform linear{.srgb = false};
    CHECK(applyDisplayTransform(glm::vec3(0.25f), linear).x == 0.25f);
    REQUIRE_SSS_ERROR(toDisplay(Image(1, 1), DisplayTransform{.exposure = std::nanf("")}), ErrorKind::InvalidArgument,
                      Contains("exposure"));
}

TEST_CASE("display transform: the filmic curve rolls highlights off and is monotonic", "[cpu][display]") {
    const DisplayTransform filmic{.toneMap = ToneMap::Filmic, .srgb = false};
    // Narkowicz's fit: f(x) = x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14).
    const float x = 0.5f, expected = x * (2.51f * x + 0.03f) / (x * (2.43f * x + 0.59f) + 0.14f);
    CHECK(std::abs(applyDisplayTransform(glm::vec3(x), filmic).x - expected) < 1e-6f);
    float previous = -1.0f;
    for (float v = 0.0f; v < 64.0f; v = v * 1.1f + 0.01f) {
        const float y = applyDisplayTransform(glm::vec3(v), filmic).x;
        REQUIRE(y >= previous);
        REQUIRE(y <= 1.0f);
        previous = y;
    }
    CHECK(applyDisplayTransform(glm::vec3(4.0f), filmic).x < 1.0f);       // no hard clip at 1
    CHECK(applyDisplayTransform(glm::vec3(4.0f), {.srgb = false}).x == 1.0f);  // None clips
    CHECK(parseToneMap("filmic") == ToneMap::Filmic);
    CHECK(std::string(toneMapName(ToneMap::Filmic)) == "filmic");
    REQUIRE_SSS_ERROR(parseToneMap("aces"), ErrorKind::InvalidArgument, Contains("aces"));
}

TEST_CASE("OpenEXR round trip returns the linear values exactly", "[cpu][display][exr]") {
    sss::test::TempDir dir;
    Image image(37, 23);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> value(-2.0f, 50.0f);
    for (float& v : image.data()) v = value(rng);
    image.at(0, 0) = glm::vec4(1e-30f, 3.4e38f, 0.18f, 0.0f);
    const auto path = dir.path() / "linear.exr";
    image.saveExr(path);
    const Image back = Image::loadExr(path);
    REQUIRE(back.width() == 37);
    REQUIRE(back.height() == 23);
    REQUIRE(back.data() == image.data());

    REQUIRE_SSS_ERROR(Image::loadExr(dir.path() / "missing.exr"), ErrorKind::Io, Contains("missing.exr"));
    const auto garbage = dir.write("garbage.exr", "this is not an OpenEXR file");
    REQUIRE_SSS_ERROR(Image::loadExr(garbage), ErrorKind::Parse, Contains("garbage.exr"));
    REQUIRE_SSS_ERROR(image.saveExr(dir.path() / "no_such_dir" / "x.exr"), ErrorKind::Io, Contains("x.exr"));
}
