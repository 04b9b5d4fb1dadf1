#include "tf_editor_widget.h"

#include <imgui.h>

#include <glm/common.hpp>

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <vector>

namespace viewer {
namespace {

ImU32 toColor(glm::vec3 c, float alpha = 1.0f) {
    return ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, alpha));
}

// Keys the canvas reacts to while no text field has the keyboard. ImGui 1.86 indexes keys by
// the backend's (GLFW's) key codes.
bool pressed(int glfwKey) { return ImGui::IsKeyPressed(glfwKey, false); }

}  // namespace

namespace {

// Where the canvas is on screen, and the mapping between screen pixels and (value, opacity).
struct Canvas {
    ImVec2 origin, outerMax, min, max, size;
    glm::vec2 toCanvas(ImVec2 p) const { return {(p.x - min.x) / size.x, 1.0f - (p.y - min.y) / size.y}; }
    ImVec2 toScreen(float value, float opacity) const {
        return {min.x + value * size.x, min.y + (1.0f - opacity) * size.y};
    }
};

constexpr float kMargin = 7.0f;  // room for points on the edges

Canvas layOut(float height) {
    Canvas c;
    c.origin = ImGui::GetCursorScreenPos();
    const float width = std::max(ImGui::GetContentRegionAvail().x, 64.0f);
    c.outerMax = ImVec2(c.origin.x + width, c.origin.y + height);
    c.min = ImVec2(c.origin.x + kMargin, c.origin.y + kMargin);
    c.max = ImVec2(c.outerMax.x - kMargin, c.outerMax.y - kMargin - 12.0f);  // 12 px colour bar below
    c.size = ImVec2(c.max.x - c.min.x, c.max.y - c.min.y);
    return c;
}

// Mouse on the canvas, and the keyboard while no text field is being edited.
void handleInput(sss::TransferFunctionEditor& editor, bool hovered, glm::vec2 mouse) {
    if (ImGui::IsItemActivated() && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) editor.pointerDown(mouse);
    if (ImGui::IsItemActive() && editor.dragging() &&
        (ImGui::GetIO().MouseDelta.x != 0.0f || ImGui::GetIO().MouseDelta.y != 0.0f))
        editor.pointerDrag(mouse);
    if (editor.dragging() && !ImGui::IsMouseDown(ImGuiMouseButton_Left)) editor.pointerUp();
    if (hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Right)) editor.removeAt(mouse);
    if (ImGui::GetIO().WantTextInput) return;
    if ((pressed(GLFW_KEY_DELETE) || pressed(GLFW_KEY_BACKSPACE)) && editor.selected()) editor.removeSelected();
    if (ImGui::GetIO().KeyCtrl && pressed(GLFW_KEY_Z)) editor.undo();
    if (ImGui::GetIO().KeyCtrl && pressed(GLFW_KEY_Y)) editor.redo();
}

// Backdrop, histogram, grid, and the colour bar: the function's colour with its opacity over a
// dark background.
void drawBackground(ImDrawList* draw, const Canvas& c, const TfEditorWidgetState& state, const sss::TransferFunction& tf) {
    draw->AddRectFilled(c.origin, c.outerMax, IM_COL32(24, 24, 28, 255), 3.0f);
    if (!state.histogram.empty()) {
        const float barWidth = c.size.x / static_cast<float>(state.histogram.size());
        for (std::size_t i = 0; i < state.histogram.size(); ++i) {
            const float x0 = c.min.x + static_cast<float>(i) * barWidth;
            draw->AddRectFilled(ImVec2(x0, c.max.y - state.histogram[i] * c.size.y),
                                ImVec2(x0 + std::max(barWidth, 1.0f), c.max.y), IM_COL32(90, 90, 100, 160));
        }
    }
    for (int i = 1; i < 4; ++i) {
        const float t = static_cast<float>(i) / 4.0f;
        draw->AddLine(c.toScreen(t, 0.0f), c.toScreen(t, 1.0f), IM_COL32(255, 255, 255, 25));
        draw->AddLine(c.toScreen(0.0f, t), c.toScreen(1.0f, t), IM_COL32(255, 255, 255, 25));
    }
    draw->AddRect(c.min, c.max, IM_COL32(255, 255, 255, 60));
    const int segments = std::max(2, static_cast<int>(c.size.x / 3.0f));
    for (int i = 0; i < segments; ++i) {
        const float t0 = static_cast<float>(i) / static_cast<float>(segments);
        const float t1 = static_cast<float>(i + 1) / static_cast<float>(segments);
        const glm::vec4 colour = tf.evaluate(0.5f * (t0 + t1));
        draw->AddRectFilled(ImVec2(c.min.x + t0 * c.size.x, c.max.y + 4.0f),
                            ImVec2(c.min.x + t1 * c.size.x + 1.0f, c.max.y + 14.0f),
                            toColor(glm::vec3(colour), 0.35f + 0.65f * colour.a));
    }
}

// Opacity polyline (constant beyond the end points) and the points in their colours.
void drawPoints(ImDrawList* draw, const Canvas& c, const sss::TransferFunctionEditor& editor,
                std::optional<std::size_t> hit) {
    const auto& points = editor.transferFunction().points();
    std::vector<ImVec2> line;
    line.push_back(c.toScreen(0.0f, points.front().opacity));
    for (const sss::ControlPoint& p : points) line.push_back(c.toScreen(p.value, p.opacity));
    line.push_back(c.toScreen(1.0f, points.back().opacity));
    draw->AddPolyline(line.data(), static_cast<int>(line.size()), IM_COL32(230, 230, 230, 220), 0, 1.5f);
    for (std::size_t i = 0; i < points.size(); ++i) {
        const ImVec2 at = c.toScreen(points[i].value, points[i].opacity);
        const bool isSelected = editor.selected() == i;
        draw->AddCircleFilled(at, isSelected ? 6.5f : 5.0f, toColor(points[i].color));
        draw->AddCircle(at, isSelected ? 7.5f : 5.5f,
                        isSelected ? IM_COL32(255, 220, 60, 255)
                                   : (hit == i ? IM_COL32(255, 255, 255, 255) : IM_COL32(0, 0, 0, 200)),
                        0, isSelected ? 2.0f : 1.0f);
    }
}

// The selected point's value, opacity and colour, then undo and redo.
void pointControls(sss::TransferFunctionEditor& editor) {
    const auto& points = editor.transferFunction().points();
    if (const auto s = editor.selected()) {
        const sss::ControlPoint p = points[*s];
        float position[2] = {p.value, p.opacity};
        ImGui::SetNextItemWidth(160.0f);
        if (ImGui::DragFloat2("value, opacity", position, 0.002f, 0.0f, 1.0f, "%.3f"))
            editor.moveSelected({position[0], position[1]});
        if (ImGui::IsItemDeactivatedAfterEdit()) editor.endEdit();
        ImGui::SameLine();
        float color[3] = {p.color.r, p.color.g, p.color.b};
        if (ImGui::ColorEdit3("colour", color, ImGuiColorEditFlags_NoInputs | ImGuiColorEditFlags_Float))
            editor.setSelectedColor(glm::clamp(glm::vec3(color[0], color[1], color[2]), glm::vec3(0.0f),
                                               glm::vec3(1.0f)));
        if (ImGui::IsItemDeactivatedAfterEdit()) editor.endEdit();
        ImGui::SameLine();
        if (ImGui::Button("Delete point")) editor.removeSelected();
    } else {
        ImGui::TextDisabled("click the canvas to add or select a point");
    }
    ImGui::BeginDisabled(!editor.canUndo());
    if (ImGui::Button("Undo")) editor.undo();
    ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::BeginDisabled(!editor.canRedo());
    if (ImGui::Button("Redo")) editor.redo();
    ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::Text("%zu points", editor.transferFunction().points().size());
    if (!editor.lastError().empty()) {
        ImGui::SameLine();
        ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "%s", editor.lastError().c_str());
    }
}

}  // namespace

bool transferFunctionEditorWidget(sss::TransferFunctionEditor& editor, const TfEditorWidgetState& state,
                                  float height, ScreenRect* canvas) {
    const uint64_t revisionBefore = editor.transferFunction().revision();
    const Canvas c = layOut(height);
    if (canvas) *canvas = {c.min.x, c.min.y, c.max.x, c.max.y};
    // Picking is a circle of 7 px on screen, whatever the canvas's aspect.
    sss::TransferFunctionEditorOptions options = editor.options();
    options.pickRadius = {kMargin / c.size.x, kMargin / c.size.y};
    editor.setOptions(options);

    ImGui::InvisibleButton("tf-canvas", ImVec2(c.outerMax.x - c.origin.x, height),
                           ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight);
    const bool hovered = ImGui::IsItemHovered();
    const glm::vec2 mouse = c.toCanvas(ImGui::GetIO().MousePos);
    handleInput(editor, hovered, mouse);

    ImDrawList* draw = ImGui::GetWindowDrawList();
    drawBackground(draw, c, state, editor.transferFunction());
    const auto hit = hovered ? editor.hitTest(mouse) : std::nullopt;
    drawPoints(draw, c, editor, hit);
    if (hovered && !editor.dragging()) {
        const glm::vec2 m = glm::clamp(mouse, glm::vec2(0.0f), glm::vec2(1.0f));
        ImGui::SetTooltip("value %.3f (raw %d), opacity %.3f\n%s", m.x,
                          static_cast<int>(std::lround(state.rawRange.first +
                                                       m.x * (state.rawRange.second - state.rawRange.first))),
                          m.y, hit ? "drag: move, right-click: delete" : "click: add a point");
    }
    pointControls(editor);
    return editor.transferFunction().revision() != revisionBefore;
}

}  // namespace viewer
