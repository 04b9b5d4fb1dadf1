#include "viewer_state.h"

#include <sss/error.h>

#include <nlohmann/json.hpp>

#include <fstream>
#include <system_error>

namespace viewer {
namespace {

// ordered_json: keys stay in the order written here, so the file reads top-down.
using json = nlohmann::ordered_json;

json rect(const std::optional<ScreenRect>& r) {
    if (!r) return nullptr;
    return json::array({r->x0, r->y0, r->x1, r->y1});
}

json vec3(glm::vec3 v) { return json::array({v.x, v.y, v.z}); }

json transferFunction(const sss::TransferFunctionEditor& editor) {
    json points = json::array();
    for (const sss::ControlPoint& p : editor.transferFunction().points())
        points.push_back({{"value", p.value}, {"opacity", p.opacity}, {"color", vec3(p.color)}});
    json selected = nullptr;
    if (editor.selected()) selected = *editor.selected();
    return {{"points", points}, {"selected", selected}, {"undo", editor.undoDepth()}, {"redo", editor.redoDepth()}};
}

}  // namespace

void writeViewerState(const std::filesystem::path& path, const ViewerState& state) {
    const json j = {
        {"frame", state.frame},
        {"running", state.running},
        {"window", json::array({state.window.x, state.window.y})},
        {"camera",
         {{"target", vec3(state.camera.target())},
          {"distance", state.camera.distance()},
          {"yaw", state.camera.yaw()},
          {"pitch", state.camera.pitch()},
          {"fovY", state.camera.fovY()}}},
        {"ui",
         {{"shown", state.uiShown},
          {"vertices", state.uiVertices},
          {"panel", rect(state.panel)},
          {"overlay", rect(state.overlay)},
          {"transferFunction", rect(state.tfWindow)},
          {"tfCanvas", rect(state.tfCanvas)}}},
        {"transferFunction", state.editor ? transferFunction(*state.editor) : json(nullptr)},
        {"screenshots", state.screenshots},
        {"glErrors", state.glErrors},
        {"lastGlError", state.lastGlError},
    };
    std::filesystem::path temporary = path;
    temporary += ".tmp";
    {
        std::ofstream out(temporary, std::ios::trunc);
        out << j.dump(2) << '\n';
        if (!out.flush())
            throw sss::Error(sss::ErrorKind::Io, "--dump-state: cannot write " + temporary.string());
    }
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error)
        throw sss::Error(sss::ErrorKind::Io, "--dump-state: cannot rename " + temporary.string() + " to " +
                                                 path.string() + ": " + error.message());
}

}  // namespace viewer
