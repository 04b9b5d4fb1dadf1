// libFuzzer target: sss::TransferFunction::loadParaViewJson (ParaView / vtk.js colour-map
// presets), then evaluate() and table() of what it loads.
//
// The input is the JSON file. It is loaded without a data range, and once more with one if the
// preset object (or the first element of a top-level array) has a "_fuzzDataRange": [lo, hi]
// member of two numbers: the loader ignores unknown members, so the fuzzer steers the range
// through the file while seeds stay valid presets.
//
// Oracle (see fuzz_support.h): the load returns or throws sss::Error. A loaded function has at
// least one control point, values in [0,1] strictly increasing, colour and opacity in [0,1];
// evaluate() at 0, 1, many points in between, just outside and far outside [0,1] gives finite
// values in [0,1]; evaluate(NaN) throws sss::Error; table(256) and table(2) match evaluate().
#include "fuzz_support.h"

#include "sss/error.h"
#include "sss/transfer_function.h"

#include <glm/common.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

namespace {

bool unit(float v) { return std::isfinite(v) && v >= 0.0f && v <= 1.0f; }
bool unit4(glm::vec4 v) { return unit(v.r) && unit(v.g) && unit(v.b) && unit(v.a); }

void checkAt(const sss::TransferFunction& tf, float x) {
    const glm::vec4 c = tf.evaluate(x);
    SSS_FUZZ_CHECK(unit4(c), "evaluate(%.9g) = (%g, %g, %g, %g)", x, c.r, c.g, c.b, c.a);
}

void checkFunction(const sss::TransferFunction& tf) {
    const auto& points = tf.points();
    SSS_FUZZ_CHECK(!points.empty(), "no control points");
    for (std::size_t i = 0; i < points.size(); ++i) {
        const sss::ControlPoint& p = points[i];
        SSS_FUZZ_CHECK(unit(p.value) && unit(p.color.r) && unit(p.color.g) && unit(p.color.b) && unit(p.opacity),
                       "point %zu: value %g, colour (%g, %g, %g), opacity %g", i, p.value, p.color.r, p.color.g,
                       p.color.b, p.opacity);
        if (i > 0)
            SSS_FUZZ_CHECK(points[i - 1].value < p.value, "points %zu and %zu not strictly increasing (%.9g, %.9g)",
                           i - 1, i, points[i - 1].value, p.value);
    }

    constexpr int kSamples = 1024;
    for (int i = 0; i <= kSamples; ++i) checkAt(tf, static_cast<float>(i) / kSamples);
    for (const sss::ControlPoint& p : points) {
        checkAt(tf, p.value);
        checkAt(tf, std::nextafter(p.value, 0.0f));
        checkAt(tf, std::nextafter(p.value, 1.0f));
    }
    constexpr float kInf = std::numeric_limits<float>::infinity();
    for (float x : {-kInf, -1.0f, -std::numeric_limits<float>::denorm_min(), 1.0f + 1e-7f, 2.0f, kInf})
        checkAt(tf, x);
    bool threw = false;
    try {
        (void)tf.evaluate(std::numeric_limits<float>::quiet_NaN());
    } catch (const sss::Error&) {
        threw = true;
    }
    SSS_FUZZ_CHECK(threw, "evaluate(NaN) did not throw sss::Error");

    for (int entries : {256, 2}) {
        const std::vector<glm::vec4> table = tf.table(entries);
        SSS_FUZZ_CHECK(table.size() == static_cast<std::size_t>(entries), "table(%d) has %zu entries", entries,
                       table.size());
        for (std::size_t i = 0; i < table.size(); ++i) {
            SSS_FUZZ_CHECK(unit4(table[i]), "table(%d)[%zu] = (%g, %g, %g, %g)", entries, i, table[i].r,
                           table[i].g, table[i].b, table[i].a);
            const glm::vec4 e = tf.evaluate(static_cast<float>(i) / static_cast<float>(entries - 1));
            const glm::vec4 d = glm::abs(table[i] - e);
            SSS_FUZZ_CHECK(std::max({d.r, d.g, d.b, d.a}) <= 1e-6f, "table(%d)[%zu] differs from evaluate()",
                           entries, i);
        }
    }
}

// "_fuzzDataRange": [lo, hi] from the preset the loader reads, if present.
std::optional<std::pair<double, double>> fuzzDataRange(const uint8_t* data, std::size_t size) {
    const nlohmann::json root = nlohmann::json::parse(data, data + size, nullptr, /*allow_exceptions=*/false);
    const nlohmann::json* preset = &root;
    if (root.is_array() && !root.empty()) preset = &root.front();
    if (!preset->is_object()) return std::nullopt;
    const auto it = preset->find("_fuzzDataRange");
    if (it == preset->end() || !it->is_array() || it->size() != 2 || !(*it)[0].is_number() ||
        !(*it)[1].is_number())
        return std::nullopt;
    return std::make_pair((*it)[0].get<double>(), (*it)[1].get<double>());
}

void loadAndCheck(const std::filesystem::path& path, std::optional<std::pair<double, double>> range) {
    std::optional<sss::TransferFunction> tf;
    try {
        tf = sss::TransferFunction::loadParaViewJson(path, range);
    } catch (const sss::Error&) {
        return;  // any other exception escapes: a bug
    }
    checkFunction(*tf);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
    const std::filesystem::path path = sss::fuzz::writeScratchFile("input.json", data, size);
    loadAndCheck(path, std::nullopt);
    if (const auto range = fuzzDataRange(data, size)) loadAndCheck(path, range);
    return 0;
}
