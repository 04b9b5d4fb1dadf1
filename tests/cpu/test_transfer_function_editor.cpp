#include "sss/transfer_function_editor.h"

#include "sss/procedural.h"
#include "sss/volume.h"

#include "test_helpers.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

using Catch::Contains;
using sss::ControlPoint;
using sss::EditorAction;
using sss::ErrorKind;
using sss::TransferFunction;
using sss::TransferFunctionEditor;
using sss::TransferFunctionEditorOptions;
using sss::test::KindIs;

namespace {

// 0.2 red transparent, 0.6 green half opaque, 0.8 blue opaque.
TransferFunction threePoints() {
    return TransferFunction({{0.2f, {1, 0, 0}, 0.0f}, {0.6f, {0, 1, 0}, 0.5f}, {0.8f, {0, 0, 1}, 1.0f}});
}

const float kNaN = std::numeric_limits<float>::quiet_NaN();

}  // namespace

TEST_CASE("Editor hit-tests the nearest point inside the pick radius", "[cpu]") {
    TransferFunctionEditor editor(threePoints(), {.pickRadius = {0.05f, 0.1f}});
    CHECK(editor.hitTest({0.2f, 0.0f}) == std::optional<std::size_t>(0));
    CHECK(editor.hitTest({0.63f, 0.45f}) == std::optional<std::size_t>(1));
    CHECK(editor.hitTest({0.8f, 0.92f}) == std::optional<std::size_t>(2));
    // The radius is elliptical: 0.08 off in y is inside (0.1), 0.08 off in x is not (0.05).
    CHECK(editor.hitTest({0.6f, 0.58f}) == std::optional<std::size_t>(1));
    CHECK_FALSE(editor.hitTest({0.68f, 0.5f}).has_value());
    CHECK_FALSE(editor.hitTest({0.4f, 0.5f}).has_value());
    CHECK_FALSE(editor.hitTest({kNaN, 0.5f}).has_value());
    // Two candidates: the nearer one wins.
    TransferFunctionEditor close(TransferFunction({{0.50f, {1, 1, 1}, 0.5f}, {0.52f, {1, 1, 1}, 0.5f}}),
                                 {.pickRadius = {0.05f, 0.05f}});
    CHECK(close.hitTest({0.515f, 0.5f}) == std::optional<std::size_t>(1));
    CHECK(close.hitTest({0.505f, 0.5f}) == std::optional<std::size_t>(0));
}

TEST_CASE("Editor rejects bad options and bad selections", "[cpu]") {
    CHECK_THROWS_MATCHES(TransferFunctionEditor(TransferFunction(), {.pickRadius = {0.0f, 0.1f}}), sss::Error,
                         KindIs(ErrorKind::InvalidArgument));
    TransferFunctionEditor editor(threePoints());
    CHECK_THROWS_WITH(editor.setOptions({.pickRadius = {kNaN, 0.1f}}), Contains("pickRadius"));
    CHECK_THROWS_WITH(editor.select(3), Contains("out of range"));
    editor.select(2);
    CHECK(editor.selected() == std::optional<std::size_t>(2));
    editor.select(std::nullopt);
    CHECK_FALSE(editor.selected().has_value());
}

TEST_CASE("Clicking a point selects it without editing", "[cpu]") {
    TransferFunctionEditor editor(threePoints());
    const uint64_t revision = editor.transferFunction().revision();
    CHECK(editor.pointerDown({0.605f, 0.51f}) == EditorAction::Selected);
    CHECK(editor.selected() == std::optional<std::size_t>(1));
    CHECK(editor.dragging());
    editor.pointerUp();
    CHECK_FALSE(editor.dragging());
    CHECK(editor.transferFunction().revision() == revision);
    CHECK_FALSE(editor.canUndo());  // a click is no edit
    // A point on the canvas edge can be grabbed from just outside it.
    TransferFunctionEditor ramp;
    CHECK(ramp.pointerDown({1.01f, 1.02f}) == EditorAction::Selected);
    CHECK(ramp.selected() == std::optional<std::size_t>(1));
}

TEST_CASE("Clicking empty space adds a point coloured from the function", "[cpu]") {
    TransferFunctionEditor editor(threePoints());
    CHECK(editor.pointerDown({0.4f, 0.9f}) == EditorAction::Added);
    const auto& points = editor.transferFunction().points();
    REQUIRE(points.size() == 4);
    REQUIRE(editor.selected() == std::optional<std::size_t>(1));
    CHECK(points[1].value == Approx(0.4f));
    CHECK(points[1].opacity == Approx(0.9f));  // opacity from the click, not the curve
    // Colour halfway between red (0.2) and green (0.6).
    CHECK(points[1].color.r == Approx(0.5f));
    CHECK(points[1].color.g == Approx(0.5f));
    CHECK(points[1].color.b == Approx(0.0f));
    CHECK(editor.canUndo());
    // Outside the canvas nothing is added and the selection is dropped.
    CHECK(editor.pointerDown({1.2f, 0.5f}) == EditorAction::None);
    CHECK(editor.transferFunction().points().size() == 4);
    CHECK_FALSE(editor.selected().has_value());
    CHECK(editor.pointerDown({kNaN, 0.5f}) == EditorAction::None);
}

TEST_CASE("addPoint clamps to the canvas", "[cpu]") {
    TransferFunctionEditor editor(threePoints());
    const std::size_t index = editor.addPoint({1.5f, -0.5f});
    const ControlPoint& p = editor.transferFunction().points()[index];
    CHECK(index == 3);
    CHECK(p.value == 1.0f);
    CHECK(p.opacity == 0.0f);
    CHECK(p.color == glm::vec3(0, 0, 1));  // constant beyond the last point
    CHECK_THROWS_MATCHES(editor.addPoint({kNaN, 0.0f}), sss::Error, KindIs(ErrorKind::InvalidArgument));
}

TEST_CASE("Dragging moves value and opacity, clamped, keeping the grab offset", "[cpu]") {
    TransferFunctionEditor editor(threePoints());
    REQUIRE(editor.pointerDown({0.61f, 0.52f}) == EditorAction::Selected);  // grabbed 0.01/0.02 off
    CHECK(editor.pointerDrag({0.71f, 0.32f}));
    const auto& points = editor.transferFunction().points();
    CHECK(points[1].value == Approx(0.7f));
    CHECK(points[1].opacity == Approx(0.3f));
    CHECK(points[1].color == glm::vec3(0, 1, 0));  // the colour travels with the point
    CHECK(editor.pointerDrag({0.71f, 5.0f}));
    CHECK(points[1].opacity == 1.0f);
    editor.pointerUp();
    CHECK_FALSE(editor.pointerDrag({0.3f, 0.3f}));  // no gesture any more
    CHECK(points[1].value == Approx(0.7f));
    // The whole gesture is one undo step.
    CHECK(editor.undoDepth() == 1);
    REQUIRE(editor.undo());
    CHECK(editor.transferFunction().points()[1].value == Approx(0.6f));
    CHECK(editor.transferFunction().points()[1].opacity == Approx(0.5f));
}

TEST_CASE("Dragging past a neighbour re-sorts like TransferFunction::movePoint", "[cpu]") {
    TransferFunctionEditor editor(threePoints());
    REQUIRE(editor.pointerDown({0.2f, 0.0f}) == EditorAction::Selected);
    CHECK(editor.pointerDrag({0.7f, 0.2f}));
    // red moved between green (0.6) and blue (0.8): it is index 1 now, and stays selected.
    REQUIRE(editor.selected() == std::optional<std::size_t>(1));
    CHECK(editor.transferFunction().points()[1].color == glm::vec3(1, 0, 0));
    CHECK(editor.pointerDrag({2.0f, 0.2f}));
    REQUIRE(editor.selected() == std::optional<std::size_t>(2));
    CHECK(editor.transferFunction().points()[2].value == 1.0f);
    // Dropping it exactly on another point's value nudges it instead of merging.
    CHECK(editor.pointerDrag({0.8f, 0.2f}));
    CHECK(editor.transferFunction().points().size() == 3);
    editor.pointerUp();
}

TEST_CASE("keepOrder stops a dragged point at its neighbours", "[cpu]") {
    TransferFunctionEditor editor(threePoints(), {.keepOrder = true});
    REQUIRE(editor.pointerDown({0.6f, 0.5f}) == EditorAction::Selected);
    CHECK(editor.pointerDrag({0.95f, 0.5f}));
    const auto& points = editor.transferFunction().points();
    REQUIRE(editor.selected() == std::optional<std::size_t>(1));
    CHECK(points[1].color == glm::vec3(0, 1, 0));
    CHECK(points[1].value < 0.8f);
    CHECK(points[1].value > 0.79999f);
    CHECK(editor.pointerDrag({0.0f, 0.5f}));
    CHECK(points[1].value > 0.2f);
    CHECK(points[1].value < 0.20001f);
}

TEST_CASE("moveSelected needs a selection", "[cpu]") {
    TransferFunctionEditor editor(threePoints());
    CHECK_FALSE(editor.moveSelected({0.5f, 0.5f}).has_value());
    CHECK_THAT(editor.lastError(), Contains("selected"));
    editor.select(0);
    CHECK(editor.moveSelected({0.1f, 0.25f}) == std::optional<std::size_t>(0));
    CHECK(editor.transferFunction().points()[0].value == Approx(0.1f));
    CHECK(editor.transferFunction().points()[0].opacity == Approx(0.25f));
    CHECK(editor.lastError().empty());
    // A field being dragged is one undo step; endEdit() starts the next.
    CHECK(editor.moveSelected({0.12f, 0.3f}).has_value());
    CHECK(editor.undoDepth() == 1);
    editor.endEdit();
    CHECK(editor.moveSelected({0.14f, 0.3f}).has_value());
    CHECK(editor.undoDepth() == 2);
    CHECK_FALSE(editor.moveSelected({kNaN, 0.5f}).has_value());
    REQUIRE(editor.undo());
    REQUIRE(editor.undo());
    CHECK(editor.transferFunction().points()[0].value == Approx(0.2f));
}

TEST_CASE("Deleting removes the selected point but never the last one", "[cpu]") {
    TransferFunctionEditor editor(threePoints());
    CHECK_FALSE(editor.removeSelected());
    CHECK_THAT(editor.lastError(), Contains("no point is selected"));
    editor.select(1);
    REQUIRE(editor.removeSelected());
    CHECK(editor.lastError().empty());
    CHECK_FALSE(editor.selected().has_value());
    REQUIRE(editor.transferFunction().points().size() == 2);
    CHECK(editor.transferFunction().points()[1].color == glm::vec3(0, 0, 1));
    // Right-click removal hits by position.
    CHECK_FALSE(editor.removeAt({0.5f, 0.5f}));
    CHECK_THAT(editor.lastError(), Contains("no control point"));
    REQUIRE(editor.removeAt({0.8f, 1.0f}));
    REQUIRE(editor.transferFunction().points().size() == 1);
    // The last point stays, with a clear reason, and the history gets no empty step.
    const std::size_t depth = editor.undoDepth();
    editor.select(0);
    CHECK_FALSE(editor.removeSelected());
    CHECK_THAT(editor.lastError(), Contains("last control point"));
    CHECK_FALSE(editor.removeAt({0.2f, 0.0f}));
    CHECK(editor.transferFunction().points().size() == 1);
    CHECK(editor.selected() == std::optional<std::size_t>(0));
    CHECK(editor.undoDepth() == depth);
}

TEST_CASE("Setting the selected point's colour and opacity", "[cpu]") {
    TransferFunctionEditor editor(threePoints());
    CHECK_FALSE(editor.setSelectedColor({1, 1, 0}));
    editor.select(2);
    REQUIRE(editor.setSelectedColor({1, 1, 0}));
    CHECK(editor.transferFunction().points()[2].color == glm::vec3(1, 1, 0));
    CHECK(editor.transferFunction().points()[2].opacity == 1.0f);
    // A colour picker being dragged is one undo step.
    REQUIRE(editor.setSelectedColor({0.5f, 1, 0}));
    REQUIRE(editor.setSelectedColor({0.25f, 1, 0}));
    CHECK(editor.undoDepth() == 1);
    CHECK_THROWS_MATCHES(editor.setSelectedColor({2, 0, 0}), sss::Error, KindIs(ErrorKind::InvalidArgument));
    CHECK(editor.transferFunction().points()[2].color == glm::vec3(0.25f, 1, 0));
    REQUIRE(editor.setSelectedOpacity(0.125f));
    CHECK(editor.transferFunction().points()[2].opacity == 0.125f);
    CHECK(editor.undoDepth() == 2);
    CHECK_THROWS_MATCHES(editor.setSelectedOpacity(kNaN), sss::Error, KindIs(ErrorKind::InvalidArgument));
    REQUIRE(editor.undo());
    REQUIRE(editor.undo());
    CHECK(editor.transferFunction().points()[2].color == glm::vec3(0, 0, 1));
}

TEST_CASE("Undo and redo restore function and selection", "[cpu]") {
    TransferFunctionEditor editor(threePoints(), {.undoLimit = 3});
    CHECK_FALSE(editor.undo());
    CHECK_FALSE(editor.redo());
    editor.addPoint({0.4f, 0.4f});  // 4 points, selected 1
    editor.select(3);
    REQUIRE(editor.removeSelected());  // 3 points: 0.2, 0.4, 0.6
    uint64_t revision = editor.transferFunction().revision();
    REQUIRE(editor.undo());
    CHECK(editor.transferFunction().revision() != revision);  // renderers notice the change
    CHECK(editor.transferFunction().points().size() == 4);
    CHECK(editor.selected() == std::optional<std::size_t>(3));
    REQUIRE(editor.undo());
    CHECK(editor.transferFunction().points().size() == 3);
    CHECK(editor.transferFunction().points()[1].value == Approx(0.6f));
    CHECK_FALSE(editor.canUndo());
    REQUIRE(editor.redo());
    REQUIRE(editor.redo());
    CHECK(editor.transferFunction().points().size() == 3);
    CHECK(editor.transferFunction().points()[2].value == Approx(0.6f));
    CHECK_FALSE(editor.canRedo());
    // A new edit after an undo drops the redo list.
    REQUIRE(editor.undo());
    CHECK(editor.canRedo());
    editor.setTransferFunction(TransferFunction::preset("bucky"));
    CHECK_FALSE(editor.canRedo());
    CHECK_FALSE(editor.selected().has_value());
    // The history is bounded by undoLimit.
    for (int i = 0; i < 5; ++i) editor.addPoint({0.05f * static_cast<float>(i + 1), 0.5f});
    CHECK(editor.undoDepth() == 3);
    revision = editor.transferFunction().revision();
    while (editor.undo()) {
    }
    CHECK(editor.transferFunction().revision() != revision);
    CHECK(editor.transferFunction().points().size() == TransferFunction::preset("bucky").points().size() + 2);
}

TEST_CASE("Histogram bars are log-scaled into [0,1]", "[cpu]") {
    const std::vector<float> bars = TransferFunctionEditor::histogramBars({0, 1, 9, 99, 999});
    REQUIRE(bars.size() == 5);
    CHECK(bars[0] == 0.0f);
    CHECK(bars[4] == Approx(1.0f));
    CHECK(bars[3] == Approx(std::log(100.0) / std::log(1000.0)));
    CHECK(bars[1] == Approx(std::log(2.0) / std::log(1000.0)));
    CHECK(bars[1] > 0.09f);  // a single voxel is still visible next to 999 (linear: 0.001)
    CHECK(TransferFunctionEditor::histogramBars({0, 0, 0}) == std::vector<float>{0, 0, 0});
    CHECK(TransferFunctionEditor::histogramBars(std::vector<uint32_t>{}).empty());

    const sss::Volume shell = sss::makeShellVolume(16);
    const std::vector<float> fromVolume = TransferFunctionEditor::histogramBars(shell, 64);
    REQUIRE(fromVolume.size() == 64);
    CHECK(fromVolume.front() == Approx(1.0f));  // most of a shell volume is empty space
    const int top = static_cast<int>(shell.valueRange().second) * 64 / 256;  // the densest voxels' bin (0..255, 64 bins)
    CHECK(fromVolume[static_cast<std::size_t>(top)] > 0.0f);
    for (float b : fromVolume) {
        CHECK(b >= 0.0f);
        CHECK(b <= 1.0f);
    }
    CHECK_THROWS_MATCHES(TransferFunctionEditor::histogramBars(shell, 0), sss::Error,
                         KindIs(ErrorKind::InvalidArgument));
}

TEST_CASE("Histogram bars of 16-bit data span the editor's x axis: the data's min..max, not 0..65535", "[cpu]") {
    // A 12-bit-like volume with values 1000..4000: 1000..2499 twice each, 2500..4000 once each.
    std::vector<uint8_t> bytes;
    auto add = [&](int value) {
        bytes.push_back(static_cast<uint8_t>(value & 0xff));
        bytes.push_back(static_cast<uint8_t>(value >> 8));
    };
    for (int v = 1000; v <= 4000; ++v) {
        add(v);
        if (v < 2500) add(v);
    }
    const int voxels = static_cast<int>(bytes.size() / 2);  // 4501
    const sss::Volume volume = sss::Volume::fromData({voxels, 1, 1}, sss::VoxelType::UInt16, bytes);
    REQUIRE(volume.transferFunctionRange() == std::pair<double, double>(1000.0, 4000.0));

    // The counts behind the bars: 128 bins of 3000 / 128 = 23.4 values; bin 64 starts at 2500.
    const std::vector<uint32_t> counts = volume.histogram(128, volume.transferFunctionRange());
    REQUIRE(counts.size() == 128);
    for (std::size_t i = 0; i < 64; ++i) {
        INFO("bin " << i);
        CHECK(counts[i] >= 2 * 23);
        CHECK(counts[i] <= 2 * 24);
    }
    for (std::size_t i = 64; i < 128; ++i) {
        INFO("bin " << i);
        CHECK(counts[i] >= 23);
        CHECK(counts[i] <= 25);  // the last bin also holds 4000
    }

    // Every bar is drawn (binned over 0..65535, only bars 1..7 were), in proportion: log(1 + n).
    const std::vector<float> bars = TransferFunctionEditor::histogramBars(volume, 128);
    REQUIRE(bars.size() == 128);
    const double top = std::log1p(48.0);
    for (std::size_t i = 0; i < 128; ++i) {
        INFO("bar " << i);
        const double n = i < 64 ? 47.0 : 23.5;
        CHECK(bars[i] == Approx(std::log1p(n) / top).margin(0.02));
    }
}
