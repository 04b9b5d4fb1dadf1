#include "tf_editor_widget.h"

#include <imgui.h>

#include <glm/common.hpp>

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace viewer {
namespace {

ImU32 toColor(glm::vec3 c, float alpha = 1.0f) {
    return ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, alpha));
}

// Keys the canvas reacts to while no text field has the keyboard. ImGui 1.86 indexes keys by
// the backend's (GLFW's) key codes.
bool pressed(int glfwKey) { return ImGui::IsKeyPressed(glfwKey, false); }

}  // namespace

bool transferFunctionEditorWidget(sss::TransferFunctionEditor& editor, const TfEditorWidgetState& state,
                                  float height, ScreenRect* canvas) {
    const uint64_t revisionBefore = editor.transferFunction().revision();
    ImDrawList* draw = ImGui::GetWindowDrawList();
    const float margin = 7.0f;  // room for points on the edges
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    const float width = std::max(ImGui::GetContentRegionAvail().x, 64.0f);
    const ImVec2 outerMax(origin.x + width, origin.y + height);
    const ImVec2 canvasMin(origin.x + margin, origin.y + margin);
    const ImVec2 canvasMax(outerMax.x - margin, outerMax.y - margin - 12.0f);  // 12 px colour bar below
    const ImVec2 size(canvasMax.x - canvasMin.x, canvasMax.y - canvasMin.y);
    if (canvas) *canvas = {canvasMin.x, canvasMin.y, canvasMax.x, canvasMax.y};
    auto toCanvas = [&](ImVec2 p) {
        return glm::vec2((p.x - canvasMin.x) / size.x, 1.0f - (p.y - canvasMin.y) / size.y);
    };
    auto toScreen = [&](float value, float opacity) {
        return ImVec2(canvasMin.x + value * size.x, canvasMin.y + (1.0f - opacity) * size.y);
    };

    // Picking is a circle of 7 px on screen, whatever the canvas's aspect.
    sss::TransferFunctionEditorOptions options = editor.options();
    options.pickRadius = {margin / size.x, margin / size.y};
    editor.setOptions(options);

    ImGui::InvisibleButton("tf-canvas", ImVec2(width, height),
                           ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight);
    const bool hovered = ImGui::IsItemHovered();
    const glm::vec2 mouse = toCanvas(ImGui::GetIO().MousePos);
    if (ImGui::IsItemActivated() && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) editor.pointerDown(mouse);
    if (ImGui::IsItemActive() && editor.dragging() &&
        (ImGui::GetIO().MouseDelta.x != 0.0f || ImGui::GetIO().MouseDelta.y != 0.0f))
        editor.pointerDrag(mouse);
    if (editor.dragging() && !ImGui::IsMouseDown(ImGuiMouseButton_Left)) editor.pointerUp();
    if (hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Right)) editor.removeAt(mouse);

    // Keyboard: only while no text field is being edited.
    if (!ImGui::GetIO().WantTextInput) {
        if ((pressed(GLFW_KEY_DELETE) || pressed(GLFW_KEY_BACKSPACE)) && editor.selected()) editor.removeSelected();
        if (ImGui::GetIO().KeyCtrl && pressed(GLFW_KEY_Z)) editor.undo();
        if (ImGui::GetIO().KeyCtrl && pressed(GLFW_KEY_Y)) editor.redo();
    }

    // Backdrop, histogram, grid.
    draw->AddRectFilled(origin, outerMax, IM_COL32(24, 24, 28, 255), 3.0f);
    if (!state.histogram.empty()) {
        const float barWidth = size.x / static_cast<float>(state.histogram.size());
        for (std::size_t i = 0; i < state.histogram.size(); ++i) {
            const float x0 = canvasMin.x + static_cast<float>(i) * barWidth;
            draw->AddRectFilled(ImVec2(x0, canvasMax.y - state.histogram[i] * size.y),
                                ImVec2(x0 + std::max(barWidth, 1.0f), canvasMax.y), IM_COL32(90, 90, 100, 160));
        }
    }
    for (int i = 1; i < 4; ++i) {
        const float t = static_cast<float>(i) / 4.0f;
        draw->AddLine(toScreen(t, 0.0f), toScreen(t, 1.0f), IM_COL32(255, 255, 255, 25));
        draw->AddLine(toScreen(0.0f, t), toScreen(1.0f, t), IM_COL32(255, 255, 255, 25));
    }
    draw->AddRect(canvasMin, canvasMax, IM_COL32(255, 255, 255, 60));

    // Colour bar: the function's colour with its opacity over a dark background.
    const sss::TransferFunction& tf = editor.transferFunction();
    const int segments = std::max(2, static_cast<int>(size.x / 3.0f));
    for (int i = 0; i < segments; ++i) {
        const float t0 = static_cast<float>(i) / static_cast<float>(segments);
        const float t1 = static_cast<float>(i + 1) / static_cast<float>(segments);
        const glm::vec4 c = tf.evaluate(0.5f * (t0 + t1));
        draw->AddRectFilled(ImVec2(canvasMin.x + t0 * size.x, canvasMax.y + 4.0f),
                            ImVec2(canvasMin.x + t1 * size.x + 1.0f, canvasMax.y + 14.0f),
                            toColor(glm::vec3(c), 0.35f + 0.65f * c.a));
    }

    // Opacity polyline (constant beyond the end points) and the points in their colours.
    const auto& points = tf.points();
    std::vector<ImVec2> line;
    line.push_back(toScreen(0.0f, points.front().opacity));
    for (const sss::ControlPoint& p : points) line.push_back(toScreen(p.value, p.opacity));
    line.push_back(toScreen(1.0f, points.back().opacity));
    draw->AddPolyline(line.data(), static_cast<int>(line.size()), IM_COL32(230, 230, 230, 220), 0, 1.5f);
    const auto hit = hovered ? editor.hitTest(mouse) : std::nullopt;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const ImVec2 c = toScreen(points[i].value, points[i].opacity);
        const bool isSelected = editor.selected() == i;
        draw->AddCircleFilled(c, isSelected ? 6.5f : 5.0f, toColor(points[i].color));
        draw->AddCircle(c, isSelected ? 7.5f : 5.5f,
                        isSelected ? IM_COL32(255, 220, 60, 255)
                                   : (hit == i ? IM_COL32(255, 255, 255, 255) : IM_COL32(0, 0, 0, 200)),
                        0, isSelected ? 2.0f : 1.0f);
    }
    if (hovered && !editor.dragging()) {
        const glm::vec2 m = glm::clamp(mouse, glm::vec2(0.0f), glm::vec2(1.0f));
        ImGui::SetTooltip("value %.3f (raw %d), opacity %.3f\n%s", m.x,
                          static_cast<int>(std::lround(state.rawRange.first +
                                                       m.x * (state.rawRange.second - state.rawRange.first))),
                          m.y,
                          hit ? "drag: move, right-click: delete" : "click: add a point");
    }

    // The selected point's controls.
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
    ImGui::Text("%zu points", points.size());
    if (!editor.lastError().empty()) {
        ImGui::SameLine();
        ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "%s", editor.lastError().c_str());
    }
    return editor.transferFunction().revision() != revisionBefore;
}

}  // namespace viewer
