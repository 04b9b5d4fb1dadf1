// ParaView JSON colour-map presets: TransferFunction::loadParaViewJson / saveParaViewJson.
#include "sss/transfer_function.h"

#include "test_helpers.h"

#include <glm/geometric.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

using Catch::Contains;
using sss::ErrorKind;
using sss::TransferFunction;

namespace {

// tests/data (the fixtures).
std::filesystem::path dataDir() { return SSS_TEST_DATA_DIR; }

void requireNear(glm::vec4 actual, glm::vec4 expected, float eps = 1e-5f) {
    INFO("actual = (" << actual.x << ", " << actual.y << ", " << actual.z << ", " << actual.w << "), expected = ("
                      << expected.x << ", " << expected.y << ", " << expected.z << ", " << expected.w << ")");
    REQUIRE(glm::length(actual - expected) < eps);
}

// Loading `json` from a temp file must fail with `kind` and a message containing `fragment`
// and the file name.
void requireLoadError(const std::string& json, ErrorKind kind, const std::string& fragment) {
    sss::test::TempDir dir;
    const std::filesystem::path file = dir.write("bad.json", json);
    INFO("file contents: " << json);
    REQUIRE_SSS_ERROR(TransferFunction::loadParaViewJson(file), kind, Contains(fragment) && Contains("bad.json"));
}

}  // namespace

TEST_CASE("ParaView JSON: save then load gives the same function", "[cpu]") {
    sss::test::TempDir dir;
    // Ends inside (0,1): saving must add the end nodes so the load maps x back unchanged.
    const TransferFunction inner({{0.2f, {1, 0, 0}, 0.0f},
                                  {0.33f, {0.1f, 0.7f, 0.3f}, 0.45f},
                                  {0.6f, {0, 1, 0}, 0.5f},
                                  {0.9f, {0.123456f, 0.654321f, 1}, 1.0f}});
    std::vector<TransferFunction> functions{inner, TransferFunction(), TransferFunction({{0.5f, {0.3f, 0.2f, 0.1f}, 0.7f}})};
    for (const std::string& name : TransferFunction::presetNames()) functions.push_back(TransferFunction::preset(name));
    for (std::size_t f = 0; f < functions.size(); ++f) {
        const std::filesystem::path file = dir.path() / ("tf" + std::to_string(f) + ".json");
        functions[f].saveParaViewJson(file, "round \"trip\" " + std::to_string(f));
        const TransferFunction loaded = TransferFunction::loadParaViewJson(file);
        INFO("function " << f);
        for (int i = 0; i <= 1000; ++i) {
            const float v = static_cast<float>(i) / 1000.0f;
            INFO("at " << v);
            requireNear(loaded.evaluate(v), functions[f].evaluate(v), 1e-6f);
        }
    }
}

TEST_CASE("ParaView JSON: the saved file is a ParaView preset array", "[cpu]") {
    sss::test::TempDir dir;
    const TransferFunction tf({{0.25f, {1, 0.5f, 0}, 0.1f}, {1.0f, {0, 0, 1}, 0.75f}});
    const std::filesystem::path file = dir.path() / "preset.json";
    tf.saveParaViewJson(file, "my map");
    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    const std::string s = text.str();
    CHECK_THAT(s, Contains("\"Name\": \"my map\""));
    CHECK_THAT(s, Contains("\"ColorSpace\": \"RGB\""));
    // An extra node at 0 (the function is constant below 0.25), then the two points.
    CHECK_THAT(s, Contains("\"RGBPoints\": [\n      0, 1, 0.5, 0,\n      0.25, 1, 0.5, 0,\n      1, 0, 0, 1\n    ]"));
    CHECK_THAT(s, Contains("\"Points\": [\n      0, 0.1, 0.5, 0,\n      0.25, 0.1, 0.5, 0,\n      1, 0.75, 0.5, 0\n    ]"));
    CHECK(s.front() == '[');
}

TEST_CASE("ParaView JSON: colour and opacity nodes at different x are merged", "[cpu]") {
    sss::test::TempDir dir;
    // Colour: red at 100 -> blue at 300. Opacity: 0 at 0, 0.2 at 150, 1 at 250 (data units).
    const std::filesystem::path file = dir.write("merge.json", R"({
        "Name": "merge", "ColorSpace": "Diverging",
        "RGBPoints": [100, 1, 0, 0,  300, 0, 0, 1],
        "Points": [0, 0, 0.5, 0,  150, 0.2, 0.5, 0,  250, 1, 0.7, 0.3]
    })");
    auto expected = [](double x) {  // the two curves in data units
        const double s = std::clamp((x - 100.0) / 200.0, 0.0, 1.0);
        double a = 1.0;
        if (x <= 150.0) a = 0.2 * x / 150.0;
        else if (x <= 250.0) a = 0.2 + 0.8 * (x - 150.0) / 100.0;
        return glm::vec4(static_cast<float>(1.0 - s), 0.0f, static_cast<float>(s), static_cast<float>(a));
    };

    SECTION("range from the file: 0..300") {
        const TransferFunction tf = TransferFunction::loadParaViewJson(file);
        // Union of {1/3, 1} and {0, 0.5, 5/6}.
        REQUIRE(tf.points().size() == 5);
        for (double x : {0.0, 50.0, 100.0, 125.0, 150.0, 200.0, 250.0, 280.0, 300.0}) {
            INFO("x = " << x);
            requireNear(tf.evaluate(static_cast<float>(x / 300.0)), expected(x));
        }
    }
    SECTION("a wider data range: nodes keep their data positions, ends hold") {
        const TransferFunction tf = TransferFunction::loadParaViewJson(file, std::pair{-300.0, 600.0});
        for (double x : {-300.0, -100.0, 0.0, 100.0, 200.0, 275.0, 300.0, 450.0, 600.0}) {
            INFO("x = " << x);
            requireNear(tf.evaluate(static_cast<float>((x + 300.0) / 900.0)), expected(std::max(x, 0.0)));
        }
    }
    SECTION("a narrower data range cuts the curves at its ends") {
        const TransferFunction tf = TransferFunction::loadParaViewJson(file, std::pair{120.0, 220.0});
        REQUIRE(tf.points().front().value == 0.0f);
        REQUIRE(tf.points().back().value == 1.0f);
        for (double x : {120.0, 150.0, 190.0, 220.0}) {
            INFO("x = " << x);
            requireNear(tf.evaluate(static_cast<float>((x - 120.0) / 100.0)), expected(x));
        }
    }
    SECTION("without \"Points\" the opacity is a linear ramp over the range") {
        const std::filesystem::path noOpacity =
            dir.write("no_opacity.json", R"([{"RGBPoints": [100, 1, 0, 0, 300, 0, 0, 1]}])");
        const TransferFunction tf = TransferFunction::loadParaViewJson(noOpacity);
        requireNear(tf.evaluate(0.0f), {1, 0, 0, 0});
        requireNear(tf.evaluate(0.25f), {0.75f, 0, 0.25f, 0.25f});
        requireNear(tf.evaluate(1.0f), {0, 0, 1, 1});
        const TransferFunction ranged = TransferFunction::loadParaViewJson(noOpacity, std::pair{0.0, 400.0});
        requireNear(ranged.evaluate(0.5f), {0.5f, 0, 0.5f, 0.5f});  // x = 200
        requireNear(ranged.evaluate(0.1f), {1, 0, 0, 0.1f});        // below the first colour node
    }
    SECTION("x values near the ends of the double range map without overflow") {
        // hi - lo overflows to infinity here; the loader once read past the node vector (issue 9, D2).
        const std::filesystem::path wide =
            dir.write("wide.json", R"({"RGBPoints": [-1e308, 1, 0, 0, 0, 0, 1, 0, 1e308, 0, 0, 1]})");
        const TransferFunction tf = TransferFunction::loadParaViewJson(wide);
        REQUIRE(tf.points().size() == 3);
        requireNear(tf.evaluate(0.0f), {1, 0, 0, 0});
        requireNear(tf.evaluate(0.5f), {0, 1, 0, 0.5f});
        requireNear(tf.evaluate(0.75f), {0, 0.5f, 0.5f, 0.75f});
        const TransferFunction ranged = TransferFunction::loadParaViewJson(wide, std::pair{-1.7e308, 1.7e308});
        requireNear(ranged.evaluate(0.5f), {0, 1, 0, 0.5f});
        for (const TransferFunction* f : {&tf, &ranged})
            for (const glm::vec4& entry : f->table(256))
                for (int c = 0; c < 4; ++c) REQUIRE((entry[c] >= 0.0f && entry[c] <= 1.0f));
    }
    SECTION("equal x: the later node wins") {
        const std::filesystem::path dup =
            dir.write("dup.json", R"([{"RGBPoints": [0, 1, 0, 0, 0.5, 0, 1, 0, 0.5, 0, 0, 1, 1, 1, 1, 1]}])");
        const TransferFunction tf = TransferFunction::loadParaViewJson(dup);
        REQUIRE(tf.points().size() == 3);
        requireNear(tf.evaluate(0.5f), {0, 0, 1, 0.5f});
    }
}

TEST_CASE("ParaView JSON: the test fixture preset loads as written", "[cpu]") {
    // tests/data/paraview_preset_ember.json: colour at -200, 300, 800; opacity at -200, 100, 550,
    // 800; a second preset in the array is ignored.
    const TransferFunction tf = TransferFunction::loadParaViewJson(dataDir() / "paraview_preset_ember.json");
    auto at = [&](double x) { return tf.evaluate(static_cast<float>((x + 200.0) / 1000.0)); };
    REQUIRE(tf.points().size() == 5);  // t = 0, 0.3, 0.5, 0.75, 1
    requireNear(at(-200), {0.05f, 0.02f, 0.10f, 0.0f});
    requireNear(at(100), {0.5f, 0.128f, 0.07f, 0.0f});  // colour 60 % of the way from -200 to 300
    requireNear(at(300), {0.80f, 0.20f, 0.05f, 0.3f * 200.0f / 450.0f});
    requireNear(at(675), {0.95f, 0.725f, 0.3125f, 0.6f});
    requireNear(at(800), {1.0f, 0.9f, 0.4f, 0.9f});
}

TEST_CASE("ParaView JSON: bad files are rejected with the file and the problem", "[cpu]") {
    using K = ErrorKind;
    SECTION("missing file") {
        sss::test::TempDir dir;
        REQUIRE_SSS_ERROR(TransferFunction::loadParaViewJson(dir.path() / "nope.json"), K::Io,
                          Contains("nope.json") && Contains("file not found"));
    }
    SECTION("not JSON: the parser's position is given") {
        requireLoadError("[{\"RGBPoints\": [0, 1, 0,\n 0, }]", K::Parse, "not valid JSON");
        requireLoadError("[{\"RGBPoints\": [0, 1, 0,\n 0, }]", K::Parse, "line 2, column 5");
        requireLoadError("", K::Parse, "not valid JSON");
    }
    SECTION("non-finite numbers") {
        requireLoadError(R"([{"RGBPoints": [0, NaN, 0, 0]}])", K::Parse, "NaN and Infinity are not JSON numbers");
        requireLoadError(R"([{"RGBPoints": [0, 1, 0, 0, 1e999, 1, 1, 1]}])", K::Parse, "not finite");
        requireLoadError(R"([{"RGBPoints": [0, 1, 0, 0], "Points": [-1e400, 0, 0.5, 0]}])", K::Parse, "not finite");
    }
    SECTION("no preset, no RGBPoints, empty lists") {
        requireLoadError("[]", K::Parse, "no preset");
        requireLoadError("42", K::Parse, "expected a preset object or an array of them, got number");
        requireLoadError("[\"viridis\"]", K::Parse, "must be a preset object, got string");
        requireLoadError(R"([{"Name": "x", "ColorSpace": "RGB"}])", K::Parse, "no \"RGBPoints\"");
        requireLoadError(R"([{"RGBPoints": []}])", K::Parse, "\"RGBPoints\" is empty");
        requireLoadError(R"([{"RGBPoints": [0, 1, 1, 1], "Points": []}])", K::Parse, "\"Points\" is empty");
        requireLoadError(R"([{"RGBPoints": {"x": 1}}])", K::Parse, "\"RGBPoints\" must be an array of numbers, got object");
    }
    SECTION("lengths that are not whole nodes") {
        requireLoadError(R"([{"RGBPoints": [0, 1, 0, 0, 1, 1]}])", K::Parse,
                         "\"RGBPoints\" must hold [x, r, g, b] groups of 4 numbers: its length 6 is not a multiple of 4");
        requireLoadError(R"([{"RGBPoints": [0, 1, 0, 0], "Points": [0, 0, 0.5, 0, 1, 1]}])", K::Parse,
                         "\"Points\" must hold [x, alpha, midpoint, sharpness] groups of 4 numbers: its length 6");
    }
    SECTION("entries that are not numbers or out of range") {
        requireLoadError(R"([{"RGBPoints": [0, 1, "red", 0]}])", K::Parse,
                         "\"RGBPoints\"[2] (g of node 0) is not a number, got string");
        requireLoadError(R"([{"RGBPoints": [0, 0, 0, 0, 1, 1, 1.5, 1]}])", K::Parse,
                         "\"RGBPoints\"[6] (g of node 1) is 1.5, outside [0,1]");
        requireLoadError(R"([{"RGBPoints": [0, 0, 0, -0.25]}])", K::Parse, "(b of node 0) is -0.25, outside [0,1]");
        requireLoadError(R"([{"RGBPoints": [0, 0, 0, 0], "Points": [0, 0, 0.5, 0, 1, 2, 0.5, 0]}])", K::Parse,
                         "\"Points\"[5] (alpha of node 1) is 2, outside [0,1]");
        requireLoadError(R"([{"RGBPoints": [0, 0, 0, 0], "Points": [0, 0, 1.5, 0]}])", K::Parse,
                         "(midpoint of node 0) is 1.5, outside [0,1]");
    }
    SECTION("unsorted x") {
        requireLoadError(R"([{"RGBPoints": [0, 0, 0, 0, 5, 1, 1, 1, 2, 1, 0, 0]}])", K::Parse,
                         "\"RGBPoints\": x of node 2 (2) is smaller than x of node 1 (5); nodes must be sorted by ascending x");
        requireLoadError(R"([{"RGBPoints": [0, 0, 0, 0], "Points": [1, 0, 0.5, 0, 0, 1, 0.5, 0]}])", K::Parse,
                         "\"Points\": x of node 1 (0) is smaller than x of node 0 (1)");
    }
    SECTION("a bad data range") {
        sss::test::TempDir dir;
        const auto file = dir.write("ok.json", R"([{"RGBPoints": [0, 0, 0, 0, 1, 1, 1, 1]}])");
        REQUIRE_SSS_ERROR(TransferFunction::loadParaViewJson(file, std::pair{1.0, 1.0}), K::InvalidArgument,
                          Contains("dataRange must be finite with lo < hi"));
        REQUIRE_SSS_ERROR(TransferFunction::loadParaViewJson(file, std::pair{0.0, std::nan("")}), K::InvalidArgument,
                          Contains("dataRange"));
    }
}

TEST_CASE("ParaView JSON: saving to an unwritable place names the file", "[cpu]") {
    sss::test::TempDir dir;
    const auto file = dir.path() / "no-such-dir" / "tf.json";
    REQUIRE_SSS_ERROR(TransferFunction().saveParaViewJson(file), ErrorKind::Io,
                      Contains("tf.json") && Contains("cannot open for writing"));
}
