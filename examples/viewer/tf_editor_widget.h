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
    /// (Volume::transferFunctionRange(): 0..255, or a 16-bit volume's min..max).
    std::pair<double, double> rawRange{0.0, 255.0};
};

/// Draws the editor canvas (full available width, `height` pixels) and the selected point's
/// controls, and applies the user's edits to `editor`. Returns true if the function changed.
bool transferFunctionEditorWidget(sss::TransferFunctionEditor& editor, const TfEditorWidgetState& state,
                                  float height = 150.0f);

}  // namespace viewer
