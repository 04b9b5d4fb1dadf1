#pragma once
// Dear ImGui front end of sss::TransferFunctionEditor: a canvas with the histogram backdrop,
// the opacity polyline and the control points, plus the selected point's controls.

#include <sss/transfer_function_editor.h>

#include <string>
#include <utility>
#include <vector>

namespace viewer {

struct TfEditorWidgetState {
    std::vector<float> histogram;  ///< bar heights in [0,1] (TransferFunctionEditor::histogramBars)
    /// Raw voxel values at the canvas's left and right edge, for the tooltip
    /// (Volume::transferFunctionRange(): 0..255 for uint8, else the data's min..max, or the
    /// value window).
    std::pair<double, double> rawRange{0.0, 255.0};
};

/// A rectangle in window pixels (y down): (x0, y0) top left, (x1, y1) bottom right.
struct ScreenRect {
    float x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

/// Draws the editor canvas (full available width, `height` pixels) and the selected point's
/// controls, and applies the user's edits to `editor`. Returns true if the function changed.
/// `canvas`, if given, receives where value 0..1 and opacity 1..0 are drawn (the square the
/// editor's canvas coordinates map onto).
bool transferFunctionEditorWidget(sss::TransferFunctionEditor& editor, const TfEditorWidgetState& state,
                                  float height = 150.0f, ScreenRect* canvas = nullptr);

}  // namespace viewer
