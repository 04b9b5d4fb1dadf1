#include "viewer_options.h"

#include <sss/procedural.h>
#include <sss/transfer_function.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <vector>

namespace fs = std::filesystem;

namespace viewer {
namespace {

using examples::parseFloat;
using examples::parseInt;
using examples::split;

constexpr const char* kUsage = R"(usage: sss-viewer [--mesh PATH] [--volume PATH] [options]
       sss-viewer --scene FILE.json [options]

Interactive viewer for light scattering in meshes (subsurface scattering) and volumes (light
volume), alone or together in one hybrid scene. Needs a display (X11, or xvfb-run).
PATH may be a file or procedural:sphere | procedural:torus | procedural:slab (meshes),
procedural:blobs | procedural:shell | procedural:bucky (volumes). Relative paths not found as
given are looked up in the data directory (and its meshes/ and volumes/ folders): --data-dir,
else $SSS_DATA_DIR, else ../shared/data if it exists. Both can also be opened from the UI.
A scene file (docs/scene-files.md) opens with --scene if it holds at most one mesh, one volume
and one directional light; "Save scene" in the UI (or --save-scene) writes the scene shown, for
sss-render --scene. In a Cornell box the default view is yaw 14, pitch 12.

controls: left drag orbits, right or middle drag pans, the wheel zooms, F key reframes;
F12 saves a screenshot, F1 toggles the UI, Ctrl+Q quits; in the transfer-function editor click
to add a point, drag to move it, right-click or Delete removes it, Ctrl+Z / Ctrl+Y undo and redo.
)";

}  // namespace

ViewerOptions parseArgs(int argc, char** argv) {
    ViewerOptions o;
    CLI::App app(kUsage, "sss-viewer");
    examples::addInputOptions(app, o.input);
    app.add_flag("--cornell-box", o.cornellBox, "put the scene in a Cornell box")->group("placement");
    examples::addEnum(app, "--mesh-mode", o.mesh.shading, "mesh shading")->group("mesh scattering");
    examples::addMeshOptions(app, o.mesh, o.material, o.noTexture);
    examples::addInt(app, "--accumulation", o.mesh.accumulationFrames, "the old spelling of --frames", "F")
        ->group("mesh scattering");
    examples::addEnum(app, "--volume-mode", o.volume.shading, "volume shading")->group("volume");
    examples::addVolumeOptions(app, o.volume);
    examples::addCameraOptions(app, o.camera);
    examples::addParsed(app, "--light-angles", o.lightAzimuth,
                        [&o](const std::string& name, const std::string& text) {
                            const auto parts = split(text, ',');
                            if (parts.size() != 2) throw UsageError(name + ": expected AZ,EL, got \"" + text + "\"");
                            o.lightElevation = parseFloat(name, parts[1]);
                            return parseFloat(name, parts[0]);
                        },
                        "light azimuth and elevation in degrees", "AZ,EL",
                        examples::defaultText(o.lightAzimuth) + "," + examples::defaultText(o.lightElevation))
        ->group("light");
    examples::addVec3(app, "--light-color", o.lightColor, "light colour", "R,G,B")->group("light");
    examples::addFloat(app, "--light-intensity", o.lightIntensity, "light intensity", "I")->group("light");
    examples::addDisplayOptions(app, o.display);
    examples::addSizeOption(app, o.width, o.height, "window size");
    app.add_flag_callback("--no-vsync", [&o] { o.vsync = false; }, "do not wait for the display's refresh")
        ->group("window");
    app.add_flag("--no-ui", o.hideUi, "hide the UI (toggle with F1)")->group("window");
    examples::addAntiAliasingOption(app, o.antiAliasing,
                                    "anti-aliasing: while nothing moves, average N frames with sub-pixel camera "
                                    "offsets, one more per frame (1 = off)");
    examples::addParsed(app, "--exit-after", o.exitAfter,
                        [](const std::string& name, const std::string& text) {
                            const int n = parseInt(name, text);
                            if (n < 1) throw UsageError(name + ": must be >= 1");
                            return n;
                        },
                        "render N frames, then exit (scripts, tests)", "N")
        ->group("batch");
    app.add_option("--screenshot", o.screenshot,
                   "after the last frame save the scene image (without UI) and exit 0; --exit-after defaults to 10")
        ->type_name("FILE.png")
        ->group("batch");
    app.add_flag("--screenshot-ui", o.screenshotUi, "save the window with its UI instead")->group("batch");
    app.add_option("--save-scene", o.saveScene, "write the scene shown as a JSON scene file at exit")
        ->type_name("FILE.json")
        ->group("batch");
    app.add_option("--dump-state", o.dumpState,
                   "write the camera, UI layout and transfer function as JSON to FILE after every frame and at exit "
                   "(scripted input tests)")
        ->type_name("FILE")
        ->group("batch");
    examples::addParsed(app, "--timeout", o.timeout,
                        [](const std::string& name, const std::string& text) {
                            const double seconds = parseFloat(name, text);
                            if (!(seconds > 0.0)) throw UsageError(name + ": must be > 0 seconds");
                            return seconds;
                        },
                        "exit 1 if the window is still open after S seconds", "S")
        ->group("batch");
    examples::parseCommandLine(app, argc, argv);

    o.yawGiven = examples::given(app, "--yaw");
    o.pitchGiven = examples::given(app, "--pitch");
    for (const char* name : {"--screenshot", "--dump-state", "--save-scene"})
        if (examples::given(app, name) && app.get_option(name)->as<std::string>().empty())
            throw UsageError(std::string(name) + ": empty file name");
    if (!o.input.scene.empty())
        examples::rejectWithScene(app, {"--mesh", "--volume", "--dims", "--type", "--spacing", "--tf", "--tf-range",
                                        "--cornell-box"});
    if (o.screenshotUi && o.screenshot.empty()) throw UsageError("--screenshot-ui needs --screenshot FILE.png");
    if (!o.screenshot.empty() && !examples::given(app, "--exit-after")) o.exitAfter = 10;
    if (!o.screenshot.empty()) o.vsync = false;  // batch runs need not wait for a display refresh
    if (!o.screenshot.empty() && o.input.mesh.empty() && o.input.volume.empty() && o.input.scene.empty())
        throw UsageError("--screenshot: nothing to render: give --mesh PATH and/or --volume PATH, or --scene");
    return o;
}

std::string guessPreset(const std::string& volumePath) {
    const std::string name = fs::path(volumePath).filename().string();
    for (const std::string& preset : sss::TransferFunction::presetNames())
        if (preset != "ramp" && name.find(preset) != std::string::npos) return preset;
    if (name.find("cthead") != std::string::npos) return "ct-skin";
    if (name.find("blobs") != std::string::npos || name.find("shell") != std::string::npos) return "bucky";
    return "ramp";
}

}  // namespace viewer
