#pragma once
/// @file
/// 1D transfer function: maps a normalized scalar in [0,1] to colour and opacity.

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace sss {

/// One control point of a TransferFunction. All fields must be finite and in [0,1].
struct ControlPoint {
    float value = 0.0f;           ///< scalar position in [0,1]
    glm::vec3 color{0.0f};        ///< linear RGB, each in [0,1]
    float opacity = 0.0f;         ///< in [0,1]; how a renderer turns it into extinction is its business
};

/// Piecewise-linear colour and opacity over control points sorted by strictly increasing value.
/// Below the first point and above the last the end values hold. Always has >= 1 point.
/// Every constructor and edit gives the function a new revision() (see there).
class TransferFunction {
public:
    /// A ramp: 0 -> black, opacity 0; 1 -> white, opacity 1 (same as preset("ramp")).
    TransferFunction();

    /// @throws Error InvalidArgument if points is empty, any field is non-finite or outside
    ///         [0,1], or values are not strictly increasing (the message names the index).
    explicit TransferFunction(std::vector<ControlPoint> points);

    /// Inserts a point in value order and returns its index. If a point with exactly the same
    /// value exists, its colour and opacity are replaced instead.
    /// @throws Error InvalidArgument if the point is invalid (as in the constructor).
    std::size_t addPoint(ControlPoint point);

    /// Moves point `index` to newValue (clamped to [0,1]), re-sorts and returns its new index.
    /// If another point already has exactly that value, the moved point is nudged to the nearest
    /// free float on the side it came from, so dragging never throws or merges points.
    /// @throws Error InvalidArgument if index is out of range or newValue is NaN.
    std::size_t movePoint(std::size_t index, float newValue);

    /// Replaces the colour and opacity of point `index`.
    /// @throws Error InvalidArgument if index is out of range or a value is invalid.
    void setPoint(std::size_t index, glm::vec3 color, float opacity);

    /// Removes point `index`. @throws Error InvalidArgument if index is out of range or it is
    /// the only point left.
    void removePoint(std::size_t index);

    /// The control points, sorted by strictly increasing value.
    const std::vector<ControlPoint>& points() const { return m_points; }

    /// (r, g, b, opacity) at value: linear between neighbouring points, constant beyond the ends.
    /// @throws Error InvalidArgument if value is NaN.
    glm::vec4 evaluate(float value) const;

    /// `entries` samples; entry i is evaluate(i / (entries - 1)), so the first is at 0 and the
    /// last at 1. Default 256. @throws Error InvalidArgument unless 2 <= entries <= 65536.
    std::vector<glm::vec4> table(int entries = 256) const;

    /// Changes (strictly increases) on every edit. Revisions come from one process-wide counter,
    /// so two functions with different contents never share a revision: a renderer that caches
    /// revision() also notices when a whole new TransferFunction is assigned. Copies keep it.
    uint64_t revision() const { return m_revision; }

    /// A named preset; see presetNames(). Names are: "ramp", "bucky", "bonsai", "ct-bone",
    /// "ct-skin", "engine" (tuned on the 8-bit data sets of those names; the ct ones assume
    /// 8-bit CT stored as floor((HU + 1024) / 16)).
    /// @throws Error InvalidArgument for an unknown name, listing the valid ones.
    static TransferFunction preset(std::string_view name);

    /// Names accepted by preset(), in a stable order.
    static std::vector<std::string> presetNames();

private:
    void touch();

    std::vector<ControlPoint> m_points;
    uint64_t m_revision = 0;
};

}  // namespace sss
