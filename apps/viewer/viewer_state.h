#pragma once
// --dump-state: what the viewer shows, as JSON, for scripted input tests (tests/viewer): the
// camera, where the UI's windows and the transfer-function canvas are, and the function being
// edited. Written after every frame, so a test can also wait for frames to pass.

#include "tf_editor_widget.h"

#include <sss/camera.h>
#include <sss/transfer_function_editor.h>

#include <glm/vec2.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace viewer {

struct ViewerState {
    int frame = 0;                     ///< frames drawn so far
    bool running = true;               ///< false in the file written at exit
    glm::ivec2 window{0};              ///< framebuffer size in pixels
    sss::Camera camera;
    bool uiShown = false;              ///< F1 / --no-ui
    int uiVertices = 0;                ///< vertices ImGui drew in the last frame (0: no UI on screen)
    std::optional<ScreenRect> panel, overlay, tfWindow;  ///< the UI's windows, when drawn
    std::optional<ScreenRect> tfCanvas;  ///< value 0..1 left to right, opacity 0..1 bottom to top
    const sss::TransferFunctionEditor* editor = nullptr;  ///< the function and its history
    std::vector<std::string> screenshots;  ///< files written by F12 / Save, oldest first
    unsigned long long glErrors = 0;   ///< GL errors reported through KHR_debug (debug contexts)
    std::string lastGlError;           ///< the last of them
};

/// Writes `state` as JSON to `path` through a temporary file and a rename, so a reader never
/// sees a partial file. @throws sss::Error (Io) if the file cannot be written.
void writeViewerState(const std::filesystem::path& path, const ViewerState& state);

}  // namespace viewer
