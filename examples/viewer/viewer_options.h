#pragma once
// Command line of sss-viewer, and loading what it names (shared with the UI's path fields).

#include "common/scene_inputs.h"

#include <sss/display.h>
#include <sss/mesh.h>
#include <sss/mesh_scattering_renderer.h>
#include <sss/volume.h>

#include <glm/vec3.hpp>

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>

namespace viewer {

using examples::UsageError;  // bad command-line usage: stderr, exit code 2
using examples::dataDirectory;  // --data-dir, else $SSS_DATA_DIR, else ../shared/data
using examples::loadSceneMesh;  // a path or procedural:NAME (scene_inputs.h)
using examples::loadSceneVolume;

struct ViewerOptions {
    std::string mesh;                      ///< --mesh PATH or procedural:NAME
    std::string volume;                    ///< --volume PATH or procedural:NAME
    std::optional<glm::ivec3> dims;        ///< --dims XxYxZ
    std::optional<sss::VoxelType> type;    ///< --type uint8|uint16|int16|float32
    std::optional<std::pair<double, double>> tfRange;  ///< --tf-range LO,HI (Volume::setValueWindow)
    std::optional<glm::vec3> spacing;      ///< --spacing X,Y,Z
    std::string dataDir;                   ///< --data-dir DIR
    std::string tf;                        ///< --tf NAME|FILE.json (default: guessed from the volume's name)
    std::string material = "marble";       ///< --material NAME
    sss::ScatteringProfile profile = sss::MeshRenderOptions{}.profile;  ///< --profile calibrated|dipole
    double scale = 40.0;                   ///< --scale MM: millimetres per scene unit (the scene is ~1-2 units)
    bool meshScattering = true;            ///< --mesh-mode sss|blinn-phong
    std::string volumeMode = "scattering"; ///< --volume-mode
    int cameras = 8, samples = 24, mapResolution = 512, accumulation = 8;
    float lightVolumeScale = 1.0f;         ///< --light-volume-scale
    sss::LightVolumeFallback lightVolumeFallback = sss::LightVolumeFallback::Reduce;  ///< --light-volume-fallback
    sss::DisplayTransform display;         ///< --exposure, --tonemap
    bool cornellBox = false;               ///< --cornell-box
    std::optional<float> yaw, pitch;       ///< --yaw/--pitch (degrees; default 25, 15; 14, 12 in a Cornell box)
    float lightAzimuth = 35.0f, lightElevation = 40.0f;  ///< --light-angles AZ,EL (degrees)
    int width = 1280, height = 720;        ///< --size WxH (window)
    std::string screenshot;                ///< --screenshot FILE.png
    bool screenshotUi = false;             ///< --screenshot-ui: the window with its UI instead of the scene only
    int frames = 0;                        ///< --frames N: exit after N frames (0: run until closed)
    bool hideUi = false;                   ///< --no-ui
    std::string dumpState;                 ///< --dump-state FILE.json: state after every frame and at exit
    double timeout = 0.0;                  ///< --timeout S: fail if still open after S seconds (0: never)
    bool vsync = true;                     ///< --no-vsync
    int antiAliasing = 8;                  ///< --aa N: jittered frames averaged while nothing moves (1: off)
};

/// Parses argv. Prints the usage and exits 0 for --help.
/// @throws UsageError naming the option and the problem.
ViewerOptions parseArgs(int argc, char** argv);

/// A transfer-function preset that suits a volume name ("bonsai_256x..." -> bonsai), or "ramp".
std::string guessPreset(const std::string& volumePath);

}  // namespace viewer
