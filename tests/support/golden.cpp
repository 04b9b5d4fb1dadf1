#include "support/golden.h"

#include "support/gl_test.h"

#include <catch2/catch.hpp>
#include <sss/display.h>
#include <sss/error.h>
#include <sss/image_compare.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>

namespace sss::test {

void requireMatchesGolden(const Image& linear, const std::string& name, GoldenTolerance tolerance) {
    const Image8 actual = toDisplay(linear);
    // Goldens are made on Mesa's llvmpipe; other rasterisers round differently. ctest runs the
    // [golden] cases with SSS_EGL_SOFTWARE=1, which picks Mesa's software device on GPU machines.
    if (const ContextInfo& info = glContext().info(); !info.software)
        skipTest("golden images are compared on Mesa's llvmpipe only, and this context is " + info.renderer +
                 " (run with SSS_EGL_SOFTWARE=1 where Mesa is installed)");
    const std::filesystem::path golden = std::filesystem::path(SSS_GOLDEN_DIR) / (name + ".png");
    const std::filesystem::path outputDir = SSS_TEST_OUTPUT_DIR;
    std::filesystem::create_directories(outputDir);
    const char* update = std::getenv("SSS_UPDATE_GOLDENS");
    if (update && std::strcmp(update, "1") == 0) {
        std::filesystem::create_directories(golden.parent_path());
        actual.savePng(golden);
        WARN("SSS_UPDATE_GOLDENS=1: wrote " << golden.string());
        return;
    }
    const std::filesystem::path actualPath = outputDir / (name + ".actual.png");
    if (!std::filesystem::exists(golden)) {
        actual.savePng(actualPath);
        FAIL("missing golden image " << golden.string() << " (actual written to " << actualPath.string()
                                     << "; create it deliberately with SSS_UPDATE_GOLDENS=1)");
    }
    const Image8 expected = Image8::loadPng(golden);
    if (expected.width() != actual.width() || expected.height() != actual.height()) {
        actual.savePng(actualPath);
        FAIL("golden " << golden.string() << " is " << expected.width() << "x" << expected.height()
                       << " but the image is " << actual.width() << "x" << actual.height());
    }
    const ImageDifference d = compareImages(actual, expected, 1);
    const bool ok = d.maxChannelDelta <= tolerance.maxChannelDelta &&
                    d.differingFraction <= tolerance.maxDifferingFraction;
    INFO("golden " << name << ": max channel delta " << d.maxChannelDelta << " (allowed "
                   << tolerance.maxChannelDelta << "), differing pixels " << d.differingFraction * 100.0
                   << " % (allowed " << tolerance.maxDifferingFraction * 100.0 << " %), mean |delta| "
                   << d.meanAbsDelta);
    if (ok) {
        // Leftovers of an earlier failing run would otherwise suggest this case still fails.
        std::filesystem::remove(actualPath);
        std::filesystem::remove(outputDir / (name + ".diff.png"));
    } else {
        actual.savePng(actualPath);
        diffImage(actual, expected).savePng(outputDir / (name + ".diff.png"));
        INFO("wrote " << actualPath.string() << " and " << (outputDir / (name + ".diff.png")).string());
    }
    CHECK(d.maxChannelDelta <= tolerance.maxChannelDelta);
    REQUIRE(d.differingFraction <= tolerance.maxDifferingFraction);
}

}  // namespace sss::test
