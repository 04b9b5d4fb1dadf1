#pragma once
// The viewer's Dear ImGui windows: the settings panel (scene, light and camera, mesh, volume,
// timings), the transfer-function editor along the bottom, and the overlay with frame times and
// messages. They edit a ViewerModel and report where they were drawn (for --dump-state).
#include "tf_editor_widget.h"
#include "viewer_model.h"

#include <sss/stats.h>

#include <optional>

namespace viewer {

/// Where this frame's UI went.
struct UiLayout {
    std::optional<ScreenRect> panel, overlay, tfWindow, tfCanvas;
};

class Panels {
public:
    explicit Panels(ViewerModel& model) : m_model(model) {}

    /// The settings panel and, with a volume, the transfer-function window.
    void draw();
    // Frame time, progress and messages, top right.
    void drawOverlay();
    /// Where the UI went this frame (reset by beginFrame()).
    const UiLayout& layout() const { return m_layout; }
    void beginFrame() { m_layout = {}; }

private:
    // The editor gets a wide window along the bottom, right of the panel.
    void drawTransferFunctionWindow();
    void sceneSection();
    void lightSection();
    void meshSection();
    void volumeSection();
    void clipSection();
    void transferFunctionSection(float windowHeight);
    // Window/level of the value window (Volume::setValueWindow, in data units): the TF's domain is
    // level -+ window / 2. Applied when a drag ends, since the volume is uploaded again.
    void valueWindowRow();
    void timingSection();
    void statsTable(const char* owner, const sss::RenderStats& stats);
    // Where the window being built lies (window pixels).
    static ScreenRect currentWindowRect();

    ViewerModel& m_model;
    UiLayout m_layout;
};

}  // namespace viewer
