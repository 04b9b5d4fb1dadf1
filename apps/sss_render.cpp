// sss-render: renders a scene headless to a PNG or EXR (or a turntable of them) and prints the
// timing. The scene comes from --mesh/--volume and the options that describe them, or from a
// JSON scene file (--scene). Run `sss-render --help` for the options.
// Exit codes: 0 ok, 1 runtime failure, 2 bad usage.
#include "common/cli_options.h"

#include <sss/sss.h>
#include <sss/option_table.h>
#include <sss/scene.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

namespace fs = std::filesystem;

namespace {

using namespace examples;

constexpr const char* kDescription = R"(usage: sss-render [--mesh PATH] [--volume PATH] [options] --out FILE.png
       sss-render --scene FILE.json [output options] --out FILE.png

Renders a triangle mesh and/or a scalar volume headless with OpenGL 4.5 (EGL), or the scene of a
JSON scene file (several meshes, volumes and lights with transforms, the camera and the output;
docs/scene-files.md). --save-scene writes the scene a command line describes as such a file.
Relative paths not found as given are looked up in the scene file's folder and the data
directory (and its meshes/ and volumes/ folders).

--mode MODE picks the shading: blinn-phong or sss (mesh); emission-absorption, gradient,
scattering or scattering-gradient (volume); hybrid (a mesh and a volume: sss + scattering,
sharing light and shadows). Default: blinn-phong for a mesh, emission-absorption for a volume.
With both a mesh and a volume, MODE is the volume's; the mesh is drawn in blinn-phong and cuts
the volume's rays. In a Cornell box the default light is a point light under its ceiling and the
default view is straight in (yaw 0, pitch 0).

--isosurface VALUE[:MATERIAL] (repeatable) extracts the surface where the volume's data cross
VALUE (its units: Hounsfield for CT) as a mesh in the volume's box, at its physical size
(spacing in millimetres), in MATERIAL (default: --material). With a volume MODE or hybrid the
volume is drawn around it (--mesh-offset moves the surfaces beside it); with --mode sss or
blinn-phong only the surfaces are drawn. Write negative values as --isosurface=-500:skin1.

--clip-plane and --crop cut the volume (its rays, light volume and path tracer); meshes are not
cut. The cut matter casts no shadows, so a cut face is lit like the inside it exposes, unless
--clip-shadows. A plane NX,NY,NZ,D keeps the points p with n.p + d >= 0 in the volume's normalised
data coordinates (0..1, like --crop); a plane PX,PY,PZ,NX,NY,NZ is in world space, where the
volume's box is 1 unit on its longest side and centred on the origin (before --volume-offset).
Write a leading minus as --clip-plane=-0.1,...
)";

/// Everything the command line says.
struct Args {
    InputArgs input;
    LightArgs light;
    std::string out = "sss-render.png", mode, material = "potato", saveScene;
    sss::MeshRenderOptions mesh;
    sss::BlinnPhongMaterial baseline;
    sss::VolumeRenderOptions volume;
    sss::SceneCamera camera;
    sss::SceneOutput output;
    sss::HybridOptions hybrid;
    std::optional<float> meshSize;
    std::vector<std::string> isosurfaces;  // --isosurface VALUE[:MATERIAL], repeatable
    std::vector<std::string> clipPlanes;   // --clip-plane NX,NY,NZ,D or PX,PY,PZ,NX,NY,NZ, repeatable
    std::string crop;                      // --crop X0,Y0,Z0,X1,Y1,Z1
    bool clipShadows = false;              // --clip-shadows
    sss::CropSpace cropSpace = sss::CropSpace::Data;  // --crop-space
    glm::vec3 meshOffset{0.0f}, volumeOffset{0.0f};
    int repeat = 1, turntable = 0;
    bool listTf = false, listMaterials = false;
    bool noTexture = false;  // --no-texture
    std::string exportTf;
};

/// "VALUE[:MATERIAL]" of --isosurface; the material defaults to `material`.
std::pair<double, std::string> parseIsosurfaceSpec(const std::string& spec, const std::string& material) {
    const std::size_t colon = spec.find(':');
    const std::string valueText = spec.substr(0, colon);
    const std::string name = colon == std::string::npos ? material : spec.substr(colon + 1);
    char* end = nullptr;
    const double value = std::strtod(valueText.c_str(), &end);
    if (valueText.empty() || end != valueText.c_str() + valueText.size() || !std::isfinite(value))
        throw UsageError("--isosurface: expected VALUE[:MATERIAL] with a number VALUE, got \"" + spec + "\"");
    const std::vector<std::string> names = sss::materialPresetNames();
    if (std::find(names.begin(), names.end(), name) == names.end())
        throw UsageError("--isosurface: unknown material \"" + name + "\" (see --list-materials)");
    return {value, name};
}

std::optional<sss::VolumeShading> volumeShading(const std::string& mode) {
    if (mode == "hybrid") return std::nullopt;
    return sss::parseEnumName<sss::VolumeShading>(mode);
}

/// The scene the command-line flags describe (without --scene).
sss::SceneDescription sceneFromFlags(const CLI::App& app, Args& a) {
    if ((!a.clipPlanes.empty() || !a.crop.empty() || a.clipShadows) && a.input.volume.empty())
        throw UsageError("--clip-plane, --crop and --clip-shadows need --volume: they cut the volume");
    if (a.cropSpace == sss::CropSpace::World && a.crop.empty()) throw UsageError("--crop-space world needs --crop");
    if (!a.isosurfaces.empty() && a.input.volume.empty())
        throw UsageError("--isosurface needs --volume: the surface is extracted from it");
    if (a.input.mesh.empty() && a.input.volume.empty())
        throw UsageError("nothing to render: give --mesh PATH and/or --volume PATH, or --scene FILE.json");
    for (const auto& [name, offset] : {std::pair{"--mesh-offset", a.meshOffset}, std::pair{"--volume-offset", a.volumeOffset}})
        if (!(glm::all(glm::lessThanEqual(glm::abs(offset), glm::vec3(sss::Mesh::kMaxCoordinate)))))
            throw UsageError(std::string(name) + ": components must be within +-1e18 (scene units)");
    if (!a.isosurfaces.empty() && a.meshSize)
        throw UsageError("--mesh-size: an isosurface keeps the volume's size");
    if (!a.isosurfaces.empty() && !a.input.mesh.empty())
        throw UsageError("--isosurface makes the meshes: it cannot be combined with --mesh");
    const bool hasMesh = !a.input.mesh.empty() || !a.isosurfaces.empty();
    if (a.mode.empty()) a.mode = a.input.volume.empty() ? "blinn-phong" : "emission-absorption";
    const bool meshMode = a.mode == "blinn-phong" || a.mode == "sss";
    if (a.volume.multipleScattering) {
        if (a.mode != "scattering" && a.mode != "hybrid")
            throw UsageError("--multiple-scattering needs --mode scattering or hybrid (with a volume), got --mode " +
                             a.mode);
        if (given(app, "--volume-model") && a.volume.model != sss::VolumeModel::Physical)
            throw UsageError("--multiple-scattering path-traces the physical model: it cannot be combined with "
                             "--volume-model paper");
        a.volume.model = sss::VolumeModel::Physical;
    }
    if (a.volume.multipleScatteringCache) {
        if (a.volume.multipleScattering)
            throw UsageError("--multiple-scattering-cache adds to single scattering what --multiple-scattering path-traces "
                             "whole: give one of them");
        if (a.mode != "scattering" && a.mode != "scattering-gradient" && a.mode != "hybrid")
            throw UsageError("--multiple-scattering-cache needs --mode scattering, scattering-gradient or hybrid (with a "
                             "volume), got --mode " + a.mode);
        if (given(app, "--volume-model") && a.volume.model != sss::VolumeModel::Physical)
            throw UsageError("--multiple-scattering-cache adds to the physical model's single scattering: it cannot be "
                             "combined with --volume-model paper");
        a.volume.model = sss::VolumeModel::Physical;
    }
    if (a.mode == "hybrid") {
        if (!hasMesh || a.input.volume.empty()) throw UsageError("--mode hybrid needs --mesh (or --isosurface) and --volume");
    } else if (!meshMode && !volumeShading(a.mode)) {
        throw UsageError("--mode: unknown mode \"" + a.mode +
                         "\" (blinn-phong, sss, emission-absorption, gradient, scattering, scattering-gradient, hybrid)");
    } else if (meshMode && !hasMesh) {
        throw UsageError("--mode " + a.mode + " needs --mesh (or --isosurface with --volume)");
    } else if (!meshMode && a.input.volume.empty()) {
        throw UsageError("--mode " + a.mode + " needs --volume");
    } else if (meshMode && !a.input.volume.empty() && a.isosurfaces.empty()) {
        throw UsageError("--mode " + a.mode + " is a mesh mode; with --volume give the volume's mode");
    }

    sss::SceneDescription scene;
    scene.options = a.hybrid;
    scene.camera = a.camera;
    scene.output = a.output;
    const auto addMesh = [&](sss::SceneMesh mesh, const std::string& material) {
        mesh.size = a.meshSize;
        mesh.transform.translate += a.meshOffset;
        mesh.options = a.mesh;
        mesh.options.shading = a.mode == "sss" || a.mode == "hybrid" ? sss::MeshShading::Scattering
                                                                     : sss::MeshShading::BlinnPhong;
        if (scene.options.cornellBox && !given(app, "--environment")) mesh.options.environment = glm::vec3(0.05f);
        mesh.material = sss::materialPreset(material);
        mesh.texture = !a.noTexture;
        mesh.baseline = a.baseline;
        scene.meshes.push_back(std::move(mesh));
    };
    if (!a.input.mesh.empty()) {
        sss::SceneMesh mesh;
        mesh.source = a.input.mesh;
        addMesh(std::move(mesh), a.material);
    }
    for (const std::string& spec : a.isosurfaces) {
        // VALUE[:MATERIAL]; the surface lies where the volume does.
        const auto [value, material] = parseIsosurfaceSpec(spec, a.material);
        sss::SceneMesh mesh;
        mesh.isosurface.emplace().options.value = value;
        mesh.transform.translate = a.volumeOffset;
        addMesh(std::move(mesh), material);
    }
    if (!a.input.volume.empty()) {
        sss::SceneVolume volume;
        volume.source = a.input.volume;
        volume.raw = a.input.raw;
        volume.valueWindow = a.input.tfRange;
        const std::string tf = a.input.tf.empty() ? "ramp" : a.input.tf;
        const bool file = tf.size() > 5 && tf.substr(tf.size() - 5) == ".json";
        if (file) volume.transferFunction.file = tf;
        else volume.transferFunction.preset = tf;
        volume.transform.translate = a.volumeOffset;
        volume.options = a.volume;
        volume.options.shading = meshMode ? sss::VolumeShading::Scattering
                                          : volumeShading(a.mode).value_or(sss::VolumeShading::Scattering);
        volume.visible = !meshMode;  // a mesh mode with --isosurface draws the surfaces alone
        addClipPlanes("--clip-plane", a.clipPlanes, volume.clip);
        volume.clip.cropSpace = a.cropSpace;
        if (!a.crop.empty()) std::tie(volume.clip.cropMin, volume.clip.cropMax) = parseCrop("--crop", a.crop, a.cropSpace);
        volume.clip.clippedMatterCastsShadows = a.clipShadows;
        if (volume.options.multipleScattering)
            volume.options.samplesPerFrame = a.mesh.samples;  // --samples: the path tracer's paths per frame
        scene.volumes.push_back(std::move(volume));
    }
    // A Cornell box is seen straight through its open side unless --yaw or --pitch say otherwise.
    if (scene.options.cornellBox) {
        if (!given(app, "--yaw")) scene.camera.yaw = 0.0f;
        if (!given(app, "--pitch")) scene.camera.pitch = 0.0f;
    }
    if (a.light.given || !scene.options.cornellBox) {
        sss::validateLight(a.light.light(), "--light");
        scene.lights = {a.light.light()};
    }  // else the default Cornell-box light, set once the box is known (run())
    return scene;
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

/// "out.png", frame 7 of a turntable -> "out_0007.png".
fs::path numbered(const fs::path& out, int frame) {
    char suffix[16];
    std::snprintf(suffix, sizeof suffix, "_%04d", frame);
    return out.parent_path() / (out.stem().string() + suffix + out.extension().string());
}

/// Encodes the turntable's numbered PNGs into an MP4 next to them when ffmpeg is installed.
void encodeTurntableVideo(const fs::path& out) {
    if (std::system("command -v ffmpeg >/dev/null 2>&1") != 0) {
        std::printf("turntable: ffmpeg not found, no video written (the frames are PNGs)\n");
        return;
    }
    const fs::path pattern = out.parent_path() / (out.stem().string() + "_%04d.png");
    const fs::path video = out.parent_path() / (out.stem().string() + ".mp4");
    // Even sizes for yuv420p; 30 frames a second.
    const std::string command = "ffmpeg -loglevel error -y -framerate 30 -i '" + pattern.string() +
                                "' -vf 'scale=trunc(iw/2)*2:trunc(ih/2)*2' -pix_fmt yuv420p '" + video.string() + "'";
    if (std::system(command.c_str()) == 0) std::printf("wrote %s\n", video.string().c_str());
    else std::fprintf(stderr, "sss-render: warning: ffmpeg could not encode %s\n", video.string().c_str());
}

/// --list-tf, --list-materials and --export-tf: print or write, and say so. False if none was given.
bool listOrExport(const Args& a) {
    if (a.listTf || a.listMaterials) {
        for (const std::string& name : a.listTf ? sss::TransferFunction::presetNames() : sss::materialPresetNames())
            std::cout << name << "\n";
        return true;
    }
    if (a.exportTf.empty()) return false;
    const std::string tf = a.input.tf.empty() ? "ramp" : a.input.tf;
    sss::TransferFunction::preset(tf).saveParaViewJson(a.exportTf, tf);
    std::printf("wrote %s\n", a.exportTf.c_str());
    return true;
}

/// The flags that describe a scene, which --scene replaces: every flag of the option tables and
/// of the inputs, light, camera and placement.
std::vector<std::string> sceneFlags() {
    std::vector<std::string> flags = {"--mesh", "--isosurface", "--volume", "--mode", "--dims", "--type", "--spacing", "--tf",
                                      "--tf-range", "--material", "--map-resolution", "--no-specular",
                                      "--preintegration", "--color", "--shininess", "--yaw", "--pitch", "--zoom",
                                      "--fov", "--ortho", "--light-dir", "--light-color", "--light-intensity",
                                      "--point-light", "--spot-light", "--mesh-size", "--mesh-offset",
                                      "--volume-offset", "--cornell-box", "--background", "--clip-plane", "--crop",
                                      "--crop-space", "--clip-shadows"};
    auto add = [&flags](const auto& field) {
        if (!field.flag.empty()) flags.emplace_back(field.flag);
    };
    sss::forEachOptionField<sss::MeshRenderOptions>(add);
    sss::forEachOptionField<sss::VolumeRenderOptions>(add);
    return flags;
}

/// The scene to render: the --scene file with the command line's output options, or the flags'.
sss::SceneDescription chooseScene(const CLI::App& app, Args& a) {
    if (a.input.scene.empty()) return sceneFromFlags(app, a);
    for (const std::string& flag : sceneFlags())
        if (given(app, flag)) throw UsageError(flag + " cannot be combined with --scene: the scene file describes it");
    sss::SceneDescription scene = sss::loadSceneFile(a.input.scene);
    if (given(app, "--size")) scene.output.width = a.output.width, scene.output.height = a.output.height;
    if (given(app, "--aa")) scene.output.antiAliasing = a.output.antiAliasing;
    if (given(app, "--exposure")) scene.output.display.exposure = a.output.display.exposure;
    if (given(app, "--tonemap")) scene.output.display.toneMap = a.output.display.toneMap;
    return scene;
}

/// One sss-render run on a loaded, validated scene: the GL objects, the timings and the images.
class Render {
public:
    Render(const Args& a, sss::SceneDescription sceneIn, sss::SceneAssets assetsIn)
        : m_args(a), m_scene(std::move(sceneIn)), m_assets(std::move(assetsIn)), m_context(sss::EglContext::create()),
          m_width(m_scene.output.width), m_height(m_scene.output.height), m_target(m_width, m_height),
          m_timer(*m_context) {
        sss::populateCompositor(m_compositor, m_scene, m_assets);
        if (m_scene.lights.empty()) setCornellBoxLight();
        if (!a.saveScene.empty()) {
            sss::saveSceneFile(m_scene, a.saveScene);
            std::printf("wrote %s\n", a.saveScene.c_str());
        }
        m_camera = sss::sceneCamera(m_scene, m_assets, m_compositor.bounds(), float(m_width) / float(m_height));
        m_scattering = std::any_of(m_scene.meshes.begin(), m_scene.meshes.end(), [](const sss::SceneMesh& m) {
            return m.options.shading == sss::MeshShading::Scattering;
        });
        m_multipleScattering = std::any_of(m_scene.volumes.begin(), m_scene.volumes.end(),
                                           [](const sss::SceneVolume& v) { return v.options.multipleScattering; });
        m_scatteringCache = std::any_of(m_scene.volumes.begin(), m_scene.volumes.end(),
                                        [](const sss::SceneVolume& v) { return v.options.multipleScatteringCache; });
        // The path tracer's frames before the timed ones: the first mesh's --frames.
        m_pathTraceFrames = m_scene.meshes.empty() ? a.mesh.accumulationFrames
                                                   : m_scene.meshes.front().options.accumulationFrames;
    }

    /// Scattering maps and the path tracer's mean converge before the timed frames, so the
    /// timing shows what a static scene costs ("fixed": no view-independent pass reruns).
    void converge() {
        if (m_scattering) {
            m_timer.begin();
            convergeMeshes();
            m_convergeMs = m_timer.endMilliseconds();
        }
        if (m_multipleScattering) {
            m_timer.begin();
            pathTrace();
            m_pathTraceMs = m_timer.endMilliseconds();
        }
        if (m_scatteringCache) {
            m_timer.begin();
            refineCaches();
            m_cacheMs = m_timer.endMilliseconds();
        }
    }

    void renderStill(int repeat) {
        for (int i = 1; i < repeat; ++i) {
            m_timer.begin();
            m_compositor.render(m_camera, m_target);
            m_times.push_back(m_timer.endMilliseconds());
        }
        m_image = renderImage(true);
        write(m_image, m_args.out);
    }

    void renderTurntable(int frames);
    void warnIfEmpty() const;
    void report();

private:
    void setCornellBoxLight();
    void convergeMeshes();
    void pathTrace() {
        for (int i = 0; i < m_pathTraceFrames; ++i) m_compositor.render(m_camera, m_target);
    }
    // Frames until every volume's multiple-scattering cache holds its photons.
    void refineCaches() {
        for (std::size_t i = 0; i < m_compositor.volumeCount(); ++i) {
            const sss::VolumeRenderOptions& o = m_compositor.volume(i).options();
            if (!o.multipleScatteringCache) continue;
            while (m_compositor.volume(i).cachedPhotons() < static_cast<std::uint64_t>(o.cachePhotons)) {
                m_compositor.render(m_camera, m_target);
                ++m_cacheFrames;
            }
        }
    }
    sss::Image renderImage(bool timed);
    bool showsPreview() {
        for (std::size_t i = 0; i < m_compositor.volumeCount(); ++i)
            if (m_compositor.volume(i).lightVolumePreviewed()) return true;
        return false;
    }
    void write(const sss::Image& image, const fs::path& path) const {
        if (path.extension() == ".exr") image.saveExr(path);  // linear radiance, as rendered
        else sss::toDisplay(image, m_scene.output.display).savePng(path);
    }
    void reportScattering();

    const Args& m_args;
    sss::SceneDescription m_scene;
    sss::SceneAssets m_assets;
    std::unique_ptr<sss::EglContext> m_context;
    int m_width, m_height;
    sss::RenderTarget m_target;
    sss::HybridCompositor m_compositor;
    sss::Camera m_camera;
    sss::GpuTimer m_timer;
    bool m_scattering = false, m_multipleScattering = false, m_scatteringCache = false;
    int m_pathTraceFrames = 0, m_cacheFrames = 0;
    double m_convergeMs = 0.0, m_pathTraceMs = 0.0, m_cacheMs = 0.0;
    std::vector<double> m_times;
    sss::Image m_image{1, 1};
};

// The default Cornell-box light, in the colour and intensity the command line gives.
void Render::setCornellBoxLight() {
    m_scene.lights = sss::defaultSceneLights(m_scene, m_compositor.bounds());
    for (sss::Light& light : m_scene.lights)
        if (auto* p = std::get_if<sss::PointLight>(&light))
            p->color = m_args.light.directional.color, p->intensity *= m_args.light.directional.intensity;
    m_compositor.setLights(m_scene.lights);
}

// Every scattering mesh's maps accumulate their frames (each render() adds one to all).
void Render::convergeMeshes() {
    for (std::size_t i = 0; i < m_compositor.meshCount(); ++i)
        if (m_scene.meshes[i].options.shading == sss::MeshShading::Scattering)
            for (int frame = 0; !m_compositor.mesh(i).converged(); ++frame) {
                if (frame > m_scene.meshes[i].options.accumulationFrames + 8)
                    throw sss::Error(sss::ErrorKind::Gl,
                                     "meshes[" + std::to_string(i) + "]: the scattering maps did not converge");
                m_compositor.render(m_camera, m_target);
            }
}

// One image of the current view: the timed frame, then anti-aliasing (sub-pixel offsets would
// restart the path tracer's mean at every frame, so it goes without).
sss::Image Render::renderImage(bool timed) {
    if (timed) m_timer.begin();
    m_compositor.render(m_camera, m_target);
    if (timed) m_times.push_back(m_timer.endMilliseconds());
    // A preview light volume (--light-volume-preview) is for interactive edits: the picture
    // written is the full one, which the next frame builds.
    while (showsPreview()) m_compositor.render(m_camera, m_target);
    const int antiAliasing = m_scene.output.antiAliasing;
    if (antiAliasing <= 1 || m_multipleScattering) return m_target.readColor();
    sss::FrameAccumulator accumulator(m_width, m_height);
    for (int i = 0; i < antiAliasing; ++i) {
        m_camera.setSubpixelOffset(sss::FrameAccumulator::subpixelOffset(i, m_width, m_height));
        m_compositor.render(m_camera, m_target);
        accumulator.add(m_target);
    }
    m_camera.setSubpixelOffset({0.0f, 0.0f});
    return accumulator.result().readColor();
}

// Only the camera moves: the scattering maps and light volumes stay as they are, and each frame
// costs a fixed frame (the path tracer restarts at every view). The camera circles the centre of
// the scene's bounding sphere at the distance where the sphere fits the view (Camera::frame), so
// the subject stays whole and the same size all the way round.
void Render::renderTurntable(int frames) {
    const sss::Bounds content =
        m_scene.options.cornellBox ? sss::makeCornellBox(m_compositor.bounds()).bounds : m_compositor.bounds();
    if (!m_scene.camera.target) {
        m_camera.frame(content);
        if (m_width < m_height) m_camera.setDistance(m_camera.distance() * float(m_height) / float(m_width));
        if (m_scene.camera.zoom != 1.0f) m_camera.zoom(m_scene.camera.zoom);
        const float radius = 0.5f * glm::length(content.size());
        m_camera.setClipPlanes(std::max(m_camera.distance() - 1.2f * radius, 1e-4f * m_camera.distance()),
                               m_camera.distance() + 1.2f * radius);
    }
    const float startYaw = m_camera.yaw();
    for (int frame = 0; frame < frames; ++frame) {
        m_camera.setYaw(startYaw + 360.0f * float(frame) / float(frames));
        if (m_multipleScattering && frame > 0) pathTrace();
        m_image = renderImage(true);
        write(m_image, numbered(m_args.out, frame));
    }
}

void Render::warnIfEmpty() const {
    if (showsOnlyBackground(m_image, glm::vec3(m_scene.options.background)))
        std::fprintf(stderr, "sss-render: warning: the image shows only the background: nothing of the scene is in "
                             "view (check --mesh-offset, --volume-offset, --zoom, --step and the scene's size)\n");
}

void Render::report() {
    std::vector<double> times = m_times;
    std::sort(times.begin(), times.end());
    std::printf("renderer: %s (%s)\n", m_context->info().renderer.c_str(), m_context->info().backend.c_str());
    for (const sss::Mesh& mesh : m_assets.meshes)
        std::printf("mesh: %zu vertices, %zu triangles\n", mesh.vertexCount(), mesh.triangleCount());
    for (const sss::Volume& volume : m_assets.volumes)
        std::printf("volume: %dx%dx%d %s, spacing %g,%g,%g, values %g..%g, TF range %g..%g\n", volume.dims().x,
                    volume.dims().y, volume.dims().z, sss::voxelTypeName(volume.type()), volume.spacing().x,
                    volume.spacing().y, volume.spacing().z, volume.valueRange().first, volume.valueRange().second,
                    volume.transferFunctionRange().first, volume.transferFunctionRange().second);
    std::printf("frame: %.2f ms median, %.2f min, %.2f max over %zu run(s) at %dx%d, %s; first run includes "
                "shader compilation\n",
                times[times.size() / 2], times.front(), times.back(), times.size(), m_width, m_height,
                m_timer.method() == sss::TimingMethod::GlTimerQuery ? "GL timer query" : "CPU clock around glFinish");
    reportScattering();
    if (m_multipleScattering)
        for (std::size_t i = 0; i < m_compositor.volumeCount(); ++i)
            std::printf("multiple scattering: %d paths per pixel (%d frames took %.2f ms before the timed frames, "
                        "includes shader compilation)\n",
                        m_compositor.volume(i).accumulatedSamples(), m_pathTraceFrames, m_pathTraceMs);
    if (m_scatteringCache)
        for (std::size_t i = 0; i < m_compositor.volumeCount(); ++i)
            if (m_compositor.volume(i).options().multipleScatteringCache)
                std::printf("multiple-scattering cache: %llu photons (%d frames took %.2f ms before the timed frames, "
                            "includes shader compilation)\n",
                            static_cast<unsigned long long>(m_compositor.volume(i).cachedPhotons()), m_cacheFrames,
                            m_cacheMs);
}

void Render::reportScattering() {
    for (std::size_t i = 0; i < m_scene.meshes.size(); ++i) {
        const sss::SceneMesh& m = m_scene.meshes[i];
        if (m.options.shading != sss::MeshShading::Scattering) continue;
        const sss::MeshScatteringRenderer& renderer = m_compositor.mesh(i);
        char why[64] = "";
        if (m.texture && m_assets.meshes[i].baseColour())
            std::printf("scattering: the reflectance comes from the mesh's %dx%d base-colour texture\n",
                        m_assets.meshes[i].baseColour()->width(), m_assets.meshes[i].baseColour()->height());
        if (m.options.combine == sss::MeshCombine::Automatic)
            std::snprintf(why, sizeof why, " (auto: edges %.3g diffusion lengths)", renderer.edgeToDiffusionLength());
        if (renderer.activeCombine() == sss::MeshCombine::VertexEstimate)
            std::printf("scattering: %s, vertex estimate (no maps)%s, N = %d; converging took %.2f ms (includes "
                        "shader compilation)\n",
                        m.material.name.c_str(), why, m.options.samples, m_convergeMs);
        else
            std::printf("scattering: %s, K = %d, N = %d, maps %d^2, %s combine%s; converging took %.2f ms (includes "
                        "shader compilation)\n",
                        m.material.name.c_str(), m.options.cameras, m.options.samples, m.options.mapResolution,
                        std::string(sss::enumName(renderer.activeCombine())).c_str(), why, m_convergeMs);
    }
}

int run(CLI::App& app, Args& a) {
    if (listOrExport(a)) return 0;
    const std::string ext = fs::path(a.out).extension().string();
    if (ext != ".png" && ext != ".exr") throw UsageError("--out: the file must end in .png or .exr, got \"" + a.out + "\"");
    if (a.turntable < 0 || a.turntable > 100000) throw UsageError("--turntable: must be in 0..100000 frames");
    sss::SceneDescription scene = chooseScene(app, a);
    // Load and validate everything before touching GL, so bad input fails fast and clearly.
    const std::vector<fs::path> searchDirs = {dataDirectory(a.input.dataDir)};
    sss::SceneAssets assets = sss::loadSceneAssets(scene, searchDirs);
    for (const sss::SceneMesh& m : scene.meshes) sss::validate(m.options), sss::validate(m.baseline);
    for (const sss::SceneVolume& v : scene.volumes) sss::validate(v.options);
    sss::validate(scene.options);

    Render render(a, std::move(scene), std::move(assets));
    render.converge();
    if (a.turntable > 0) render.renderTurntable(a.turntable);
    else render.renderStill(a.repeat);
    render.warnIfEmpty();
    render.report();
    if (a.turntable > 0) {
        std::printf("wrote %d turntable frames %s .. %s\n", a.turntable, numbered(a.out, 0).string().c_str(),
                    numbered(a.out, a.turntable - 1).string().c_str());
        if (ext == ".png") encodeTurntableVideo(a.out);
    } else {
        std::printf("wrote %s\n", a.out.c_str());
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return runReportingErrors("sss-render", [&] {
        Args a;
        CLI::App app(kDescription, "sss-render");
        addInputOptions(app, a.input);
        app.add_option("--mode", a.mode, "shading (above)")->type_name("MODE")->group("input");
        addParsed(app, "--mesh-size", a.meshSize,
                  [](const std::string& name, const std::string& text) {
                      const float size = parseFloat(name, text);
                      if (!(size > 0.0f && size <= 1e6f)) throw UsageError(name + ": must be in (0, 1e6] scene units");
                      return std::optional(size);
                  },
                  "scale the mesh uniformly to a largest side of S scene units, centred on the origin (default: the "
                  "file's own units); --scale then says how many mm a unit is",
                  "S")
            ->group("placement");
        addVec3(app, "--mesh-offset", a.meshOffset, "move the mesh (scene units)")->group("placement");
        app.add_option("--isosurface", a.isosurfaces,
                       "a surface of --volume where its data cross VALUE, as a translucent mesh in MATERIAL (above; "
                       "repeatable)")
            ->type_name("VALUE[:MATERIAL]")
            ->allow_extra_args(false)
            ->group("input");
        app.add_option("--clip-plane", a.clipPlanes,
                       "cut the volume by a plane, keeping n.p + d >= 0 in normalised data coordinates (NX,NY,NZ,D), "
                       "or the side the normal N points to of a world-space plane through P (PX,PY,PZ,NX,NY,NZ); "
                       "repeatable, up to 6, all in one form")
            ->type_name("NX,NY,NZ,D|PX,PY,PZ,NX,NY,NZ")
            ->allow_extra_args(false)
            ->group("clipping");
        app.add_option("--crop", a.crop,
                       "keep only this box of the volume, in normalised data coordinates (0..1) or, with --crop-space "
                       "world, world coordinates")
            ->type_name("X0,Y0,Z0,X1,Y1,Z1")
            ->group("clipping");
        addEnum(app, "--crop-space", a.cropSpace, "where --crop's box is given")->group("clipping");
        app.add_flag("--clip-shadows", a.clipShadows, "matter cut by --clip-plane or --crop still casts shadows")
            ->group("clipping");
        addVec3(app, "--volume-offset", a.volumeOffset, "move the volume (its box is 1 unit on its longest side)")
            ->group("placement");
        app.add_flag("--cornell-box", a.hybrid.cornellBox, "put the scene in a Cornell box")->group("placement");
        addMeshOptions(app, a.mesh, a.material, a.noTexture);
        addBaselineOptions(app, a.baseline);
        addVolumeOptions(app, a.volume);
        addCameraOptions(app, a.camera);
        addLightOptions(app, a.light);
        app.add_option("--out", a.out,
                       "output image: a PNG is the display image (exposure, tone mapping, sRGB); an OpenEXR file "
                       "holds the linear radiance in 32-bit float")
            ->type_name("FILE.png|FILE.exr")
            ->default_str(a.out)
            ->group("output");
        addSizeOption(app, a.output.width, a.output.height, "image size (default: the thesis viewport)");
        addParsed(app, "--background", a.hybrid.background,
                  [](const std::string& name, const std::string& text) { return glm::vec4(parseVec3(name, text), 1.0f); },
                  "linear background colour (the default displays as the dark grey-blue sRGB 0.1,0.1,0.12)", "R,G,B",
                  defaultText(glm::vec3(a.hybrid.background)))
            ->group("output");
        addAntiAliasingOption(app, a.output.antiAliasing,
                              "anti-aliasing: average N frames with sub-pixel camera offsets, after the timed frames "
                              "(1 = off)");
        addDisplayOptions(app, a.output.display);
        addParsed(app, "--repeat", a.repeat,
                  [](const std::string& name, const std::string& text) {
                      const int n = parseInt(name, text);
                      if (n < 1) throw UsageError(name + ": must be >= 1");
                      return n;
                  },
                  "render N times and report median/min/max", "N", "1")
            ->group("output");
        addInt(app, "--turntable", a.turntable,
               "render N frames orbiting the scene (360 degrees of yaw) as OUT_0000.png ...; with ffmpeg "
               "installed also OUT.mp4. Scattering maps and light volumes are computed once",
               "N")
            ->group("output");
        app.add_option("--save-scene", a.saveScene, "also write the scene as a JSON scene file")
            ->type_name("FILE.json")
            ->group("output");
        app.add_flag("--list-tf", a.listTf, "print the transfer-function presets and exit")->group("lists");
        app.add_flag("--list-materials", a.listMaterials, "print the material presets and exit")->group("lists");
        app.add_option("--export-tf", a.exportTf,
                       "write the --tf preset as a ParaView JSON colour map (x in [0,1]) and exit (other programs, "
                       "e.g. benchmarks/vtk_peer.py, then use the same function)")
            ->type_name("FILE.json")
            ->group("lists");
        parseCommandLine(app, argc, argv);
        return run(app, a);
    });
}
