// sss-render: renders a mesh and/or a volume headless to a PNG and prints the timing.
// Run `sss-render --help` for the options. Exit codes: 0 ok, 1 runtime failure, 2 bad usage.
#include "common/scene_inputs.h"

#include <sss/sss.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

using namespace examples;

constexpr const char* kUsage = R"(usage: sss-render [--mesh PATH] [--volume PATH] [options] --out FILE.png

Renders a triangle mesh (.obj .ply .stl .gltf .glb .off) and/or a scalar volume (.raw .nrrd .nhdr
.mhd .mha .nii .nii.gz .vti, or a directory holding a DICOM series) headless
with OpenGL 4.5 (EGL).
PATH may also be a procedural asset: procedural:sphere | procedural:torus | procedural:slab
(meshes), procedural:blobs | procedural:shell | procedural:bucky (volumes).
Relative paths not found as given are looked up in the data directory (and its meshes/ and
volumes/ folders): --data-dir, else $SSS_DATA_DIR, else ../shared/data if it exists.

input:
  --mesh PATH               triangle mesh: OBJ, PLY, STL, glTF 2.0 (.gltf/.glb) or OFF
  --volume PATH             volume: NRRD, MetaImage, NIfTI, VTK .vti or a DICOM directory (dims,
                            type, spacing and orientation from the header), or headerless raw
                            data with dims/type parsed from names like bonsai_256x256x256_uint8.raw
  --dims XxYxZ              raw volume dimensions (overrides the name)
  --type T                  raw voxel type: uint8|uint16|int16|float32 (overrides the name;
                            default uint8)
  --spacing X,Y,Z           raw voxel spacing (default 1,1,1)
  --data-dir DIR            where to look for relative paths
output:
  --out FILE.png|FILE.exr   output image (default: sss-render.png): a PNG is the display image
                            (exposure, tone mapping, sRGB); an OpenEXR file holds the linear
                            radiance in 32-bit float, untransformed
  --exposure EV             exposure in stops for the display image (default: 0)
  --tonemap none|filmic     tone mapping for the display image (default: none: values above 1 clip)
  --size WxH                image size (default: 1200x680, the thesis viewport)
  --background R,G,B        linear background colour (default: 0.01,0.01,0.0137, which
                            displays as the dark grey-blue sRGB 0.1,0.1,0.12)
  --repeat N                render N times and report median/min/max (default: 1)
  --aa N                    anti-aliasing: average N frames with sub-pixel camera offsets, after
                            the timed frames (default: 4; 1 = off)
shading:
  --mode MODE               blinn-phong or sss (mesh); emission-absorption, gradient,
                            scattering or scattering-gradient (volume); hybrid (a mesh and a
                            volume: sss + scattering, sharing light and shadows);
                            default: blinn-phong for a mesh, emission-absorption for a volume.
                            With both a mesh and a volume, MODE is the volume's; the mesh is
                            drawn in blinn-phong and cuts the volume's rays.
  --material NAME           translucent material for --mode sss (default: potato); see --list-materials
  --list-materials          print the material presets and exit
  --combine WHERE           per-pixel (the K maps looked up at every pixel) or per-vertex (resolved
                            once per vertex after each map update: fixed frames cost about a
                            Blinn-Phong frame) (default: per-pixel)
  --profile NAME            subsurface profile: calibrated (the directional dipole rescaled to a
                            random walk, plus single scattering) or dipole (the paper's, as the
                            thesis) (default: calibrated)
  --cameras K               scattering maps, 1..32 (default: 8)
  --samples N               samples per pixel and frame, 1..4096 (default: 24); with
                            --multiple-scattering, the volume's paths per pixel and frame
  --map-resolution R        scattering-map and light-buffer side in texels (default: 512)
  --frames F                frames accumulated into the scattering maps, and with
                            --multiple-scattering into the volume's running mean (default: 8)
  --scale MM                millimetres per scene unit (default: 1000, i.e. metres)
  --no-specular             no specular highlight on the translucent surface
  --environment R,G,B       radiance of a uniform environment lighting the translucent mesh, so
                            faces the light misses are not black (default: 0,0,0; 0.05 in
                            a Cornell box)
  --color R,G,B             mesh diffuse colour (default: 0.8,0.75,0.7)
  --shininess S             mesh Blinn-Phong exponent (default: 40)
  --tf NAME|FILE.json       transfer-function preset (default: ramp; see --list-tf) or a
                            ParaView JSON colour map (RGBPoints/Points)
  --tf-range LO,HI          value window: the data values (e.g. Hounsfield units) that the
                            transfer function's domain spans; values outside clamp to its ends
                            (default: 0..255 for uint8, else the data's min..max). A JSON's x
                            axis is mapped with it too (default there: the file's own x range)
  --list-tf                 print the transfer-function presets and exit
  --step VOXELS             ray step in voxels (default: 1)
  --early-termination A     stop rays at this opacity, (0,1] (default: 0.99)
  --no-jitter               no per-pixel ray offset
  --no-skipping             no empty-space skipping (same image, slower)
  --no-gradient-volume      gradient modes compute gradients per sample instead of reading a
                            gradient volume computed once (8 bytes per voxel)
  --light-volume-scale S    light-volume resolution relative to the data, (0,1] (default: 1)
  --light-volume-fallback reduce|fail
                            when the light volume does not fit the GPU: halve its resolution
                            until it fits, with a warning, or fail (default: reduce)
  --anisotropy G            Henyey-Greenstein g for the scattering cone, (-1,1) (default: 0.5)
  --volume-model M          paper (Ropinski: ambient + diffuse x light-volume colour) or physical
                            (single scattering: TF colour as albedo x phase function x light;
                            about 4 pi dimmer, raise --light-intensity or --exposure) (default: paper)
  --eye-pass                add the second, view-dependent pass towards the viewer
  --multiple-scattering     volume modes scattering and hybrid: progressive GPU path tracing of
                            all orders of scattering (the physical model: implies --volume-model
                            physical; paper is an error). --frames F x --samples N paths per
                            pixel before the timed frames (each --repeat adds N more); through
                            pixel centres, so --aa is not applied
  --max-bounces B           with --multiple-scattering: scatterings per path, >= 1 (1 = single
                            scattering; default: 100000, Russian roulette ends paths earlier)
camera and light:
  --yaw DEG --pitch DEG     orbit angles around the scene centre (default: 30, 20)
  --zoom F                  distance factor after framing the scene (default: 1; < 1 moves
                            closer; scales the orthographic view too). The scene (the mesh's
                            vertices, the volume's box, or the Cornell box) is framed tightly
                            for the view direction and the image's aspect: it fills the image
                            up to a 4 % margin on one axis and is centred on the other
  --fov DEG                 vertical field of view (default: 45)
  --ortho                   orthographic projection
  --light-dir X,Y,Z         direction the light travels (default: -1,-1,-1)
  --light-color R,G,B       light colour (default: 1,1,1)
  --light-intensity I       light intensity (default: 1)
  --point-light X,Y,Z       use a point light at this position instead
  --mesh-size S             scale the mesh uniformly to a largest side of S scene units,
                            centred on the origin, as sss-viewer does with S = 1 (default: the
                            file's own units); --scale then says how many mm a unit is
  --mesh-offset X,Y,Z       move the mesh (scene units; default: 0,0,0)
  --volume-offset X,Y,Z     move the volume (its box is 1 unit on its longest side)
  --cornell-box             put the scene in a Cornell box (default light: a point light
                            under its ceiling; default view: straight in, yaw 0 and pitch 0)
  --help                    this text
)";

// Space left around the framed scene box: a fraction of the image's half-width/half-height.
constexpr float kFramingMargin = 0.04f;

struct Args {
    std::string mesh, volume, out = "sss-render.png", mode, tf = "ramp", dataDir, material = "potato";
    int cameras = 8, samples = 24, mapResolution = 512, frames = 8;
    double scale = 1000.0;
    bool specular = true, listMaterials = false;
    sss::ScatteringProfile profile = sss::MeshRenderOptions{}.profile;
    sss::MeshCombine combine = sss::MeshRenderOptions{}.combine;
    std::optional<glm::ivec3> dims;
    std::optional<sss::VoxelType> type;
    std::optional<glm::vec3> spacing;
    int width = 1200, height = 680, repeat = 1, antiAliasing = 4;
    glm::vec3 background{0.010f, 0.010f, 0.0137f};  // linear; displays as sRGB (0.1, 0.1, 0.12)
    glm::vec3 color{0.8f, 0.75f, 0.7f};
    float shininess = 40.0f, step = 1.0f, earlyTermination = 0.99f, lightVolumeScale = 1.0f, anisotropy = 0.5f;
    sss::VolumeModel volumeModel = sss::VolumeRenderOptions{}.model;
    bool eyePass = false, multipleScattering = false, volumeModelGiven = false;
    int maxBounces = sss::VolumeRenderOptions{}.maxBounces;
    sss::DisplayTransform display;
    sss::LightVolumeFallback lightVolumeFallback = sss::LightVolumeFallback::Reduce;
    bool gradientVolume = true;
    bool jitter = true, skipping = true, ortho = false, listTf = false, cornellBox = false, lightGiven = false;
    float yaw = 30.0f, pitch = 20.0f, zoom = 1.0f, fov = 45.0f;
    glm::vec3 lightDir{-1.0f, -1.0f, -1.0f}, lightColor{1.0f};
    float lightIntensity = 1.0f;
    std::optional<glm::vec3> pointLight, environment;
    std::optional<float> meshSize, yawGiven, pitchGiven;
    std::optional<std::pair<double, double>> tfRange;
    glm::vec3 meshOffset{0.0f}, volumeOffset{0.0f};
};

std::optional<sss::VolumeShading> volumeShading(const std::string& mode) {
    if (mode == "emission-absorption") return sss::VolumeShading::EmissionAbsorption;
    if (mode == "gradient") return sss::VolumeShading::Gradient;
    if (mode == "scattering") return sss::VolumeShading::Scattering;
    if (mode == "scattering-gradient") return sss::VolumeShading::ScatteringGradient;
    return std::nullopt;
}

Args parseArgs(int argc, char** argv) {
    Args a;
    for (OptionCursor args(argc, argv); args.next();) {
        const std::string& opt = args.option();
        auto value = [&args] { return args.value(); };
        if (args.isHelp()) {
            std::cout << kUsage;
            std::exit(0);
        } else if (opt == "--mesh") a.mesh = value();
        else if (opt == "--volume") a.volume = value();
        else if (opt == "--out") a.out = value();
        else if (opt == "--exposure") a.display.exposure = parseExposure(opt, value());
        else if (opt == "--tonemap") a.display.toneMap = parseToneMap(opt, value());
        else if (opt == "--mode") a.mode = value();
        else if (opt == "--tf") a.tf = value();
        else if (opt == "--list-tf") a.listTf = true;
        else if (opt == "--tf-range") {
            a.tfRange = parseRange(opt, value());
        }
        else if (opt == "--material") a.material = value();
        else if (opt == "--list-materials") a.listMaterials = true;
        else if (opt == "--combine") {
            const std::string v = value();
            if (v == "per-pixel") a.combine = sss::MeshCombine::PerPixel;
            else if (v == "per-vertex") a.combine = sss::MeshCombine::PerVertex;
            else throw UsageError("--combine: expected per-pixel or per-vertex, got \"" + v + "\"");
        } else if (opt == "--profile") {
            const std::string v = value();
            const auto profile = sss::parseScatteringProfile(v);
            if (!profile) throw UsageError("--profile: expected calibrated or dipole, got \"" + v + "\"");
            a.profile = *profile;
        }
        else if (opt == "--cameras") a.cameras = parseInt(opt, value());
        else if (opt == "--samples") a.samples = parseInt(opt, value());
        else if (opt == "--map-resolution") a.mapResolution = parseInt(opt, value());
        else if (opt == "--frames") a.frames = parseInt(opt, value());
        else if (opt == "--scale") a.scale = parseFloat(opt, value());
        else if (opt == "--no-specular") a.specular = false;
        else if (opt == "--environment") a.environment = parseVec3(opt, value());
        else if (opt == "--data-dir") a.dataDir = value();
        else if (opt == "--dims") a.dims = parseDims(opt, value());
        else if (opt == "--type") a.type = parseVoxelType(opt, value());
        else if (opt == "--spacing") a.spacing = parseVec3(opt, value());
        else if (opt == "--size") {
            const std::string v = value();
            const auto parts = split(v, 'x');
            if (parts.size() != 2) throw UsageError("--size: expected WxH, got \"" + v + "\"");
            a.width = parseInt(opt, parts[0]);
            a.height = parseInt(opt, parts[1]);
            if (a.width <= 0 || a.height <= 0 || a.width > 16384 || a.height > 16384)
                throw UsageError("--size: width and height must be in 1..16384, got \"" + v + "\"");
        } else if (opt == "--background") a.background = parseVec3(opt, value());
        else if (opt == "--repeat") {
            a.repeat = parseInt(opt, value());
            if (a.repeat < 1) throw UsageError("--repeat: must be >= 1");
        } else if (opt == "--aa") {
            a.antiAliasing = parseInt(opt, value());
            if (a.antiAliasing < 1 || a.antiAliasing > 256) throw UsageError("--aa: must be in 1..256");
        } else if (opt == "--color") a.color = parseVec3(opt, value());
        else if (opt == "--shininess") a.shininess = parseFloat(opt, value());
        else if (opt == "--step") a.step = parseFloat(opt, value());
        else if (opt == "--early-termination") a.earlyTermination = parseFloat(opt, value());
        else if (opt == "--no-jitter") a.jitter = false;
        else if (opt == "--no-skipping") a.skipping = false;
        else if (opt == "--no-gradient-volume") a.gradientVolume = false;
        else if (opt == "--eye-pass") a.eyePass = true;
        else if (opt == "--light-volume-scale") a.lightVolumeScale = parseFloat(opt, value());
        else if (opt == "--light-volume-fallback") a.lightVolumeFallback = parseLightVolumeFallback(opt, value());
        else if (opt == "--anisotropy") a.anisotropy = parseFloat(opt, value());
        else if (opt == "--volume-model") {
            const std::string v = value();
            const auto model = sss::parseVolumeModel(v);
            if (!model) throw UsageError("--volume-model: expected paper or physical, got \"" + v + "\"");
            a.volumeModel = *model;
            a.volumeModelGiven = true;
        } else if (opt == "--multiple-scattering") a.multipleScattering = true;
        else if (opt == "--max-bounces") a.maxBounces = parseInt(opt, value());
        else if (opt == "--yaw") a.yaw = *(a.yawGiven = parseFloat(opt, value()));
        else if (opt == "--pitch") a.pitch = *(a.pitchGiven = parseFloat(opt, value()));
        else if (opt == "--zoom") {
            a.zoom = parseFloat(opt, value());
            if (!(a.zoom > 0.0f)) throw UsageError("--zoom: must be > 0");
        } else if (opt == "--fov") a.fov = parseFloat(opt, value());
        else if (opt == "--ortho") a.ortho = true;
        else if (opt == "--cornell-box") a.cornellBox = true;
        else if (opt == "--mesh-size") {
            a.meshSize = parseFloat(opt, value());
            if (!(*a.meshSize > 0.0f && *a.meshSize <= 1e6f)) throw UsageError("--mesh-size: must be in (0, 1e6] scene units");
        } else if (opt == "--mesh-offset") a.meshOffset = parseVec3(opt, value());
        else if (opt == "--volume-offset") a.volumeOffset = parseVec3(opt, value());
        else if (opt == "--light-dir") a.lightDir = parseVec3(opt, value()), a.lightGiven = true;
        else if (opt == "--light-color") a.lightColor = parseVec3(opt, value());
        else if (opt == "--light-intensity") a.lightIntensity = parseFloat(opt, value());
        else if (opt == "--point-light") a.pointLight = parseVec3(opt, value()), a.lightGiven = true;
        else throw UsageError("unknown option \"" + opt + "\" (see --help)");
    }
    if (a.listTf || a.listMaterials) return a;
    const std::string ext = fs::path(a.out).extension().string();
    if (ext != ".png" && ext != ".exr") throw UsageError("--out: the file must end in .png or .exr, got \"" + a.out + "\"");
    for (const auto& [name, offset] : {std::pair{"--mesh-offset", a.meshOffset}, std::pair{"--volume-offset", a.volumeOffset}})
        if (!(glm::all(glm::lessThanEqual(glm::abs(offset), glm::vec3(sss::Mesh::kMaxCoordinate)))))
            throw UsageError(std::string(name) + ": components must be within +-1e18 (scene units)");
    if (a.mesh.empty() && a.volume.empty()) throw UsageError("nothing to render: give --mesh PATH and/or --volume PATH");
    if (a.mode.empty()) a.mode = a.volume.empty() ? "blinn-phong" : "emission-absorption";
    if (a.multipleScattering) {
        if (a.mode != "scattering" && a.mode != "hybrid")
            throw UsageError("--multiple-scattering needs --mode scattering or hybrid (with a volume), got --mode " + a.mode);
        if (a.volumeModelGiven && a.volumeModel != sss::VolumeModel::Physical)
            throw UsageError("--multiple-scattering path-traces the physical model: it cannot be combined with "
                             "--volume-model paper");
        a.volumeModel = sss::VolumeModel::Physical;
    }
    if (a.mode == "hybrid") {
        if (a.mesh.empty() || a.volume.empty()) throw UsageError("--mode hybrid needs --mesh and --volume");
        return a;
    }
    const bool meshMode = a.mode == "blinn-phong" || a.mode == "sss";
    const bool volumeMode = volumeShading(a.mode).has_value();
    if (!meshMode && !volumeMode)
        throw UsageError("--mode: unknown mode \"" + a.mode +
                         "\" (blinn-phong, sss, emission-absorption, gradient, scattering, scattering-gradient, hybrid)");
    if (meshMode && a.mesh.empty()) throw UsageError("--mode " + a.mode + " needs --mesh");
    if (volumeMode && a.volume.empty()) throw UsageError("--mode " + a.mode + " needs --volume");
    if (meshMode && !a.volume.empty())
        throw UsageError("--mode " + a.mode + " is a mesh mode; with --volume give the volume's mode");
    return a;
}

sss::RawLoadOptions rawOptions(const Args& a) {
    sss::RawLoadOptions options;
    options.dims = a.dims;
    options.type = a.type;
    options.spacing = a.spacing;
    return options;
}

// True if every pixel is the clear colour: nothing was drawn, or nothing visible.
bool showsOnlyBackground(const sss::Image& image, glm::vec3 background) {
    const std::vector<float>& data = image.data();
    for (std::size_t i = 0; i < data.size(); i += 4)
        if (std::abs(data[i] - background.r) > 1e-4f || std::abs(data[i + 1] - background.g) > 1e-4f ||
            std::abs(data[i + 2] - background.b) > 1e-4f)
            return false;
    return true;
}

int run(const Args& a) {
    if (a.listTf || a.listMaterials) {
        for (const std::string& name : a.listTf ? sss::TransferFunction::presetNames() : sss::materialPresetNames())
            std::cout << name << "\n";
        return 0;
    }
    const fs::path dataDir = dataDirectory(a.dataDir);
    // Load and validate everything before touching GL, so bad input fails fast and clearly.
    std::optional<sss::Mesh> mesh;
    std::optional<sss::Volume> volume;
    std::optional<sss::TransferFunction> tf;
    // (GL objects below are created only after every input is valid.)
    if (!a.mesh.empty()) mesh = loadSceneMesh(a.mesh, dataDir);
    if (mesh && a.meshSize) {
        const sss::Bounds b = mesh->bounds();
        const glm::vec3 size = b.size();
        const float largest = std::max({size.x, size.y, size.z, 1e-30f});
        mesh = mesh->transformed(glm::scale(glm::mat4(1.0f), glm::vec3(*a.meshSize / largest)) *
                                 glm::translate(glm::mat4(1.0f), -b.center()));
    }
    const bool scattering = (a.mode == "sss" || a.mode == "hybrid") && !a.mesh.empty();
    const sss::ScatteringMaterial material = sss::materialPreset(a.material);
    if (!a.volume.empty()) {
        volume = loadSceneVolume(a.volume, dataDir, rawOptions(a));
        volume->setValueWindow(a.tfRange);
        const bool file = a.tf.size() > 5 && a.tf.substr(a.tf.size() - 5) == ".json";
        tf = file ? sss::TransferFunction::loadParaViewJson(a.tf, a.tfRange) : sss::TransferFunction::preset(a.tf);
    }
    // Options are checked before touching GL as well: a context costs memory and a second.
    sss::MeshRenderOptions meshOptions;
    meshOptions.shading = scattering ? sss::MeshShading::Scattering : sss::MeshShading::BlinnPhong;
    meshOptions.cameras = a.cameras;
    meshOptions.profile = a.profile;
    meshOptions.combine = a.combine;
    meshOptions.samples = a.samples;
    meshOptions.mapResolution = meshOptions.lightMapResolution = a.mapResolution;
    meshOptions.accumulationFrames = a.frames;
    meshOptions.millimetresPerUnit = a.scale;
    meshOptions.specular = a.specular ? 1.0f : 0.0f;
    meshOptions.environment = a.environment.value_or(glm::vec3(a.cornellBox ? 0.05f : 0.0f));
    const sss::BlinnPhongMaterial meshMaterial{.diffuse = a.color, .shininess = a.shininess};
    const sss::VolumeRenderOptions volumeOptions{
        .shading = a.mode == "hybrid" ? sss::VolumeShading::Scattering
                                      : volumeShading(a.mode).value_or(sss::VolumeShading::EmissionAbsorption),
        .stepSize = a.step,
        .earlyTermination = a.earlyTermination,
        .jitter = a.jitter,
        .emptySpaceSkipping = a.skipping,
        .gradientVolume = a.gradientVolume,
        .lightVolumeScale = a.lightVolumeScale,
        .lightVolumeFallback = a.lightVolumeFallback,
        .anisotropy = a.anisotropy,
        .model = a.volumeModel,
        .eyePass = a.eyePass,
        .multipleScattering = a.multipleScattering,
        .samplesPerFrame = a.samples,
        .maxBounces = a.maxBounces};
    const sss::HybridOptions sceneOptions{.background = glm::vec4(a.background, 1.0f), .cornellBox = a.cornellBox};
    if (mesh) sss::validate(meshOptions), sss::validate(meshMaterial);
    if (volume) sss::validate(volumeOptions);
    sss::validate(sceneOptions);
    if (!(a.fov > 0.0f && a.fov < 180.0f)) throw UsageError("--fov: must be in (0, 180) degrees");

    auto context = sss::EglContext::create();
    sss::RenderTarget target(a.width, a.height);
    sss::HybridCompositor scene(sceneOptions);
    sss::MeshScatteringRenderer* meshRenderer = nullptr;
    if (mesh) {
        meshRenderer = &scene.addMesh(*mesh, glm::translate(glm::mat4(1.0f), a.meshOffset), meshOptions);
        meshRenderer->setScatteringMaterial(material);
        meshRenderer->setMaterial(meshMaterial);
    }
    sss::VolumeScatteringRenderer* volumeRenderer = nullptr;
    if (volume) {
        try {
            volumeRenderer = &scene.addVolume(*volume, glm::translate(glm::mat4(1.0f), a.volumeOffset), volumeOptions);
            volumeRenderer->setTransferFunction(*tf);
        } catch (const sss::Error& e) {
            // The library names the GPU object; the user knows the file.
            throw sss::Error(e.kind(), a.volume + ": " + e.what());
        }
    }
    const sss::Bounds sceneBounds = a.cornellBox ? sss::makeCornellBox(scene.bounds()).bounds : scene.bounds();
    // What the camera frames: the Cornell box, else the mesh's vertices and the volume's box
    // (the compositor's bounds() holds each mesh's bounding sphere, which is loose).
    std::vector<glm::vec3> framed;
    auto addBox = [&](const sss::Bounds& b, glm::vec3 offset) {
        for (int i = 0; i < 8; ++i)
            framed.push_back(offset + glm::vec3((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y,
                                                (i & 4) ? b.max.z : b.min.z));
    };
    if (a.cornellBox) addBox(sceneBounds, glm::vec3(0.0f));
    else {
        if (mesh)
            for (const glm::vec3& p : mesh->positions()) framed.push_back(p + a.meshOffset);
        if (volume) addBox(volume->worldBounds(), a.volumeOffset);
    }
    // In a Cornell box the default light hangs under the ceiling, as in the classic scene.
    sss::Light light = a.pointLight ? sss::Light(sss::PointLight{*a.pointLight, a.lightColor, a.lightIntensity})
                                    : sss::Light(sss::DirectionalLight{a.lightDir, a.lightColor, a.lightIntensity});
    if (a.cornellBox && !a.lightGiven)
        light = sss::PointLight{sceneBounds.center() + glm::vec3(0.0f, 0.4f * sceneBounds.size().y, 0.0f), a.lightColor,
                                a.lightIntensity * 0.5f * sceneBounds.size().y * sceneBounds.size().y};
    sss::validateLight(light, "--light");
    scene.setLights({light});

    // The view direction first, then the scene framed tightly for it and the image's
    // aspect (the subject fills the image); --zoom scales the distance from there.
    sss::Camera camera;
    camera.setFovY(a.fov);
    // A Cornell box is seen straight through its open side unless --yaw or --pitch say otherwise.
    camera.setYaw(a.cornellBox ? a.yawGiven.value_or(0.0f) : a.yaw);
    camera.setPitch(a.cornellBox ? a.pitchGiven.value_or(0.0f) : a.pitch);
    camera.setProjectionType(a.ortho ? sss::Projection::Orthographic : sss::Projection::Perspective);
    camera.frameTight(framed, float(a.width) / float(a.height), kFramingMargin);
    if (a.zoom != 1.0f) {
        camera.zoom(a.zoom);
        camera.setClipPlanes(camera.nearPlane() * std::min(a.zoom, 1.0f), camera.farPlane() * std::max(a.zoom, 1.0f));
    }

    sss::GpuTimer timer(*context);
    std::vector<double> times;
    // Scattering maps converge over their first frames; build them before the timed frames so
    // the timing shows what a static scene costs ("fixed": no view-independent pass reruns).
    double convergeMs = 0.0;
    int convergeFrames = 0;
    if (scattering) {
        timer.begin();
        while (!meshRenderer->converged()) {
            scene.render(camera, target);
            ++convergeFrames;
        }
        convergeMs = timer.endMilliseconds();
    }
    // The path tracer's running mean: --frames frames before the timed ones (which add to it).
    double pathTraceMs = 0.0;
    if (a.multipleScattering) {
        timer.begin();
        for (int i = 0; i < a.frames; ++i) scene.render(camera, target);
        pathTraceMs = timer.endMilliseconds();
    }
    for (int i = 0; i < a.repeat; ++i) {
        timer.begin();
        scene.render(camera, target);
        times.push_back(timer.endMilliseconds());
    }
    sss::Image image = target.readColor();
    // Sub-pixel offsets would restart the path tracer's mean at every frame.
    if (a.antiAliasing > 1 && !a.multipleScattering) {
        sss::FrameAccumulator accumulator(a.width, a.height);
        for (int i = 0; i < a.antiAliasing; ++i) {
            camera.setSubpixelOffset(sss::FrameAccumulator::subpixelOffset(i, a.width, a.height));
            scene.render(camera, target);
            accumulator.add(target);
        }
        camera.setSubpixelOffset({0.0f, 0.0f});
        image = accumulator.result().readColor();
    }
    if (fs::path(a.out).extension() == ".exr")
        image.saveExr(a.out);  // linear radiance, as rendered
    else
        sss::toDisplay(image, a.display).savePng(a.out);
    if (showsOnlyBackground(image, a.background))
        std::fprintf(stderr, "sss-render: warning: the image shows only the background: nothing of the scene is in "
                             "view (check --mesh-offset, --volume-offset, --zoom, --step and the scene's size)\n");

    std::sort(times.begin(), times.end());
    std::printf("renderer: %s (%s)\n", context->info().renderer.c_str(), context->info().backend.c_str());
    if (mesh) std::printf("mesh: %zu vertices, %zu triangles\n", mesh->vertexCount(), mesh->triangleCount());
    if (volume)
        std::printf("volume: %dx%dx%d %s, spacing %g,%g,%g, values %g..%g, TF range %g..%g\n", volume->dims().x,
                    volume->dims().y, volume->dims().z, sss::voxelTypeName(volume->type()), volume->spacing().x,
                    volume->spacing().y, volume->spacing().z, volume->valueRange().first, volume->valueRange().second,
                    volume->transferFunctionRange().first, volume->transferFunctionRange().second);
    std::printf("frame: %.2f ms median, %.2f min, %.2f max over %d run(s) at %dx%d, %s; first run includes "
                "shader compilation\n",
                times[times.size() / 2], times.front(), times.back(), a.repeat, a.width, a.height,
                timer.method() == sss::TimingMethod::GlTimerQuery ? "GL timer query" : "CPU clock around glFinish");
    if (scattering)
        std::printf("scattering: %s, K = %d, N = %d, maps %d^2; %d frames to converge took %.2f ms "
                    "(includes shader compilation)\n",
                    material.name.c_str(), a.cameras, a.samples, a.mapResolution, convergeFrames, convergeMs);
    if (a.multipleScattering)
        std::printf("multiple scattering: %d paths per pixel (%d frames of %d took %.2f ms before the timed frames, "
                    "includes shader compilation)\n",
                    volumeRenderer->accumulatedSamples(), a.frames, a.samples, pathTraceMs);
    std::printf("wrote %s\n", a.out.c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return runReportingErrors("sss-render", [&] { return run(parseArgs(argc, argv)); });
}
