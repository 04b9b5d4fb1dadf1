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

using examples::OptionCursor;
using examples::parseFloat;
using examples::parseInt;
using examples::parseLightVolumeFallback;
using examples::split;

constexpr const char* kUsage = R"(usage: sss-viewer [--mesh PATH] [--volume PATH] [options]

Interactive viewer for light scattering in meshes (subsurface scattering) and volumes (light
volume), alone or together in one hybrid scene. Needs a display (X11, or xvfb-run).
PATH may be a file or procedural:sphere | procedural:torus | procedural:slab (meshes),
procedural:blobs | procedural:shell | procedural:bucky (volumes). Relative paths not found as
given are looked up in the data directory (and its meshes/ and volumes/ folders): --data-dir,
else $SSS_DATA_DIR, else ../shared/data if it exists. Both can also be opened from the UI.

input:
  --mesh PATH               triangle mesh (.obj)
  --volume PATH             volume: .nrrd .nhdr .mhd .mha .nii .nii.gz .vti, a DICOM directory,
                            or raw data, dims/type parsed from names like bonsai_256x256x256_uint8.raw
  --dims XxYxZ              raw volume dimensions (overrides the name)
  --type T                  raw voxel type: uint8|uint16|int16|float32 (default uint8)
  --spacing X,Y,Z           raw voxel spacing (default 1,1,1)
  --tf-range LO,HI          value window in data units (e.g. -1000,2000 Hounsfield units) that
                            the transfer function spans; window/level in the TF panel change it
  --data-dir DIR            where to look for relative paths
scene:
  --cornell-box             put the scene in a Cornell box
  --mesh-mode sss|blinn-phong                 mesh shading (default: sss)
  --volume-mode scattering|scattering-gradient|gradient|emission-absorption
                            volume shading (default: scattering)
  --material NAME           translucent material (default: marble; see sss-render --list-materials)
  --profile NAME            subsurface profile, calibrated or dipole (default: calibrated)
  --scale MM                millimetres per scene unit (default: 40; the scene is 1-2 units wide)
  --cameras K               scattering maps, 1..32 (default: 8)
  --samples N               samples per texel and frame, 1..4096 (default: 24)
  --map-resolution R        scattering-map and light-buffer side in texels (default: 512)
  --accumulation F          map frames accumulated while the scene is static (default: 8)
  --light-volume-scale S    light-volume resolution relative to the data, (0,1] (default: 1)
  --exposure EV             display exposure in stops (default: 0)
  --tonemap none|filmic     display tone mapping (default: none)
  --light-volume-fallback reduce|fail
                            when the light volume does not fit the GPU: halve its resolution
                            until it fits, with a warning, or fail (default: reduce)
  --tf NAME|FILE.json       transfer-function preset or ParaView JSON (default: from the volume's name)
  --yaw DEG --pitch DEG     initial camera orbit angles (default: 25, 15; 14, 12 with --cornell-box)
  --light-angles AZ,EL      light azimuth and elevation in degrees (default: 35,40)
window:
  --size WxH                window size (default: 1280x720)
  --no-vsync                do not wait for the display's refresh
  --no-ui                   hide the UI (toggle with F1)
batch (scripts, tests):
  --aa N                    anti-aliasing: while nothing moves, average N frames with sub-pixel
                            camera offsets, one more per frame (default: 8; 1 = off)
  --frames N                render N frames, then exit
  --screenshot FILE.png     after the last frame save the scene image (without UI) and exit 0;
                            --frames defaults to 10
  --screenshot-ui           save the window with its UI instead
  --dump-state FILE         write the camera, UI layout and transfer function as JSON to FILE
                            after every frame and at exit (scripted input tests)
  --timeout S               exit 1 if the window is still open after S seconds
  --help                    this text

controls: left drag orbits, right or middle drag pans, the wheel zooms, F key reframes;
F12 saves a screenshot, F1 toggles the UI, Ctrl+Q quits; in the transfer-function editor click
to add a point, drag to move it, right-click or Delete removes it, Ctrl+Z / Ctrl+Y undo and redo.
)";

void requireRange(const std::string& option, int value, int lo, int hi) {
    if (value < lo || value > hi)
        throw UsageError(option + ": must be in " + std::to_string(lo) + ".." + std::to_string(hi) + ", got " +
                         std::to_string(value));
}

}  // namespace

ViewerOptions parseArgs(int argc, char** argv) {
    ViewerOptions o;
    bool framesGiven = false;
    for (OptionCursor args(argc, argv); args.next();) {
        const std::string& opt = args.option();
        auto value = [&args] { return args.value(); };
        if (args.isHelp()) {
            std::cout << kUsage;
            std::exit(0);
        } else if (opt == "--mesh") o.mesh = value();
        else if (opt == "--volume") o.volume = value();
        else if (opt == "--dims") {
            o.dims = examples::parseDims(opt, value());
        } else if (opt == "--type") {
            o.type = examples::parseVoxelType(opt, value());
        } else if (opt == "--tf-range") {
            o.tfRange = examples::parseRange(opt, value());
        } else if (opt == "--spacing") {
            o.spacing = examples::parseVec3(opt, value());
        } else if (opt == "--data-dir") o.dataDir = value();
        else if (opt == "--tf") o.tf = value();
        else if (opt == "--material") o.material = value();
        else if (opt == "--profile") {
            const std::string v = value();
            const auto profile = sss::parseScatteringProfile(v);
            if (!profile) throw UsageError("--profile: expected calibrated or dipole, got \"" + v + "\"");
            o.profile = *profile;
        }
        else if (opt == "--scale") {
            o.scale = parseFloat(opt, value());
            if (!(o.scale > 0.0) || !std::isfinite(o.scale)) throw UsageError("--scale: must be > 0");
        } else if (opt == "--mesh-mode") {
            const std::string v = value();
            if (v == "sss") o.meshScattering = true;
            else if (v == "blinn-phong") o.meshScattering = false;
            else throw UsageError("--mesh-mode: expected sss or blinn-phong, got \"" + v + "\"");
        } else if (opt == "--volume-mode") {
            o.volumeMode = value();
            if (o.volumeMode != "scattering" && o.volumeMode != "scattering-gradient" && o.volumeMode != "gradient" &&
                o.volumeMode != "emission-absorption")
                throw UsageError("--volume-mode: unknown mode \"" + o.volumeMode +
                                 "\" (scattering, scattering-gradient, gradient, emission-absorption)");
        } else if (opt == "--cameras") {
            o.cameras = parseInt(opt, value());
            requireRange(opt, o.cameras, 1, 32);
        } else if (opt == "--samples") {
            o.samples = parseInt(opt, value());
            requireRange(opt, o.samples, 1, 4096);
        } else if (opt == "--map-resolution") {
            o.mapResolution = parseInt(opt, value());
            requireRange(opt, o.mapResolution, 16, 8192);
        } else if (opt == "--accumulation") {
            o.accumulation = parseInt(opt, value());
            requireRange(opt, o.accumulation, 1, 1 << 20);
        } else if (opt == "--light-volume-scale") {
            o.lightVolumeScale = parseFloat(opt, value());
            if (!(o.lightVolumeScale > 0.0f && o.lightVolumeScale <= 1.0f))
                throw UsageError("--light-volume-scale: must be in (0, 1]");
        } else if (opt == "--exposure") {
            o.display.exposure = examples::parseExposure(opt, value());
        } else if (opt == "--tonemap") {
            o.display.toneMap = examples::parseToneMap(opt, value());
        } else if (opt == "--light-volume-fallback") {
            o.lightVolumeFallback = parseLightVolumeFallback(opt, value());
        } else if (opt == "--cornell-box") o.cornellBox = true;
        else if (opt == "--yaw") o.yaw = parseFloat(opt, value());
        else if (opt == "--pitch") o.pitch = parseFloat(opt, value());
        else if (opt == "--light-angles") {
            const std::string v = value();
            const auto parts = split(v, ',');
            if (parts.size() != 2) throw UsageError("--light-angles: expected AZ,EL, got \"" + v + "\"");
            o.lightAzimuth = parseFloat(opt, parts[0]);
            o.lightElevation = parseFloat(opt, parts[1]);
        } else if (opt == "--size") {
            const std::string v = value();
            const auto parts = split(v, 'x');
            if (parts.size() != 2) throw UsageError("--size: expected WxH, got \"" + v + "\"");
            o.width = parseInt(opt, parts[0]);
            o.height = parseInt(opt, parts[1]);
            if (o.width <= 0 || o.height <= 0 || o.width > 16384 || o.height > 16384)
                throw UsageError("--size: width and height must be in 1..16384, got \"" + v + "\"");
        } else if (opt == "--no-vsync") o.vsync = false;
        else if (opt == "--no-ui") o.hideUi = true;
        else if (opt == "--aa") {
            o.antiAliasing = parseInt(opt, value());
            if (o.antiAliasing < 1 || o.antiAliasing > 256) throw UsageError("--aa: must be in 1..256");
        } else if (opt == "--frames") {
            o.frames = parseInt(opt, value());
            if (o.frames < 1) throw UsageError("--frames: must be >= 1");
            framesGiven = true;
        } else if (opt == "--screenshot") {
            o.screenshot = value();
            if (o.screenshot.empty()) throw UsageError("--screenshot: empty file name");
        } else if (opt == "--screenshot-ui") o.screenshotUi = true;
        else if (opt == "--dump-state") {
            o.dumpState = value();
            if (o.dumpState.empty()) throw UsageError("--dump-state: empty file name");
        } else if (opt == "--timeout") {
            o.timeout = parseFloat(opt, value());
            if (!(o.timeout > 0.0) || !std::isfinite(o.timeout)) throw UsageError("--timeout: must be > 0 seconds");
        }
        else throw UsageError("unknown option \"" + opt + "\" (see --help)");
    }
    if (o.screenshotUi && o.screenshot.empty()) throw UsageError("--screenshot-ui needs --screenshot FILE.png");
    if (!o.screenshot.empty() && !framesGiven) o.frames = 10;
    if (!o.screenshot.empty()) o.vsync = false;  // batch runs need not wait for a display refresh
    if (!o.screenshot.empty() && o.mesh.empty() && o.volume.empty())
        throw UsageError("--screenshot: nothing to render: give --mesh PATH and/or --volume PATH");
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
