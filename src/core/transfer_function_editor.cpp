#include "sss/transfer_function_editor.h"

#include "util/format.h"

#include "sss/error.h"
#include "sss/volume.h"

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace sss {
namespace {

bool finite(glm::vec2 p) { return std::isfinite(p.x) && std::isfinite(p.y); }

void checkOptions(const TransferFunctionEditorOptions& options) {
    const glm::vec2 r = options.pickRadius;
    if (!finite(r) || !(r.x > 0.0f) || !(r.y > 0.0f))
        throw Error(ErrorKind::InvalidArgument, "TransferFunctionEditorOptions::pickRadius must be finite and > 0, got (" +
                                                    detail::formatNumber(r.x) + ", " + detail::formatNumber(r.y) + ")");
}

bool insideCanvas(glm::vec2 p) { return p.x >= 0.0f && p.x <= 1.0f && p.y >= 0.0f && p.y <= 1.0f; }

}  // namespace

TransferFunctionEditor::TransferFunctionEditor(TransferFunction tf, const TransferFunctionEditorOptions& options)
    : m_tf(std::move(tf)), m_options(options) {
    checkOptions(options);
}

void TransferFunctionEditor::setTransferFunction(const TransferFunction& tf) {
    pushUndo();
    m_tf = tf;
    m_selected.reset();
    m_dragging = false;
    m_gestureStart.reset();
}

void TransferFunctionEditor::setOptions(const TransferFunctionEditorOptions& options) {
    checkOptions(options);
    m_options = options;
    while (m_undo.size() > m_options.undoLimit) m_undo.erase(m_undo.begin());
}

std::optional<std::size_t> TransferFunctionEditor::hitTest(glm::vec2 p) const {
    if (!finite(p)) return std::nullopt;
    std::optional<std::size_t> best;
    float bestDistance = 1.0f;  // in pick radii: inside the ellipse is <= 1
    const auto& points = m_tf.points();
    for (std::size_t i = 0; i < points.size(); ++i) {
        const glm::vec2 d = (glm::vec2(points[i].value, points[i].opacity) - p) / m_options.pickRadius;
        const float distance = std::sqrt(d.x * d.x + d.y * d.y);
        if (distance <= bestDistance) {
            bestDistance = distance;
            best = i;
        }
    }
    return best;
}

void TransferFunctionEditor::select(std::optional<std::size_t> index) {
    if (index && *index >= m_tf.points().size())
        throw Error(ErrorKind::InvalidArgument, "TransferFunctionEditor::select: index " + std::to_string(*index) +
                                                    " out of range (" + std::to_string(m_tf.points().size()) +
                                                    " points)");
    m_selected = index;
    m_lastEdit = LastEdit::Other;
}

EditorAction TransferFunctionEditor::pointerDown(glm::vec2 p) {
    m_lastEdit = LastEdit::Other;
    m_lastError.clear();
    m_dragging = false;
    m_gestureStart.reset();
    if (!finite(p)) {
        m_selected.reset();
        return EditorAction::None;
    }
    // Hit-test first: a point on the canvas edge can be grabbed from just outside it.
    if (const auto hit = hitTest(p)) {
        m_selected = hit;
        const ControlPoint& point = m_tf.points()[*hit];
        m_grabOffset = glm::vec2(point.value, point.opacity) - p;
        m_gestureStart = snapshot();  // pushed only once the point really moves
        m_dragging = true;
        return EditorAction::Selected;
    }
    if (!insideCanvas(p)) {
        m_selected.reset();
        return EditorAction::None;
    }
    addPoint(p);  // one undo step; the drag that may follow belongs to it
    m_grabOffset = glm::vec2(0.0f);
    m_dragging = true;
    return EditorAction::Added;
}

bool TransferFunctionEditor::pointerDrag(glm::vec2 p) {
    if (!m_dragging || !m_selected || !finite(p)) return false;
    if (m_gestureStart) {
        m_redo.clear();
        m_undo.push_back(std::move(*m_gestureStart));
        m_gestureStart.reset();
        if (m_undo.size() > m_options.undoLimit) m_undo.erase(m_undo.begin());
    }
    m_selected = applyMove(*m_selected, p + m_grabOffset);
    return true;
}

void TransferFunctionEditor::pointerUp() {
    m_dragging = false;
    m_gestureStart.reset();
}

std::size_t TransferFunctionEditor::addPoint(glm::vec2 p) {
    if (!finite(p))
        throw Error(ErrorKind::InvalidArgument, "TransferFunctionEditor::addPoint: position must be finite");
    p = glm::clamp(p, glm::vec2(0.0f), glm::vec2(1.0f));
    m_lastEdit = LastEdit::Other;
    m_lastError.clear();
    pushUndo();
    const glm::vec3 color = glm::clamp(glm::vec3(m_tf.evaluate(p.x)), glm::vec3(0.0f), glm::vec3(1.0f));
    m_selected = m_tf.addPoint({p.x, color, p.y});
    return *m_selected;
}

std::size_t TransferFunctionEditor::applyMove(std::size_t index, glm::vec2 p) {
    p = glm::clamp(p, glm::vec2(0.0f), glm::vec2(1.0f));
    const auto& points = m_tf.points();
    float value = p.x;
    if (m_options.keepOrder) {
        // Stay strictly between the neighbours; with no room left the point keeps its value.
        const float lo = index > 0 ? std::nextafter(points[index - 1].value, 2.0f) : 0.0f;
        const float hi = index + 1 < points.size() ? std::nextafter(points[index + 1].value, -1.0f) : 1.0f;
        value = lo <= hi ? std::clamp(value, lo, hi) : points[index].value;
    }
    const glm::vec3 color = points[index].color;
    const std::size_t moved = m_tf.movePoint(index, value);
    m_tf.setPoint(moved, color, p.y);
    return moved;
}

std::optional<std::size_t> TransferFunctionEditor::moveSelected(glm::vec2 p) {
    if (!m_selected || !finite(p)) {
        m_lastEdit = LastEdit::Other;
        fail(m_selected ? "the position is not finite" : "no point is selected");
        return std::nullopt;
    }
    m_lastError.clear();
    if (m_lastEdit != LastEdit::Move) pushUndo();
    m_selected = applyMove(*m_selected, p);
    m_lastEdit = LastEdit::Move;
    return m_selected;
}

bool TransferFunctionEditor::removeSelected() {
    m_lastEdit = LastEdit::Other;
    if (!m_selected) return fail("no point is selected");
    if (m_tf.points().size() <= 1)
        return fail("cannot remove the last control point: a transfer function needs at least one");
    pushUndo();
    m_tf.removePoint(*m_selected);
    m_selected.reset();
    m_dragging = false;
    m_lastError.clear();
    return true;
}

bool TransferFunctionEditor::removeAt(glm::vec2 p) {
    const auto hit = hitTest(p);
    if (!hit) {
        m_lastEdit = LastEdit::Other;
        return fail("no control point under the pointer");
    }
    const auto previous = m_selected;
    m_selected = hit;
    if (removeSelected()) return true;
    m_selected = previous;
    return false;
}

bool TransferFunctionEditor::setSelectedColor(glm::vec3 color) {
    if (!m_selected) {
        m_lastEdit = LastEdit::Other;
        return fail("no point is selected");
    }
    const ControlPoint point = m_tf.points()[*m_selected];
    // Validate before touching the history, so a refused colour leaves no empty undo step.
    TransferFunction probe({{point.value, color, point.opacity}});
    if (m_lastEdit != LastEdit::Color) pushUndo();
    m_tf.setPoint(*m_selected, color, point.opacity);
    m_lastEdit = LastEdit::Color;
    m_lastError.clear();
    return true;
}

bool TransferFunctionEditor::setSelectedOpacity(float opacity) {
    m_lastEdit = LastEdit::Other;
    if (!m_selected) return fail("no point is selected");
    const ControlPoint point = m_tf.points()[*m_selected];
    TransferFunction probe({{point.value, point.color, opacity}});
    pushUndo();
    m_tf.setPoint(*m_selected, point.color, opacity);
    m_lastError.clear();
    return true;
}

bool TransferFunctionEditor::undo() {
    m_lastEdit = LastEdit::Other;
    if (m_undo.empty()) return fail("nothing to undo");
    m_redo.push_back(snapshot());
    restore(m_undo.back());
    m_undo.pop_back();
    m_lastError.clear();
    return true;
}

bool TransferFunctionEditor::redo() {
    m_lastEdit = LastEdit::Other;
    if (m_redo.empty()) return fail("nothing to redo");
    m_undo.push_back(snapshot());
    restore(m_redo.back());
    m_redo.pop_back();
    m_lastError.clear();
    return true;
}

void TransferFunctionEditor::restore(const Snapshot& s) {
    // A new TransferFunction gets a new revision, so renderers caching revision() re-upload.
    m_tf = TransferFunction(s.points);
    m_selected = s.selected && *s.selected < s.points.size() ? s.selected : std::nullopt;
    m_dragging = false;
    m_gestureStart.reset();
}

void TransferFunctionEditor::pushUndo() {
    m_redo.clear();
    m_undo.push_back(snapshot());
    if (m_undo.size() > m_options.undoLimit) m_undo.erase(m_undo.begin());
}

bool TransferFunctionEditor::fail(std::string message) {
    m_lastError = std::move(message);
    return false;
}

std::vector<float> TransferFunctionEditor::histogramBars(const std::vector<uint32_t>& counts) {
    std::vector<float> bars(counts.size(), 0.0f);
    const uint32_t largest = counts.empty() ? 0 : *std::max_element(counts.begin(), counts.end());
    if (largest == 0) return bars;
    const double scale = 1.0 / std::log1p(static_cast<double>(largest));
    for (std::size_t i = 0; i < counts.size(); ++i)
        bars[i] = static_cast<float>(std::log1p(static_cast<double>(counts[i])) * scale);
    return bars;
}

std::vector<float> TransferFunctionEditor::histogramBars(const Volume& volume, int bins) {
    return histogramBars(volume.histogram(bins, volume.transferFunctionRange()));
}

}  // namespace sss
