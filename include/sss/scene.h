#pragma once
/// @file
/// Scene descriptions: the meshes, volumes, lights, camera and output of a hybrid scene as data,
/// read from and written to JSON scene files (the format is documented in docs/scene-files.md),
/// and the assets they name loaded and placed in a HybridCompositor. sss-render, sss-viewer and
/// sss-bench all take `--scene FILE.json`; the viewer saves its current scene as one.

#include "sss/api.h"
#include "sss/bssrdf.h"
#include "sss/camera.h"
#include "sss/display.h"
#include "sss/hybrid_compositor.h"
#include "sss/isosurface.h"
#include "sss/light.h"
#include "sss/materials.h"
#include "sss/mesh.h"
#include "sss/mesh_scattering_renderer.h"
#include "sss/transfer_function.h"
#include "sss/volume.h"
#include "sss/volume_scattering_renderer.h"
#include "sss/volume_clip.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

SSS_BEGIN_API

namespace sss {

/// Scale, then rotation (degrees about x, then y, then z), then translation.
struct SceneTransform {
    glm::vec3 translate{0.0f};
    glm::vec3 rotate{0.0f};  ///< Euler angles in degrees, applied x first
    glm::vec3 scale{1.0f};   ///< each finite and non-zero
    glm::mat4 matrix() const;
    bool operator==(const SceneTransform&) const = default;
};

/// A mesh extracted from one of the scene's volumes (sss::extractIsosurface), in that volume's
/// box: with the volume's transform it lies inside the volume rendering, where it was scanned.
struct SceneIsosurface {
    int volume = 0;  ///< index into SceneDescription::volumes
    IsosurfaceOptions options;
    /// Millimetres per unit of the volume's spacing (default 1: CT spacing is in millimetres).
    /// The mesh's MeshRenderOptions::millimetresPerUnit becomes this times the volume's largest
    /// side, so the surface scatters light at its physical size.
    double millimetresPerVolumeUnit = 1.0;
};

/// A triangle mesh in a scene.
struct SceneMesh {
    std::string source;  ///< a mesh file (Mesh::load) or procedural:sphere|torus|slab|folds
    std::optional<SceneIsosurface> isosurface;  ///< instead of `source` (and `size`): a surface of a scene volume
    /// If set, the mesh is first scaled uniformly to this largest side (scene units) and centred
    /// on the origin, then `transform` places it.
    std::optional<float> size;
    SceneTransform transform;
    MeshRenderOptions options;         ///< options.shading picks Blinn-Phong or scattering
    ScatteringMaterial material = materialPreset("potato");  ///< for MeshShading::Scattering
    /// Whether the mesh's base-colour texture (Mesh::baseColour(), e.g. an OBJ's map_Kd), when
    /// it has one, gives the reflectance: `material` then lends its mean free path and eta only
    /// (texturedScattering()). Scene files: "texture": false turns it off (default: true).
    bool texture = true;
    BlinnPhongMaterial baseline;       ///< for MeshShading::BlinnPhong
};

/// A transfer function by preset name, ParaView JSON file or inline control points (the first
/// of `points`, `file` and `preset` that is set wins).
struct SceneTransferFunction {
    std::string preset = "ramp";
    std::string file;
    std::vector<ControlPoint> points;
};

/// A scalar volume in a scene; its box is one unit on its longest side, centred on the origin,
/// before `transform` places it.
struct SceneVolume {
    std::string source;  ///< a volume file or DICOM directory (Volume::load), raw data, or procedural:blobs|shell|bucky
    RawLoadOptions raw;  ///< for headerless raw data
    std::optional<std::pair<double, double>> valueWindow;  ///< Volume::setValueWindow
    SceneTransferFunction transferFunction;
    SceneTransform transform;
    VolumeRenderOptions options;
    /// false: the volume is not drawn, only read (by an isosurface mesh, say).
    bool visible = true;
    /// Clip planes (world space) and crop box (VolumeScatteringRenderer::setClip).
    VolumeClip clip;
};

/// The camera orbits the scene's centre and frames it tightly for the image's aspect
/// (Camera::frameTight on the meshes' vertices, the volumes' boxes, or the Cornell box), unless
/// `target` and `distance` place it explicitly (as the viewer saves it, panned and zoomed).
struct SceneCamera {
    float yaw = 30.0f;    ///< degrees
    float pitch = 20.0f;  ///< degrees
    float zoom = 1.0f;    ///< distance factor after framing, > 0 (< 1 moves closer)
    float fovY = 45.0f;   ///< vertical field of view, degrees, in (0, 180)
    Projection projection = Projection::Perspective;
    float margin = 0.04f;  ///< space left around the framed scene, a share of the half-size, [0, 0.5]
    std::optional<glm::vec3> target;  ///< with `distance`: the orbit centre, no framing
    std::optional<float> distance;    ///< with `target`: eye-to-target distance, > 0
    bool operator==(const SceneCamera&) const = default;
};

/// The image a scene renders to.
struct SceneOutput {
    int width = 1200, height = 680;  ///< pixels, 1..kMaxImageSide
    int antiAliasing = 4;            ///< frames averaged with sub-pixel camera offsets, 1..256 (1: off)
    DisplayTransform display;        ///< applied to PNG output (EXR holds linear radiance)
};

/// Everything a scene holds.
struct SceneDescription {
    std::vector<SceneMesh> meshes;
    std::vector<SceneVolume> volumes;
    std::vector<Light> lights;  ///< empty: defaultSceneLights()
    SceneCamera camera;
    HybridOptions options;
    SceneOutput output;
    /// Where relative asset paths are looked up first (the scene file's folder after
    /// loadSceneFile); not saved.
    std::filesystem::path baseDirectory;
};

/// Parses a scene from JSON text; `name` prefixes messages. Unknown fields are errors.
/// @throws Error InvalidArgument naming the JSON path of the bad field, e.g.
///         "scene.json: lights[2].direction: must be finite and non-zero, got (0, 0, 0)".
SceneDescription parseScene(std::string_view json, std::string_view name = "scene");
/// Reads a scene file; baseDirectory becomes the file's folder.
/// @throws Error NotFound / Io / InvalidArgument naming the file.
SceneDescription loadSceneFile(const std::filesystem::path& path);
/// The scene as JSON (fields at their defaults are left out; parseScene restores them exactly).
std::string sceneToJson(const SceneDescription& scene);
/// Writes sceneToJson() to `path`. @throws Error Io naming the file.
void saveSceneFile(const SceneDescription& scene, const std::filesystem::path& path);

/// Loads a mesh source: procedural:sphere|torus|slab|folds or a file, looked up as given, then in each
/// of `searchDirs` and its meshes/ folder.
Mesh loadMeshSource(std::string_view source, std::span<const std::filesystem::path> searchDirs = {});
/// Loads a volume source: procedural:blobs|shell|bucky, a headered file or DICOM directory
/// (Volume::load), else headerless raw data (Volume::loadRaw with `raw`); looked up like meshes,
/// in volumes/ folders.
Volume loadVolumeSource(std::string_view source, const RawLoadOptions& raw = {},
                        std::span<const std::filesystem::path> searchDirs = {});

/// The scene's assets in memory, ready to be placed (meshes already resized to SceneMesh::size).
struct SceneAssets {
    std::vector<Mesh> meshes;
    /// Per mesh: MeshRenderOptions::millimetresPerUnit of an isosurface (its volume's size),
    /// 0 for meshes from files, which take their options' own.
    std::vector<double> isosurfaceMillimetresPerUnit;
    std::vector<Volume> volumes;  ///< with their value windows set
    std::vector<TransferFunction> transferFunctions;  ///< one per volume
};

/// Loads and validates everything `scene` names, before any GL work; relative paths are looked
/// up in scene.baseDirectory, then in `searchDirs`. Errors name the scene field and the file.
SceneAssets loadSceneAssets(const SceneDescription& scene, std::span<const std::filesystem::path> searchDirs = {});

/// The lights a scene without lights gets: in a Cornell box a point light under its ceiling,
/// else a directional light travelling along (-1, -1, -1). `content`: HybridCompositor::bounds().
std::vector<Light> defaultSceneLights(const SceneDescription& scene, const Bounds& content);

/// Clears `compositor` and adds the scene to it: options, meshes, volumes and lights (or
/// defaultSceneLights()). Needs a current GL context.
void populateCompositor(HybridCompositor& compositor, const SceneDescription& scene, const SceneAssets& assets);

/// The scene's camera, framed for `aspect` (width / height) on what the scene holds: the meshes'
/// vertices and the volumes' boxes, or the Cornell box around `content` (HybridCompositor::bounds()).
Camera sceneCamera(const SceneDescription& scene, const SceneAssets& assets, const Bounds& content, float aspect);

}  // namespace sss

SSS_END_API
