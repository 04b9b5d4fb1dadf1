#pragma once
// Command line of sss-viewer, and loading what it names (shared with the UI's path fields).

#include "common/cli_options.h"

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
    examples::InputArgs input;             ///< --mesh --volume --scene --data-dir --dims --type --spacing --tf --tf-range
    std::string material = "marble";       ///< --material NAME
    bool noTexture = false;                ///< --no-texture
    sss::MeshRenderOptions mesh = defaultMeshOptions();        ///< --mesh-mode, --cameras, --frames, ...
    sss::VolumeRenderOptions volume = defaultVolumeOptions();  ///< --volume-mode, --light-volume-scale, ...
    sss::DisplayTransform display;         ///< --exposure, --tonemap
    sss::SceneCamera camera = defaultCamera();  ///< --yaw --pitch --zoom --fov --ortho
    bool cornellBox = false;               ///< --cornell-box
    float lightAzimuth = 35.0f, lightElevation = 40.0f;  ///< --light-angles AZ,EL (degrees)
    glm::vec3 lightColor{1.0f};            ///< --light-color
    float lightIntensity = 1.0f;           ///< --light-intensity
    int width = 1280, height = 720;        ///< --size WxH (window)
    std::string screenshot;                ///< --screenshot FILE.png
    bool screenshotUi = false;             ///< --screenshot-ui: the window with its UI instead of the scene only
    std::string saveScene;                 ///< --save-scene FILE.json: the scene at exit
    int exitAfter = 0;                     ///< --exit-after N: exit after N frames (0: run until closed)
    bool hideUi = false;                   ///< --no-ui
    std::string dumpState;                 ///< --dump-state FILE.json: state after every frame and at exit
    double timeout = 0.0;                  ///< --timeout S: fail if still open after S seconds (0: never)
    bool vsync = true;                     ///< --no-vsync
    int antiAliasing = 8;                  ///< --aa N: jittered frames averaged while nothing moves (1: off)
    bool yawGiven = false, pitchGiven = false;

    /// "preview light edits": the light volume's scale for the frame after an edit (measured in
    /// benchmarks/README.md, Table 5.4).
    static constexpr float kLightVolumePreviewScale = 0.25f;
    /// The viewer's defaults where they differ from the library's: scattering on, a scene 1-2
    /// units wide at 40 mm a unit, light edits previewed (--light-volume-preview 0 turns it off).
    static sss::MeshRenderOptions defaultMeshOptions() {
        sss::MeshRenderOptions o;
        o.shading = sss::MeshShading::Scattering;
        o.millimetresPerUnit = 40.0;
        return o;
    }
    static sss::VolumeRenderOptions defaultVolumeOptions() {
        sss::VolumeRenderOptions o;
        o.shading = sss::VolumeShading::Scattering;
        o.lightVolumePreviewScale = kLightVolumePreviewScale;
        return o;
    }
    static sss::SceneCamera defaultCamera() {
        sss::SceneCamera camera;
        camera.yaw = 25.0f;
        camera.pitch = 15.0f;
        return camera;
    }
};

/// Parses argv. Prints the usage and exits 0 for --help.
/// @throws UsageError naming the option and the problem.
ViewerOptions parseArgs(int argc, char** argv);

/// A transfer-function preset that suits a volume name ("bonsai_256x..." -> bonsai), or "ramp".
std::string guessPreset(const std::string& volumePath);

}  // namespace viewer
