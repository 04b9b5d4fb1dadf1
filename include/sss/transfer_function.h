#pragma once
/// @file
/// 1D transfer function: maps a normalized scalar in [0,1] to colour and opacity.

#include "sss/api.h"
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

SSS_BEGIN_API

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

    /// Loads a ParaView JSON colour-map preset (the format of ParaView's "Import Presets", also
    /// used by vtk.js ColorMaps.json): a JSON array of preset objects, of which the first is
    /// used, or a single preset object. Fields read:
    ///  - "RGBPoints" (required): flat [x, r, g, b, ...], x in data units, r/g/b in [0,1];
    ///  - "Points" (optional): opacity, flat [x, alpha, midpoint, sharpness, ...], alpha,
    ///    midpoint and sharpness in [0,1]. Without "Points" the opacity is a linear ramp from 0
    ///    at the bottom of the range (below) to 1 at its top.
    /// Other fields ("Name", "ColorSpace", "NanColor", ...) are ignored.
    /// x maps to this function's [0,1] domain linearly: dataRange (lo, hi) -> (0, 1) if given,
    /// else the smallest..largest x in RGBPoints and Points together (a single x maps to 0).
    /// Nodes beyond [0,1] are cut off there (the curves are evaluated at 0 and 1); outside its
    /// nodes each curve holds its end value, as ParaView's do.
    /// Colour and opacity are merged into one list of control points at the union of their
    /// (mapped) x positions, each curve being evaluated there piecewise-linearly. Approximations:
    /// colours are interpolated in linear RGB whatever "ColorSpace" says (HSV, Lab, Diverging
    /// and Step are not reproduced between nodes); a midpoint other than 0.5 or a sharpness
    /// other than 0 is treated as a linear segment; nodes with equal x replace the earlier
    /// one (so a step discontinuity becomes the later node's value); x positions closer than
    /// float precision after mapping are merged (the first one is kept).
    /// @throws Error Io if the file is missing or unreadable; Parse if it is not JSON (the
    ///         parser's line/column is given), has no preset object, lacks "RGBPoints", has an
    ///         empty list or one whose length is not a multiple of 4, a non-number or
    ///         non-finite entry, a colour/alpha/midpoint/sharpness outside [0,1] or x not
    ///         sorted ascending (the entry's index is given); InvalidArgument if dataRange is
    ///         not finite with lo < hi. Messages start with
    ///         "TransferFunction::loadParaViewJson: <path>: ".
    static TransferFunction loadParaViewJson(const std::filesystem::path& path,
                                             std::optional<std::pair<double, double>> dataRange = {});

    /// Writes this function as a ParaView JSON preset: an array holding one object with "Name",
    /// "ColorSpace": "RGB", "RGBPoints" and "Points" (midpoint 0.5, sharpness 0: linear
    /// segments), x in [0,1]. If the first point is above 0 or the last below 1, nodes with the
    /// end values are added at 0 and 1 so that loadParaViewJson() without a dataRange maps the
    /// file back onto the same positions (the function is unchanged: it is constant there).
    /// Numbers are written with 17 significant digits, so a load gives the same points back.
    /// @throws Error Io naming the file if it cannot be written.
    void saveParaViewJson(const std::filesystem::path& path, std::string_view name = "libsss") const;

private:
    void touch();

    std::vector<ControlPoint> m_points;
    uint64_t m_revision = 0;
};

}  // namespace sss

SSS_END_API
