// ParaView JSON colour maps (declared in sss/transfer_function.h, built in the io component).
#include "sss/transfer_function.h"

#include "util/format.h"

#include "sss/error.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>
#include <system_error>
#include <tuple>
#include <utility>

namespace sss {
namespace {

template <typename T>
std::string str(const T& v) {
    return detail::formatNumber(v);
}

}  // namespace


namespace {

// One node of a ParaView curve: position (data units, later [0,1]) and up to 3 values
// (r, g, b for colour; alpha in v[0] for opacity).
struct CurveNode {
    double x = 0.0;
    std::array<double, 3> v{};
};

class JsonPreset {
public:
    explicit JsonPreset(const std::filesystem::path& path)
        : m_prefix("TransferFunction::loadParaViewJson: " + path.string() + ": ") {}

    [[noreturn]] void fail(ErrorKind kind, const std::string& problem) const {
        throw Error(kind, m_prefix + problem);
    }

    // Reads `key` as a flat list of nodes of `stride` numbers (x first, then the values); the
    // first `valueCount` values after x must be in [0,1] and are kept, the rest (ParaView's
    // midpoint and sharpness) must be in [0,1] and are ignored: every segment is treated as
    // linear. Equal x: the later node replaces the earlier (vtkColorTransferFunction /
    // vtkPiecewiseFunction AddPoint semantics).
    std::vector<CurveNode> readNodes(const nlohmann::json& preset, const char* key, int stride,
                                     const std::vector<std::string>& names) const {
        const std::string quoted = std::string("\"") + key + "\"";
        const nlohmann::json& list = preset.at(key);
        if (!list.is_array())
            fail(ErrorKind::Parse, quoted + " must be an array of numbers, got " + list.type_name());
        if (list.empty()) fail(ErrorKind::Parse, quoted + " is empty (it needs at least one node)");
        std::string group;
        for (const std::string& n : names) group += (group.empty() ? "" : ", ") + n;
        if (list.size() % static_cast<std::size_t>(stride) != 0)
            fail(ErrorKind::Parse, quoted + " must hold [" + group + "] groups of " + std::to_string(stride) +
                                       " numbers: its length " + std::to_string(list.size()) +
                                       " is not a multiple of " + std::to_string(stride));
        std::vector<CurveNode> nodes;
        for (std::size_t i = 0; i < list.size(); i += static_cast<std::size_t>(stride)) {
            const std::size_t node = i / static_cast<std::size_t>(stride);
            std::array<double, 4> n{};
            for (int k = 0; k < stride; ++k) {
                const std::size_t index = i + static_cast<std::size_t>(k);
                const std::string where = quoted + "[" + std::to_string(index) + "] (" + names[static_cast<std::size_t>(k)] +
                                          " of node " + std::to_string(node) + ")";
                const nlohmann::json& e = list[index];
                if (!e.is_number()) fail(ErrorKind::Parse, where + " is not a number, got " + std::string(e.type_name()));
                const double d = e.get<double>();
                if (!std::isfinite(d)) fail(ErrorKind::Parse, where + " is not finite");
                if (k > 0 && !(d >= 0.0 && d <= 1.0))
                    fail(ErrorKind::Parse, where + " is " + str(d) + ", outside [0,1]");
                n[static_cast<std::size_t>(k)] = d;
            }
            if (!nodes.empty() && n[0] < nodes.back().x)
                fail(ErrorKind::Parse, quoted + ": x of node " + std::to_string(node) + " (" + str(n[0]) +
                                           ") is smaller than x of node " + std::to_string(node - 1) + " (" +
                                           str(nodes.back().x) + "); nodes must be sorted by ascending x");
            CurveNode c;
            c.x = n[0];
            for (std::size_t k = 0; k < 3; ++k) c.v[k] = n[k + 1];
            if (!nodes.empty() && n[0] == nodes.back().x)
                nodes.back() = c;
            else
                nodes.push_back(c);
        }
        return nodes;
    }

private:
    std::string m_prefix;
};

// Piecewise-linear, constant beyond the end nodes; nodes sorted by strictly increasing x.
std::array<double, 3> evaluateCurve(const std::vector<CurveNode>& nodes, double x) {
    if (!(x > nodes.front().x)) return nodes.front().v;  // also NaN: never index past the end
    if (x >= nodes.back().x) return nodes.back().v;
    auto hi = std::upper_bound(nodes.begin(), nodes.end(), x, [](double v, const CurveNode& n) { return v < n.x; });
    auto lo = hi - 1;
    const double t = (x - lo->x) / (hi->x - lo->x);
    std::array<double, 3> out{};
    for (std::size_t k = 0; k < 3; ++k) out[k] = lo->v[k] + (hi->v[k] - lo->v[k]) * t;
    return out;
}

// Shortest text that reads back (through double, as JSON readers do) as exactly `v`.
std::string jsonNumber(float v) {
    std::array<char, 64> buf{};
    auto [end, ec] = std::to_chars(buf.data(), buf.data() + buf.size(), v);
    std::string text(buf.data(), end);
    double back = 0.0;
    const auto parsed = std::from_chars(text.data(), text.data() + text.size(), back);
    if (ec != std::errc() || parsed.ec != std::errc() || static_cast<float>(back) != v)
        text = nlohmann::json(static_cast<double>(v)).dump();  // 17 significant digits
    return text;
}

}  // namespace

TransferFunction TransferFunction::loadParaViewJson(const std::filesystem::path& path,
                                                    std::optional<std::pair<double, double>> dataRange) {
    const JsonPreset file(path);
    if (dataRange && !(std::isfinite(dataRange->first) && std::isfinite(dataRange->second) &&
                       dataRange->first < dataRange->second))
        file.fail(ErrorKind::InvalidArgument, "dataRange must be finite with lo < hi, got (" + str(dataRange->first) +
                                                  ", " + str(dataRange->second) + ")");
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) file.fail(ErrorKind::Io, "file not found");
    std::ifstream in(path, std::ios::binary);
    if (!in) file.fail(ErrorKind::Io, "cannot open the file for reading");
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) file.fail(ErrorKind::Io, "read error");

    nlohmann::json root;
    try {
        root = nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error& e) {
        // what() is "[json.exception.parse_error.101] parse error at line L, column C: ...".
        std::string reason = e.what();
        if (const auto close = reason.find("] "); reason.rfind("[json.", 0) == 0 && close != std::string::npos)
            reason = reason.substr(close + 2);
        const bool nonFinite = text.find("NaN") != std::string::npos || text.find("Infinity") != std::string::npos;
        file.fail(ErrorKind::Parse, "not valid JSON: " + reason + " (byte " + std::to_string(e.byte) + ")" +
                                        (nonFinite ? "; note that NaN and Infinity are not JSON numbers" : ""));
    } catch (const nlohmann::json::exception& e) {
        // Number overflow (id 406, "1e999") is the only other error the parser raises.
        file.fail(ErrorKind::Parse, std::string("contains a number that is not finite: ") + e.what());
    }

    const nlohmann::json* preset = &root;
    if (root.is_array()) {
        if (root.empty()) file.fail(ErrorKind::Parse, "the top-level array is empty (no preset in the file)");
        preset = &root.front();
        if (!preset->is_object())
            file.fail(ErrorKind::Parse, std::string("the first element of the top-level array must be a preset "
                                                    "object, got ") + preset->type_name());
    } else if (!root.is_object()) {
        file.fail(ErrorKind::Parse, std::string("expected a preset object or an array of them, got ") + root.type_name());
    }
    if (!preset->contains("RGBPoints"))
        file.fail(ErrorKind::Parse, "the preset has no \"RGBPoints\" (flat [x, r, g, b, ...] colour nodes)");

    std::vector<CurveNode> color = file.readNodes(*preset, "RGBPoints", 4, {"x", "r", "g", "b"});
    const bool hasOpacity = preset->contains("Points");
    std::vector<CurveNode> opacity;
    if (hasOpacity) opacity = file.readNodes(*preset, "Points", 4, {"x", "alpha", "midpoint", "sharpness"});

    // Data units -> [0,1].
    double lo = 0.0, hi = 1.0;
    if (dataRange) {
        std::tie(lo, hi) = *dataRange;
    } else {
        lo = color.front().x;
        hi = color.back().x;
        if (hasOpacity) {
            lo = std::min(lo, opacity.front().x);
            hi = std::max(hi, opacity.back().x);
        }
    }
    // Halved first, so that neither x - lo nor hi - lo overflows for x values near DBL_MAX
    // apart (-1e308 .. 1e308); halving is exact for all but subnormal values.
    const double halfRange = hi / 2.0 - lo / 2.0;
    auto toUnit = [&](std::vector<CurveNode>& nodes) {
        for (CurveNode& n : nodes) {
            n.x = halfRange > 0.0 ? (n.x / 2.0 - lo / 2.0) / halfRange : 0.0;
            if (!std::isfinite(n.x))
                file.fail(ErrorKind::Parse, "node x values cannot be mapped onto the data range (" + str(lo) + ", " +
                                                str(hi) + ")");
        }
        // Mapping may merge nodes that were distinct in data units (a tiny range); keep the later.
        std::vector<CurveNode> unique;
        for (const CurveNode& n : nodes) {
            if (!unique.empty() && n.x <= unique.back().x)
                unique.back() = n;
            else
                unique.push_back(n);
        }
        nodes = std::move(unique);
    };
    toUnit(color);
    if (hasOpacity)
        toUnit(opacity);
    else
        opacity = {CurveNode{0.0, {0.0, 0.0, 0.0}}, CurveNode{1.0, {1.0, 0.0, 0.0}}};  // documented ramp

    // Union of the node positions, cut to [0,1] (with nodes at 0/1 where a curve extends beyond).
    std::vector<double> xs;
    for (const auto* nodes : {&color, &opacity})
        for (const CurveNode& n : *nodes) xs.push_back(n.x);
    const auto [smallest, largest] = std::minmax_element(xs.begin(), xs.end());
    const bool below = *smallest < 0.0, above = *largest > 1.0;
    if (below) xs.push_back(0.0);
    if (above) xs.push_back(1.0);
    std::erase_if(xs, [](double x) { return x < 0.0 || x > 1.0; });
    std::sort(xs.begin(), xs.end());
    xs.erase(std::unique(xs.begin(), xs.end()), xs.end());

    std::vector<ControlPoint> points;
    for (double x : xs) {
        const float value = std::clamp(static_cast<float>(x), 0.0f, 1.0f);
        if (!points.empty() && value <= points.back().value) continue;  // closer than float precision
        const std::array<double, 3> c = evaluateCurve(color, x);
        const double a = evaluateCurve(opacity, x)[0];
        auto unit = [](double v) { return std::clamp(static_cast<float>(v), 0.0f, 1.0f); };
        points.push_back({value, glm::vec3(unit(c[0]), unit(c[1]), unit(c[2])), unit(a)});
    }
    return TransferFunction(std::move(points));
}

void TransferFunction::saveParaViewJson(const std::filesystem::path& path, std::string_view name) const {
    std::vector<ControlPoint> nodes = m_points;
    if (nodes.front().value > 0.0f) {
        ControlPoint first = nodes.front();
        first.value = 0.0f;
        nodes.insert(nodes.begin(), first);
    }
    if (nodes.back().value < 1.0f) {
        ControlPoint last = nodes.back();
        last.value = 1.0f;
        nodes.push_back(last);
    }
    std::string rgb, alpha;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        const ControlPoint& p = nodes[i];
        const std::string sep = i + 1 < nodes.size() ? ",\n" : "\n";
        rgb += "      " + jsonNumber(p.value) + ", " + jsonNumber(p.color.r) + ", " + jsonNumber(p.color.g) + ", " +
               jsonNumber(p.color.b) + sep;
        alpha += "      " + jsonNumber(p.value) + ", " + jsonNumber(p.opacity) + ", 0.5, 0" + sep;
    }
    const std::string quotedName =
        nlohmann::json(std::string(name)).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    const std::string text = "[\n  {\n    \"Name\": " + quotedName + ",\n    \"ColorSpace\": \"RGB\",\n" +
                             "    \"RGBPoints\": [\n" + rgb + "    ],\n    \"Points\": [\n" + alpha +
                             "    ]\n  }\n]\n";
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out)
        throw Error(ErrorKind::Io, "TransferFunction::saveParaViewJson: " + path.string() + ": cannot open for writing");
    out << text;
    out.flush();
    if (!out) throw Error(ErrorKind::Io, "TransferFunction::saveParaViewJson: " + path.string() + ": write failed");
}

}  // namespace sss
