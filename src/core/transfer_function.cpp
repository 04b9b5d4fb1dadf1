#include "sss/transfer_function.h"

#include "util/format.h"

#include "sss/error.h"


#include <algorithm>
#include <array>
#include <atomic>
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

// Process-wide so that revisions identify contents across objects (see revision()).
std::atomic<uint64_t> g_revisionCounter{0};

bool inUnit(float v) { return std::isfinite(v) && v >= 0.0f && v <= 1.0f; }

template <typename T>
std::string str(const T& v) {
    return detail::formatNumber(v);
}

std::string str(glm::vec3 v) { return detail::formatVec(v); }

void checkColorOpacity(const std::string& prefix, glm::vec3 color, float opacity) {
    if (!inUnit(color.x) || !inUnit(color.y) || !inUnit(color.z))
        throw Error(ErrorKind::InvalidArgument, prefix + "color must be finite and in [0,1], got " + str(color));
    if (!inUnit(opacity))
        throw Error(ErrorKind::InvalidArgument, prefix + "opacity must be finite and in [0,1], got " + str(opacity));
}

void checkPoint(const std::string& prefix, const ControlPoint& p) {
    if (!inUnit(p.value))
        throw Error(ErrorKind::InvalidArgument, prefix + "value must be finite and in [0,1], got " + str(p.value));
    checkColorOpacity(prefix, p.color, p.opacity);
}

bool valueLess(const ControlPoint& p, float v) { return p.value < v; }

}  // namespace

TransferFunction::TransferFunction()
    : TransferFunction(std::vector<ControlPoint>{{0.0f, glm::vec3(0.0f), 0.0f}, {1.0f, glm::vec3(1.0f), 1.0f}}) {}

TransferFunction::TransferFunction(std::vector<ControlPoint> points) : m_points(std::move(points)) {
    if (m_points.empty())
        throw Error(ErrorKind::InvalidArgument, "TransferFunction: needs at least one control point, got none");
    for (std::size_t i = 0; i < m_points.size(); ++i) {
        checkPoint("TransferFunction: point " + std::to_string(i) + ": ", m_points[i]);
        if (i > 0 && !(m_points[i].value > m_points[i - 1].value))
            throw Error(ErrorKind::InvalidArgument,
                        "TransferFunction: point " + std::to_string(i) + " is out of order: its value " +
                            str(m_points[i].value) + " is not greater than point " + std::to_string(i - 1) +
                            "'s value " + str(m_points[i - 1].value) + " (values must be strictly increasing)");
    }
    touch();
}

void TransferFunction::touch() { m_revision = ++g_revisionCounter; }

std::size_t TransferFunction::addPoint(ControlPoint point) {
    checkPoint("TransferFunction::addPoint: ", point);
    auto it = std::lower_bound(m_points.begin(), m_points.end(), point.value, valueLess);
    if (it != m_points.end() && it->value == point.value) {
        it->color = point.color;
        it->opacity = point.opacity;
    } else {
        it = m_points.insert(it, point);
    }
    touch();
    return static_cast<std::size_t>(it - m_points.begin());
}

std::size_t TransferFunction::movePoint(std::size_t index, float newValue) {
    if (index >= m_points.size())
        throw Error(ErrorKind::InvalidArgument, "TransferFunction::movePoint: index " + std::to_string(index) +
                                                    " is out of range (" + std::to_string(m_points.size()) +
                                                    " points)");
    if (std::isnan(newValue))
        throw Error(ErrorKind::InvalidArgument, "TransferFunction::movePoint: newValue is NaN");
    ControlPoint moved = m_points[index];
    const float old = moved.value;
    float v = std::clamp(newValue, 0.0f, 1.0f);
    // Step back towards where the point came from until the value is free; `old` itself is
    // free once the point is taken out, so this ends.
    auto takenByOther = [&](float x) {
        for (std::size_t j = 0; j < m_points.size(); ++j)
            if (j != index && m_points[j].value == x) return true;
        return false;
    };
    while (v != old && takenByOther(v)) v = std::nextafter(v, old);
    moved.value = v;
    m_points.erase(m_points.begin() + static_cast<std::ptrdiff_t>(index));
    auto it = std::lower_bound(m_points.begin(), m_points.end(), v, valueLess);
    it = m_points.insert(it, moved);
    touch();
    return static_cast<std::size_t>(it - m_points.begin());
}

void TransferFunction::setPoint(std::size_t index, glm::vec3 color, float opacity) {
    if (index >= m_points.size())
        throw Error(ErrorKind::InvalidArgument, "TransferFunction::setPoint: index " + std::to_string(index) +
                                                    " is out of range (" + std::to_string(m_points.size()) +
                                                    " points)");
    checkColorOpacity("TransferFunction::setPoint: ", color, opacity);
    m_points[index].color = color;
    m_points[index].opacity = opacity;
    touch();
}

void TransferFunction::removePoint(std::size_t index) {
    if (index >= m_points.size())
        throw Error(ErrorKind::InvalidArgument, "TransferFunction::removePoint: index " + std::to_string(index) +
                                                    " is out of range (" + std::to_string(m_points.size()) +
                                                    " points)");
    if (m_points.size() == 1)
        throw Error(ErrorKind::InvalidArgument,
                    "TransferFunction::removePoint: cannot remove the last remaining control point");
    m_points.erase(m_points.begin() + static_cast<std::ptrdiff_t>(index));
    touch();
}

glm::vec4 TransferFunction::evaluate(float value) const {
    if (std::isnan(value)) throw Error(ErrorKind::InvalidArgument, "TransferFunction::evaluate: value is NaN");
    auto rgba = [](const ControlPoint& p) { return glm::vec4(p.color, p.opacity); };
    if (value <= m_points.front().value) return rgba(m_points.front());
    if (value >= m_points.back().value) return rgba(m_points.back());
    // First point with p.value > value; it exists and is not the first (checked above).
    auto hi = std::upper_bound(m_points.begin(), m_points.end(), value,
                               [](float v, const ControlPoint& p) { return v < p.value; });
    auto lo = hi - 1;
    const float t = (value - lo->value) / (hi->value - lo->value);
    return rgba(*lo) + (rgba(*hi) - rgba(*lo)) * t;
}

std::vector<glm::vec4> TransferFunction::table(int entries) const {
    if (entries < 2 || entries > 65536)
        throw Error(ErrorKind::InvalidArgument,
                    "TransferFunction::table: entries must be in [2, 65536], got " + std::to_string(entries));
    std::vector<glm::vec4> out(static_cast<std::size_t>(entries));
    for (int i = 0; i < entries; ++i)
        out[static_cast<std::size_t>(i)] = evaluate(static_cast<float>(i) / static_cast<float>(entries - 1));
    return out;
}

std::vector<std::string> TransferFunction::presetNames() {
    return {"ramp", "bucky", "bonsai", "ct-bone", "ct-skin", "engine"};
}

TransferFunction TransferFunction::preset(std::string_view name) {
    using P = std::vector<ControlPoint>;
    if (name == "ramp") return TransferFunction();
    if (name == "bucky")
        // C60 density: most voxels are low background; carbon atoms are the top of the range.
        return TransferFunction(P{{0.00f, {0.00f, 0.00f, 0.00f}, 0.00f},
                                  {0.12f, {0.10f, 0.15f, 0.50f}, 0.00f},
                                  {0.30f, {0.20f, 0.50f, 0.90f}, 0.06f},
                                  {0.55f, {0.30f, 0.85f, 0.60f}, 0.25f},
                                  {0.80f, {1.00f, 0.80f, 0.30f}, 0.60f},
                                  {1.00f, {1.00f, 1.00f, 1.00f}, 0.90f}});
    if (name == "bonsai")
        // Noise below ~0.1 hidden; leaves (low density) green and faint; trunk (~0.5-0.6)
        // brown; pot (~0.8) light and nearly opaque.
        return TransferFunction(P{{0.00f, {0.00f, 0.00f, 0.00f}, 0.00f},
                                  {0.10f, {0.10f, 0.35f, 0.05f}, 0.00f},
                                  {0.20f, {0.25f, 0.65f, 0.15f}, 0.12f},
                                  {0.40f, {0.35f, 0.50f, 0.15f}, 0.15f},
                                  {0.50f, {0.55f, 0.35f, 0.18f}, 0.50f},
                                  {0.70f, {0.60f, 0.40f, 0.25f}, 0.60f},
                                  {0.78f, {0.75f, 0.55f, 0.45f}, 0.80f},
                                  {1.00f, {0.90f, 0.85f, 0.80f}, 0.90f}});
    if (name == "engine")
        // Engine block (peak ~0.5-0.6) translucent blue; the dense parts (~1.0) opaque and warm.
        return TransferFunction(P{{0.00f, {0.00f, 0.00f, 0.00f}, 0.00f},
                                  {0.30f, {0.20f, 0.30f, 0.60f}, 0.00f},
                                  {0.45f, {0.30f, 0.50f, 0.80f}, 0.05f},
                                  {0.55f, {0.50f, 0.70f, 0.90f}, 0.15f},
                                  {0.75f, {0.90f, 0.60f, 0.30f}, 0.30f},
                                  {0.95f, {1.00f, 0.90f, 0.70f}, 0.90f},
                                  {1.00f, {1.00f, 1.00f, 1.00f}, 1.00f}});
    // CT presets for 8-bit floor((HU + 1024) / 16) / 255: air ~0, fat (-100 HU) ~0.22,
    // soft tissue (0..100 HU) ~0.25-0.28, bone (>= 300 HU) >= ~0.32, dense bone up to ~0.65.
    if (name == "ct-skin")
        return TransferFunction(P{{0.00f, {0.00f, 0.00f, 0.00f}, 0.00f},
                                  {0.18f, {0.55f, 0.25f, 0.15f}, 0.00f},
                                  {0.23f, {0.85f, 0.55f, 0.45f}, 0.15f},
                                  {0.27f, {0.95f, 0.72f, 0.60f}, 0.40f},
                                  {0.32f, {0.98f, 0.85f, 0.75f}, 0.50f},
                                  {0.45f, {1.00f, 0.97f, 0.90f}, 0.80f},
                                  {1.00f, {1.00f, 1.00f, 1.00f}, 0.90f}});
    if (name == "ct-bone")
        return TransferFunction(P{{0.00f, {0.00f, 0.00f, 0.00f}, 0.00f},
                                  {0.30f, {0.60f, 0.35f, 0.25f}, 0.00f},
                                  {0.34f, {0.90f, 0.78f, 0.62f}, 0.35f},
                                  {0.42f, {0.97f, 0.92f, 0.82f}, 0.75f},
                                  {0.60f, {1.00f, 0.98f, 0.94f}, 0.95f},
                                  {1.00f, {1.00f, 1.00f, 1.00f}, 1.00f}});
    std::string valid;
    for (const std::string& n : presetNames()) valid += (valid.empty() ? "" : ", ") + n;
    throw Error(ErrorKind::InvalidArgument,
                "TransferFunction::preset: unknown preset \"" + std::string(name) + "\"; valid names: " + valid);
}

}  // namespace sss
