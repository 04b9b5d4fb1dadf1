#pragma once
/// @file
/// The interaction logic of a 1D transfer-function editor, independent of any UI toolkit.
///
/// Everything works in canvas-normalised coordinates: x is the scalar value in [0,1] (left to
/// right), y the opacity in [0,1] (bottom to top). A UI maps its mouse position into that square,
/// calls pointerDown/pointerDrag/pointerUp (or the explicit operations), and draws
/// transferFunction() and histogramBars(). sss-viewer does this with Dear ImGui.

#include "sss/api.h"
#include "sss/transfer_function.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

SSS_BEGIN_API

namespace sss {

class Volume;

struct TransferFunctionEditorOptions {
    /// Pick radius along x and y in canvas units; a point is hit when the ellipse with these
    /// radii around the pointer contains it. A UI passes its pixel radius divided by the canvas
    /// width and height, so picking is circular on screen (default: 0.03, 0.05).
    glm::vec2 pickRadius{0.03f, 0.05f};
    /// Dragging never moves a point past its neighbours (the order of the points stays fixed,
    /// as in ParaView). Off: a point may be dragged past others and is re-sorted, with the
    /// semantics of TransferFunction::movePoint (default: off).
    bool keepOrder = false;
    /// Most undo steps kept; the oldest are dropped beyond it, >= 0 (default: 100).
    std::size_t undoLimit = 100;
};

/// What pointerDown() did.
enum class EditorAction {
    None,      ///< nothing (e.g. the pointer was outside the canvas)
    Selected,  ///< an existing point was hit and selected; a drag moves it
    Added,     ///< empty space: a new point was added there and selected; a drag moves it
};

/// Edits a TransferFunction through canvas coordinates, with a selection, drag gestures and an
/// undo/redo history. Every edit that changes the function is one undo step; a whole drag
/// gesture (pointerDown .. pointerUp) and consecutive colour edits of the same point are one
/// step each.
class TransferFunctionEditor {
public:
    /// Starts with `tf` (default: the ramp), nothing selected and an empty history.
    /// @throws Error InvalidArgument if options.pickRadius is not finite and > 0.
    explicit TransferFunctionEditor(TransferFunction tf = {}, const TransferFunctionEditorOptions& options = {});

    /// The function being edited. Its revision() changes on every edit, undo and redo.
    const TransferFunction& transferFunction() const { return m_tf; }
    /// Replaces the whole function (a preset, a loaded file) as one undo step; clears the selection.
    void setTransferFunction(const TransferFunction& tf);

    const TransferFunctionEditorOptions& options() const { return m_options; }
    /// @throws Error InvalidArgument if options.pickRadius is not finite and > 0.
    void setOptions(const TransferFunctionEditorOptions& options);

    /// Index of the point nearest to `p` inside the pick radius (nearest in pick-radius-scaled
    /// distance), or nullopt if none is. Non-finite `p` hits nothing.
    std::optional<std::size_t> hitTest(glm::vec2 p) const;

    /// The selected point, if any.
    std::optional<std::size_t> selected() const { return m_selected; }
    /// Selects point `index`, or clears the selection with nullopt.
    /// @throws Error InvalidArgument if index is out of range.
    void select(std::optional<std::size_t> index);

    /// Starts a gesture at `p`: selects the point hit (also from just outside the canvas, for
    /// points on its edge), or, on empty space inside the canvas, adds a point at p.x with
    /// opacity p.y and the colour the function has there, and selects it. On empty space outside
    /// the canvas (or non-finite p) nothing happens and the selection is cleared. Until
    /// pointerUp(), pointerDrag() moves the selected point.
    EditorAction pointerDown(glm::vec2 p);
    /// Moves the point grabbed by pointerDown() so that it keeps its offset from the pointer.
    /// Value and opacity are clamped to [0,1]. Returns false (and does nothing) if no gesture
    /// is active or p is not finite.
    bool pointerDrag(glm::vec2 p);
    /// Ends the gesture.
    void pointerUp();
    /// True between pointerDown() on a point and pointerUp().
    bool dragging() const { return m_dragging; }

    /// Adds a point at (p.x, p.y) (both clamped to [0,1]) with the colour the function has at p.x,
    /// selects it and returns its index. A point at exactly that value is replaced.
    /// @throws Error InvalidArgument if p is not finite.
    std::size_t addPoint(glm::vec2 p);
    /// Moves the selected point to value p.x and opacity p.y (clamped to [0,1]; see
    /// TransferFunctionEditorOptions::keepOrder) and returns its new index, or nullopt if nothing
    /// is selected or p is not finite. Consecutive moves are one undo step (a field being
    /// dragged), until endEdit() or any other operation.
    std::optional<std::size_t> moveSelected(glm::vec2 p);
    /// Removes the selected point. Returns false, leaving everything as it was, if nothing is
    /// selected or it is the only point left (a function always has one); lastError() says which.
    bool removeSelected();
    /// Removes the point under `p` (a right-click); false if none is hit or it is the last one.
    bool removeAt(glm::vec2 p);
    /// Sets the colour of the selected point. Consecutive calls are one undo step (a colour picker
    /// being dragged), until endEdit() or any other operation. Returns false if nothing is selected.
    /// @throws Error InvalidArgument if a channel is not finite or outside [0,1].
    bool setSelectedColor(glm::vec3 color);
    /// Sets the opacity of the selected point; false if nothing is selected.
    /// @throws Error InvalidArgument if opacity is not finite or outside [0,1].
    bool setSelectedOpacity(float opacity);

    /// Ends a run of moveSelected() or setSelectedColor() calls, so the next one starts a new undo
    /// step (a UI calls it when the field or picker is released).
    void endEdit() { m_lastEdit = LastEdit::Other; }

    /// Why the last operation that returned false refused; empty after one that succeeded.
    const std::string& lastError() const { return m_lastError; }

    bool canUndo() const { return !m_undo.empty(); }
    bool canRedo() const { return !m_redo.empty(); }
    /// Restores the function and selection before the last edit; false if there is none.
    bool undo();
    /// Re-applies the last undone edit; false if there is none. Any new edit clears the redo list.
    bool redo();
    std::size_t undoDepth() const { return m_undo.size(); }  ///< undo steps available
    std::size_t redoDepth() const { return m_redo.size(); }  ///< redo steps available

    /// Bar heights in [0,1] for a histogram backdrop: log(1 + count) / log(1 + max count), so
    /// sparse bins stay visible next to a huge background bin. All zeros if every count is 0.
    static std::vector<float> histogramBars(const std::vector<uint32_t>& counts);
    /// histogramBars(volume.histogram(bins, volume.transferFunctionRange())): the bars span the
    /// transfer function's domain, so bar i lies under x in [i / bins, (i + 1) / bins) (for 16-bit
    /// and float data the data's min..max or the value window, not 0..65535).
    /// @throws Error InvalidArgument unless 1 <= bins <= 65536.
    static std::vector<float> histogramBars(const Volume& volume, int bins = 128);

private:
    struct Snapshot {
        std::vector<ControlPoint> points;
        std::optional<std::size_t> selected;
    };
    enum class LastEdit { Other, Move, Color };

    Snapshot snapshot() const { return {m_tf.points(), m_selected}; }
    void restore(const Snapshot& s);
    void pushUndo();
    std::size_t applyMove(std::size_t index, glm::vec2 p);
    bool fail(std::string message);

    TransferFunction m_tf;
    TransferFunctionEditorOptions m_options;
    std::optional<std::size_t> m_selected;
    bool m_dragging = false;
    bool m_dragMoved = false;
    glm::vec2 m_grabOffset{0.0f};
    std::optional<Snapshot> m_gestureStart;  // undo state taken at pointerDown, pushed on first move
    LastEdit m_lastEdit = LastEdit::Other;
    std::vector<Snapshot> m_undo;
    std::vector<Snapshot> m_redo;
    std::string m_lastError;
};

}  // namespace sss

SSS_END_API
