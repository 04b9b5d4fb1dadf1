// GL side of the Python module: the headless context, the renderers' option structs, the mesh
// and volume renderers and the hybrid scene (HybridCompositor). Every object that owns GL
// resources holds its context (ContextHolder) and makes it current before touching GL.
#include "bindings.h"

#include <sss/frame_accumulator.h>
#include <sss/hybrid_compositor.h>
#include <sss/isosurface.h>
#include <sss/mesh_scattering_renderer.h>
#include <sss/procedural.h>
#include <sss/render_target.h>
#include <sss/volume_scattering_renderer.h>


namespace ssspy {

namespace {

ContextPtr g_defaultContext;  // released by an atexit hook (module.cpp calls releaseDefaultContext)

ContextPtr makeContext(sss::EglPlatform platform, bool debug, bool preferSoftware) {
    auto holder = std::make_shared<ContextHolder>();
    holder->context = sss::EglContext::create({.platform = platform, .debug = debug, .preferSoftware = preferSoftware});
    return holder;
}

// ---- rendering one picture ---------------------------------------------------------------------

// How render() turns frames into the returned image, the steps sss-render takes:
//  1. with `converge`, frames until every scattering mesh's maps are converged;
//  2. `frames` frames (each adds samples to a multiple-scattering volume's running mean);
//  3. the image read back, or with antialias > 1 the mean of that many frames with sub-pixel
//     camera offsets (sss::FrameAccumulator), not for progressive (path-traced) volumes.
struct FrameSettings {
    int width = 640;
    int height = 480;
    int antialias = 1;
    int frames = 1;
    bool converge = true;
};

using DrawFn = std::function<void(const sss::Camera&, sss::RenderTarget&)>;

py::array_t<float> renderPicture(ContextHolder& context, const sss::Camera& cameraIn, const FrameSettings& s,
                                 const DrawFn& draw, const std::function<bool()>& converged, bool progressive) {
    if (s.antialias < 1) invalidArgument("render: antialias must be >= 1, got " + std::to_string(s.antialias));
    if (s.frames < 1) invalidArgument("render: frames must be >= 1, got " + std::to_string(s.frames));
    context.makeCurrent();
    sss::Camera camera = cameraIn;
    sss::RenderTarget target(s.width, s.height);
    if (s.converge && converged) {
        // Bounded, in case a renderer never reports convergence (accumulationFrames is at most
        // what validate() allows, far below this).
        for (int i = 0; i < 1 << 20 && !converged(); ++i) draw(camera, target);
    }
    for (int i = 0; i < s.frames; ++i) draw(camera, target);
    if (s.antialias == 1 || progressive) return toNumpy(target.readColor());
    sss::FrameAccumulator accumulator(s.width, s.height);
    for (int i = 0; i < s.antialias; ++i) {
        camera.setSubpixelOffset(sss::FrameAccumulator::subpixelOffset(i, s.width, s.height));
        draw(camera, target);
        accumulator.add(target);
    }
    return toNumpy(accumulator.result().readColor());
}

// The camera of a render() without one: yaw 30, pitch 20 (a Cornell box: 0, 0, straight in),
// the content framed tightly for the image's aspect with a 4 % margin (sss-render's default view).
sss::Camera autoCamera(const std::vector<glm::vec3>& points, int width, int height, bool straightIn = false) {
    if (points.empty()) invalidArgument("render: nothing to frame (no mesh or volume set); pass a camera");
    if (width <= 0 || height <= 0) invalidArgument("render: width and height must be > 0");
    sss::Camera camera;
    camera.setYaw(straightIn ? 0.0f : 30.0f);
    camera.setPitch(straightIn ? 0.0f : 20.0f);
    camera.frameTight(points, static_cast<float>(width) / static_cast<float>(height), 0.04f);
    return camera;
}

std::vector<glm::vec3> transformedPoints(const std::vector<glm::vec3>& points, const glm::mat4& model) {
    std::vector<glm::vec3> out;
    out.reserve(points.size());
    for (const glm::vec3& p : points) out.emplace_back(model * glm::vec4(p, 1.0f));
    return out;
}

std::vector<glm::vec3> boxCorners(const sss::Bounds& b) {
    std::vector<glm::vec3> corners;
    for (int i = 0; i < 8; ++i)
        corners.emplace_back((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y, (i & 4) ? b.max.z : b.min.z);
    return corners;
}

py::dict statsDict(const sss::RenderStats& stats) {
    py::dict d;
    for (const auto& [name, pass] : stats.passes())
        d[py::str(name)] = py::dict(py::arg("runs") = pass.runs, py::arg("last_ms") = pass.lastMs,
                                    py::arg("total_ms") = pass.totalMs);
    return d;
}

// Options from an optional struct plus keyword overrides (validated by the struct's replace()).
template <typename Options>
Options optionsFrom(const py::object& options, const py::kwargs& kw) {
    Options base = options.is_none() ? Options{} : options.cast<Options>();
    if (kw.empty()) return base;
    return py::cast(base).attr("replace")(**kw).template cast<Options>();
}

const char* kRenderDoc =
    "Renders a picture and returns it as a float32 array (height, width, 4): linear radiance, RGBA, "
    "top row first (sss.to_display() makes it an 8-bit picture). camera=None frames the content from "
    "yaw 30, pitch 20 (a Scene's Cornell box straight in). With converge, scattering meshes first accumulate their maps; then `frames` "
    "frames are drawn (each adds samples to a multiple-scattering volume); antialias > 1 averages that "
    "many frames with sub-pixel camera offsets (not for multiple scattering, whose mean it would restart).";

// ---- mesh renderer -------------------------------------------------------------------------------

struct MeshRendererPy {
    ContextPtr context;
    std::unique_ptr<sss::MeshScatteringRenderer> renderer;
    sss::BlinnPhongMaterial material;
    sss::ScatteringMaterial scatteringMaterial;
    std::vector<sss::Light> lights;
    std::vector<glm::vec3> positions;  // of the mesh, for framing
    glm::mat4 model{1.0f};

    MeshRendererPy(ContextPtr c, const sss::MeshRenderOptions& options) : context(std::move(c)) {
        context->makeCurrent();
        renderer = std::make_unique<sss::MeshScatteringRenderer>(options);
    }
    ~MeshRendererPy() {
        context->makeCurrent();
        renderer.reset();
    }
    sss::MeshScatteringRenderer& get() {
        context->makeCurrent();
        return *renderer;
    }
};

struct VolumeRendererPy {
    ContextPtr context;
    std::unique_ptr<sss::VolumeScatteringRenderer> renderer;
    sss::TransferFunction transferFunction;
    std::vector<sss::Light> lights;
    sss::Bounds bounds;  // of the volume in its own space, for framing
    glm::mat4 model{1.0f};
    bool hasVolume = false;

    VolumeRendererPy(ContextPtr c, const sss::VolumeRenderOptions& options) : context(std::move(c)) {
        context->makeCurrent();
        renderer = std::make_unique<sss::VolumeScatteringRenderer>(options);
    }
    ~VolumeRendererPy() {
        context->makeCurrent();
        renderer.reset();
    }
    sss::VolumeScatteringRenderer& get() {
        context->makeCurrent();
        return *renderer;
    }
};

// ---- hybrid scene --------------------------------------------------------------------------------

struct SceneMeshInfo {
    std::vector<glm::vec3> positions;
    glm::mat4 model{1.0f};
    sss::BlinnPhongMaterial material;
    sss::ScatteringMaterial scatteringMaterial;
};
struct SceneVolumeInfo {
    sss::Bounds bounds;
    glm::mat4 model{1.0f};
    sss::TransferFunction transferFunction;
};

struct ScenePy {
    ContextPtr context;
    std::unique_ptr<sss::HybridCompositor> compositor;
    std::vector<SceneMeshInfo> meshes;
    std::vector<SceneVolumeInfo> volumes;
    std::uint64_t generation = 0;  // bumped by clear(): handles from before it are stale

    ScenePy(ContextPtr c, const sss::HybridOptions& options) : context(std::move(c)) {
        context->makeCurrent();
        compositor = std::make_unique<sss::HybridCompositor>(options);
    }
    ~ScenePy() {
        context->makeCurrent();
        compositor.reset();
    }
    sss::HybridCompositor& get() {
        context->makeCurrent();
        return *compositor;
    }
    std::vector<glm::vec3> framingPoints() const {
        std::vector<glm::vec3> points;
        for (const SceneMeshInfo& m : meshes) {
            std::vector<glm::vec3> p = transformedPoints(m.positions, m.model);
            points.insert(points.end(), p.begin(), p.end());
        }
        for (const SceneVolumeInfo& v : volumes) {
            std::vector<glm::vec3> p = transformedPoints(boxCorners(v.bounds), v.model);
            points.insert(points.end(), p.begin(), p.end());
        }
        return points;
    }
};

// A mesh or volume of a Scene: valid until Scene.clear().
struct SceneItem {
    std::shared_ptr<ScenePy> scene;
    std::size_t index = 0;
    std::uint64_t generation = 0;
    void check() const {
        if (generation != scene->generation)
            invalidArgument("Scene: this mesh or volume was removed by Scene.clear()");
    }
};
struct SceneMeshPy : SceneItem {
    sss::MeshScatteringRenderer& get() {
        check();
        return scene->get().mesh(index);
    }
    SceneMeshInfo& info() { return scene->meshes[index]; }
};
struct SceneVolumePy : SceneItem {
    sss::VolumeScatteringRenderer& get() {
        check();
        return scene->get().volume(index);
    }
    SceneVolumeInfo& info() { return scene->volumes[index]; }
};

// Properties shared by MeshRenderer and a Scene's meshes.
template <typename W, typename Cls>
void meshProperties(Cls& cls, sss::BlinnPhongMaterial& (*material)(W&), sss::ScatteringMaterial& (*scattering)(W&)) {
    cls.def_property("options", [](W& w) { return w.get().options(); },
                     [](W& w, const sss::MeshRenderOptions& o) { w.get().setOptions(o); }, "MeshRenderOptions")
        .def("configure",
             [](W& w, const py::kwargs& kw) { w.get().setOptions(optionsFrom<sss::MeshRenderOptions>(py::cast(w.get().options()), kw)); },
             "Changes the given MeshRenderOptions fields, keeping the others.")
        .def_property("material", [material](W& w) { return material(w); },
                      [material](W& w, const sss::BlinnPhongMaterial& m) {
                          w.get().setMaterial(m);
                          material(w) = m;
                      },
                      "BlinnPhongMaterial of the BLINN_PHONG shading")
        .def_property("scattering_material", [scattering](W& w) { return scattering(w); },
                      [scattering](W& w, const sss::ScatteringMaterial& m) {
                          w.get().setScatteringMaterial(m);
                          scattering(w) = m;
                      },
                      "ScatteringMaterial of the SCATTERING shading (default: potato)")
        .def("set_textured_material",
             [](W& w, const sss::TexturedScattering& t) { w.get().setScatteringMaterial(t); }, py::arg("material"),
             "A TexturedScattering instead of scattering_material (the mesh needs texcoords, and a base colour "
             "unless the material has a reflectance texture). Setting scattering_material returns to it.")
        .def_property_readonly("converged", [](W& w) { return w.get().converged(); },
                               "True once the scattering maps hold accumulation_frames frames")
        .def_property_readonly("stats", [](W& w) { return statsDict(w.get().stats()); });
}

template <typename W, typename Cls>
void volumeProperties(Cls& cls, sss::TransferFunction& (*tf)(W&)) {
    cls.def_property("options", [](W& w) { return w.get().options(); },
                     [](W& w, const sss::VolumeRenderOptions& o) { w.get().setOptions(o); }, "VolumeRenderOptions")
        .def("configure",
             [](W& w, const py::kwargs& kw) { w.get().setOptions(optionsFrom<sss::VolumeRenderOptions>(py::cast(w.get().options()), kw)); },
             "Changes the given VolumeRenderOptions fields, keeping the others.")
        .def_property("transfer_function", [tf](W& w) { return tf(w); },
                      [tf](W& w, const sss::TransferFunction& f) {
                          w.get().setTransferFunction(f);
                          tf(w) = f;
                      },
                      "TransferFunction (default: the ramp)")
        .def_property_readonly("accumulated_samples", [](W& w) { return w.get().accumulatedSamples(); },
                               "paths per pixel in the multiple-scattering mean")
        .def_property_readonly("cached_photons", [](W& w) { return w.get().cachedPhotons(); },
                               "photons in the multiple-scattering cache (0 when it is off)")
        .def_property_readonly("light_volume_previewed", [](W& w) { return w.get().lightVolumePreviewed(); },
                               "the last frame drew a preview light volume (light_volume_preview_scale): the "
                               "next builds the full one")
        .def("set_clip",
             [](W& w, const std::vector<std::pair<glm::vec3, glm::vec3>>& planes, glm::vec3 cropMin, glm::vec3 cropMax,
                bool clippedMatterCastsShadows, sss::CropSpace cropSpace, sss::CropSpace planeSpace) {
                 sss::VolumeClip clip;
                 clip.cropSpace = cropSpace;
                 for (const auto& [point, normal] : planes) clip.planes.push_back({point, normal});
                 clip.planeSpace = planeSpace;
                 clip.cropMin = cropMin;
                 clip.cropMax = cropMax;
                 clip.clippedMatterCastsShadows = clippedMatterCastsShadows;
                 w.get().setClip(clip);
             },
             py::arg("planes") = std::vector<std::pair<glm::vec3, glm::vec3>>{}, py::arg("crop_min") = glm::vec3(0.0f),
             py::arg("crop_max") = glm::vec3(1.0f), py::arg("clipped_matter_casts_shadows") = false,
             py::arg("crop_space") = sss::CropSpace::Data, py::arg("plane_space") = sss::CropSpace::World,
             "Cuts the volume (sss::VolumeClip): planes as (point, normal) pairs, keeping the side the normal "
             "points to (up to 6), in world space or, with plane_space=\"data\", in normalised data coordinates; "
             "the crop box in normalised data coordinates, or world coordinates with "
             "crop_space=\"world\"; cut matter casts no shadows unless clipped_matter_casts_shadows. No arguments: "
             "nothing cut.")
        .def_property_readonly("clip",
                               [](W& w) {
                                   const sss::VolumeClip& c = w.get().clip();
                                   std::vector<std::pair<glm::vec3, glm::vec3>> planes;
                                   for (const sss::ClipPlane& p : c.planes) planes.emplace_back(p.point, p.normal);
                                   py::dict d;
                                   d["planes"] = planes;
                                   d["crop_min"] = c.cropMin;
                                   d["crop_max"] = c.cropMax;
                                   d["clipped_matter_casts_shadows"] = c.clippedMatterCastsShadows;
                                   d["crop_space"] = c.cropSpace;
                                   d["plane_space"] = c.planeSpace;
                                   return d;
                               },
                               "the clip as set_clip's keyword arguments")
        .def_property_readonly("light_volume_scale_in_use", [](W& w) { return w.get().lightVolumeScaleInUse(); })
        .def_property_readonly("stats", [](W& w) { return statsDict(w.get().stats()); });
}

void bindOptions(py::module_& m) {
    bindEnum<sss::MeshShading>(m, "MeshShading",
                               {{"BLINN_PHONG", sss::MeshShading::BlinnPhong}, {"SCATTERING", sss::MeshShading::Scattering}},
                               "Mesh shading: the Blinn-Phong baseline or subsurface scattering.");
    bindEnum<sss::ScatteringProfile>(m, "ScatteringProfile",
                                     {{"CALIBRATED", sss::ScatteringProfile::Calibrated},
                                      {"DIPOLE", sss::ScatteringProfile::Dipole}},
                                     "The subsurface profile of the scattering mesh shading.");
    // Here, after ScatteringProfile: its default needs the enum bound.
    m.def("material_from_reflectance", &sss::materialFromReflectance, py::arg("reflectance"),
          py::arg("mean_free_path"), py::arg("eta"), py::arg("profile") = sss::ScatteringProfile::Calibrated,
          "The homogeneous material whose profile reflects `reflectance` (normal incidence) with this mean free path.");

    bindEnum<sss::MeshCombine>(m, "MeshCombine",
                               {{"PER_PIXEL", sss::MeshCombine::PerPixel},
                                {"PER_VERTEX", sss::MeshCombine::PerVertex},
                                {"VERTEX_ESTIMATE", sss::MeshCombine::VertexEstimate},
                                {"AUTOMATIC", sss::MeshCombine::Automatic}},
                               "Where the combine pass reads the scattered light.");
    bindEnum<sss::VolumeShading>(m, "VolumeShading",
                                 {{"EMISSION_ABSORPTION", sss::VolumeShading::EmissionAbsorption},
                                  {"GRADIENT", sss::VolumeShading::Gradient},
                                  {"SCATTERING", sss::VolumeShading::Scattering},
                                  {"SCATTERING_GRADIENT", sss::VolumeShading::ScatteringGradient}},
                                 "Volume shading modes.");
    bindEnum<sss::VolumeModel>(m, "VolumeModel", {{"PAPER", sss::VolumeModel::Paper}, {"PHYSICAL", sss::VolumeModel::Physical}},
                               "What a lit volume sample scatters towards the viewer.");
    bindEnum<sss::LightVolumeFallback>(m, "LightVolumeFallback",
                                       {{"REDUCE", sss::LightVolumeFallback::Reduce}, {"FAIL", sss::LightVolumeFallback::Fail}},
                                       "What happens when a light volume does not fit the GPU.");
    bindEnum<sss::RayCaster>(m, "RayCaster",
                             {{"AUTO", sss::RayCaster::Auto}, {"FRAGMENT", sss::RayCaster::Fragment},
                              {"COMPUTE", sss::RayCaster::Compute}},
                             "Which ray caster draws a volume (the same image either way).");
    bindEnum<sss::CacheViewEvaluation>(m, "CacheViewEvaluation",
                                       {{"AUTO", sss::CacheViewEvaluation::Auto},
                                        {"PER_CELL", sss::CacheViewEvaluation::PerCell},
                                        {"PER_SAMPLE", sss::CacheViewEvaluation::PerSample}},
                                       "Where the multiple-scattering cache's light towards the viewer is evaluated.");
    bindEnum<sss::LightPropagation>(m, "LightPropagation",
                                    {{"AUTO", sss::LightPropagation::Auto}, {"SWEEP", sss::LightPropagation::Sweep},
                                     {"DOUBLING", sss::LightPropagation::Doubling}},
                                    "How the light volume is carried from the light (sweep or ray doubling).");
    bindEnum<sss::VolumeReconstruction>(m, "VolumeReconstruction",
                                        {{"TRILINEAR", sss::VolumeReconstruction::Trilinear},
                                         {"CUBIC_B_SPLINE", sss::VolumeReconstruction::CubicBSpline}},
                                        "How a volume's field is reconstructed between voxel centres.");
    bindEnum<sss::CropSpace>(m, "CropSpace", {{"DATA", sss::CropSpace::Data}, {"WORLD", sss::CropSpace::World}},
                             "Where a clip's crop box is given: normalised data coordinates or world coordinates.");

    using MO = sss::MeshRenderOptions;
    Struct<MO>(m, "MeshRenderOptions", "Options of the mesh renderer (see sss::MeshRenderOptions for each range).")
        .tableFields()
        .done([](const MO& o) { sss::validate(o); });

    using VO = sss::VolumeRenderOptions;
    Struct<VO>(m, "VolumeRenderOptions", "Options of the volume renderer (see sss::VolumeRenderOptions for each range).")
        .tableFields()
        .done([](const VO& o) { sss::validate(o); });

    using HO = sss::HybridOptions;
    Struct<HO>(m, "HybridOptions", "Options of a Scene (sss::HybridCompositor).")
        .tableFields()
        .done([](const HO& o) { sss::validate(o); });
}

void bindContext(py::module_& m) {
    bindEnum<sss::EglPlatform>(m, "EglPlatform",
                               {{"AUTO", sss::EglPlatform::Auto}, {"SURFACELESS", sss::EglPlatform::Surfaceless},
                                {"DEVICE", sss::EglPlatform::Device}, {"DEFAULT_PBUFFER", sss::EglPlatform::DefaultPbuffer}},
                               "How the headless EGL context finds a display.");
    py::class_<ContextHolder, ContextPtr>(m, "Context",
                                          "A headless OpenGL 4.5 context (EGL). Renderers use default_context() "
                                          "unless given one; each keeps its context alive.")
        .def(py::init(&makeContext), py::kw_only(), py::arg("platform") = sss::EglPlatform::Auto,
             py::arg("debug") = false, py::arg("prefer_software") = false)
        .def("make_current", &ContextHolder::makeCurrent)
        .def_property_readonly("vendor", [](const ContextHolder& c) { return c.context->info().vendor; })
        .def_property_readonly("renderer", [](const ContextHolder& c) { return c.context->info().renderer; })
        .def_property_readonly("version", [](const ContextHolder& c) { return c.context->info().version; })
        .def_property_readonly("backend", [](const ContextHolder& c) { return c.context->info().backend; })
        .def_property_readonly("debug", [](const ContextHolder& c) { return c.context->info().debug; })
        .def_property_readonly("software", [](const ContextHolder& c) { return c.context->info().software; })
        .def_property_readonly("debug_messages",
                               [](const ContextHolder& c) {
                                   const sss::DebugMessageCounts n = c.context->debugMessages();
                                   return py::dict(py::arg("errors") = n.errors, py::arg("warnings") = n.warnings,
                                                   py::arg("other") = n.other);
                               },
                               "KHR_debug message counts since creation or reset (all 0 unless debug)")
        .def_property_readonly("last_debug_error", [](const ContextHolder& c) { return c.context->lastDebugError(); })
        .def("reset_debug_messages", [](ContextHolder& c) { c.context->resetDebugMessages(); })
        .def("__repr__", [](const ContextHolder& c) {
            return "<sss.Context " + c.context->info().renderer + " (" + c.context->info().backend + ")>";
        });
    m.def("default_context", &defaultContext,
          "The context renderers use when given none, created on first use (honours SSS_GL_DEBUG and "
          "SSS_EGL_SOFTWARE).");
}

void bindRenderers(py::module_& m) {
    using MR = MeshRendererPy;
    py::class_<MR> meshCls(m, "MeshRenderer", "Draws one mesh (sss::MeshScatteringRenderer).");
    meshCls.def(py::init([](const py::object& options, const py::object& context, const py::kwargs& kw) {
                 return std::make_unique<MR>(contextFrom(context), optionsFrom<sss::MeshRenderOptions>(options, kw));
             }),
             py::arg("options") = py::none(), py::kw_only(), py::arg("context") = py::none(),
             "MeshRenderOptions as `options` and/or as keyword arguments (MeshRenderer(shading='scattering', cameras=16)).")
        .def("set_mesh",
             [](MR& w, const sss::Mesh& mesh, const std::optional<glm::mat4>& model) {
                 w.get().setMesh(mesh, model.value_or(glm::mat4(1.0f)));
                 w.positions = mesh.positions();
                 w.model = model.value_or(glm::mat4(1.0f));
             },
             py::arg("mesh"), py::arg("model") = py::none(), "Uploads a Mesh; model is a 4x4 placement matrix.")
        .def_property("model", [](MR& w) { return w.model; },
                      [](MR& w, const glm::mat4& model) {
                          w.get().setModelTransform(model);
                          w.model = model;
                      })
        .def_property("lights", [](MR& w) { return w.lights; },
                      [](MR& w, std::vector<sss::Light> lights) {
                          w.get().setLights(lights);
                          w.lights = std::move(lights);
                      },
                      "list of DirectionalLight, PointLight, SpotLight (at most 8)")
        .def("render",
             [](MR& w, const std::optional<sss::Camera>& camera, int width, int height, glm::vec4 background,
                int antialias, int frames, bool converge) {
                 const sss::Camera cam = camera ? *camera : autoCamera(transformedPoints(w.positions, w.model), width, height);
                 sss::MeshScatteringRenderer& r = w.get();
                 auto draw = [&](const sss::Camera& c, sss::RenderTarget& t) {
                     t.clear(background);
                     r.render(c, t);
                 };
                 std::function<bool()> converged;
                 if (r.options().shading == sss::MeshShading::Scattering) converged = [&r] { return r.converged(); };
                 return renderPicture(*w.context, cam, {width, height, antialias, frames, converge}, draw, converged, false);
             },
             py::arg("camera") = py::none(), py::kw_only(), py::arg("width") = 640, py::arg("height") = 480,
             py::arg("background") = sss::HybridOptions{}.background, py::arg("antialias") = 1, py::arg("frames") = 1,
             py::arg("converge") = true, kRenderDoc);
    meshProperties<MR>(meshCls, [](MR& w) -> sss::BlinnPhongMaterial& { return w.material; },
                       [](MR& w) -> sss::ScatteringMaterial& { return w.scatteringMaterial; });

    using VR = VolumeRendererPy;
    py::class_<VR> volumeCls(m, "VolumeRenderer", "Draws one volume by ray casting (sss::VolumeScatteringRenderer).");
    volumeCls
        .def(py::init([](const py::object& options, const py::object& context, const py::kwargs& kw) {
                 return std::make_unique<VR>(contextFrom(context), optionsFrom<sss::VolumeRenderOptions>(options, kw));
             }),
             py::arg("options") = py::none(), py::kw_only(), py::arg("context") = py::none(),
             "VolumeRenderOptions as `options` and/or as keyword arguments (VolumeRenderer(shading='scattering')).")
        .def("set_volume",
             [](VR& w, const sss::Volume& v, const std::optional<glm::mat4>& model) {
                 w.get().setVolume(v, model.value_or(glm::mat4(1.0f)));
                 w.bounds = v.worldBounds();
                 w.model = model.value_or(glm::mat4(1.0f));
                 w.hasVolume = true;
             },
             py::arg("volume"), py::arg("model") = py::none(),
             "Uploads a Volume; it fills Volume.world_bounds (largest side 1, centred) placed by model.")
        .def_property("model", [](VR& w) { return w.model; },
                      [](VR& w, const glm::mat4& model) {
                          w.get().setModelTransform(model);
                          w.model = model;
                      })
        .def_property("lights", [](VR& w) { return w.lights; },
                      [](VR& w, std::vector<sss::Light> lights) {
                          w.get().setLights(lights);
                          w.lights = std::move(lights);
                      },
                      "list of DirectionalLight, PointLight, SpotLight (at most 8)")
        .def("render",
             [](VR& w, const std::optional<sss::Camera>& camera, int width, int height, glm::vec4 background,
                int antialias, int frames) {
                 std::vector<glm::vec3> points;
                 if (w.hasVolume) points = transformedPoints(boxCorners(w.bounds), w.model);
                 const sss::Camera cam = camera ? *camera : autoCamera(points, width, height);
                 sss::VolumeScatteringRenderer& r = w.get();
                 auto draw = [&](const sss::Camera& c, sss::RenderTarget& t) {
                     t.clear(background);
                     r.render(c, t);
                 };
                 return renderPicture(*w.context, cam, {width, height, antialias, frames, false}, draw, {},
                                      r.options().multipleScattering);
             },
             py::arg("camera") = py::none(), py::kw_only(), py::arg("width") = 640, py::arg("height") = 480,
             py::arg("background") = sss::HybridOptions{}.background, py::arg("antialias") = 1, py::arg("frames") = 1,
             kRenderDoc);
    volumeProperties<VR>(volumeCls, [](VR& w) -> sss::TransferFunction& { return w.transferFunction; });
}

// Scene.add_mesh and Scene.add_isosurface: the mesh with its placement and materials.
SceneMeshPy addSceneMesh(const std::shared_ptr<ScenePy>& s, const sss::Mesh& mesh, const std::optional<glm::mat4>& model,
                         const sss::MeshRenderOptions& options, const std::optional<sss::BlinnPhongMaterial>& material,
                         const std::optional<sss::ScatteringMaterial>& scattering) {
    SceneMeshInfo info{mesh.positions(), model.value_or(glm::mat4(1.0f)), material.value_or(sss::BlinnPhongMaterial{}),
                       scattering.value_or(sss::ScatteringMaterial{})};
    if (material) sss::validate(*material);
    if (scattering) scattering->validate();
    sss::MeshScatteringRenderer& r = s->get().addMesh(mesh, info.model, options);
    r.setMaterial(info.material);
    r.setScatteringMaterial(info.scatteringMaterial);
    s->meshes.push_back(std::move(info));
    return SceneMeshPy{{s, s->meshes.size() - 1, s->generation}};
}

void bindScene(py::module_& m) {
    py::class_<SceneMeshPy> sceneMesh(m, "SceneMesh", "A mesh of a Scene (valid until Scene.clear()).");
    sceneMesh.def_property("model", [](SceneMeshPy& w) { w.check(); return w.info().model; },
                           [](SceneMeshPy& w, const glm::mat4& model) {
                               w.check();
                               w.scene->get().setMeshTransform(w.index, model);
                               w.info().model = model;
                           });
    meshProperties<SceneMeshPy>(sceneMesh, [](SceneMeshPy& w) -> sss::BlinnPhongMaterial& { w.check(); return w.info().material; },
                                [](SceneMeshPy& w) -> sss::ScatteringMaterial& { w.check(); return w.info().scatteringMaterial; });

    py::class_<SceneVolumePy> sceneVolume(m, "SceneVolume", "A volume of a Scene (valid until Scene.clear()).");
    sceneVolume.def_property("model", [](SceneVolumePy& w) { w.check(); return w.info().model; },
                             [](SceneVolumePy& w, const glm::mat4& model) {
                                 w.get().setModelTransform(model);
                                 w.info().model = model;
                             });
    volumeProperties<SceneVolumePy>(sceneVolume, [](SceneVolumePy& w) -> sss::TransferFunction& { w.check(); return w.info().transferFunction; });

    py::class_<ScenePy, std::shared_ptr<ScenePy>>(m, "Scene",
                                                  "Meshes and volumes rendered together with depth and shadows "
                                                  "(sss::HybridCompositor).")
        .def(py::init([](const py::object& options, const py::object& context, const py::kwargs& kw) {
                 return std::make_shared<ScenePy>(contextFrom(context), optionsFrom<sss::HybridOptions>(options, kw));
             }),
             py::arg("options") = py::none(), py::kw_only(), py::arg("context") = py::none(),
             "HybridOptions as `options` and/or as keyword arguments (Scene(cornell_box=True)).")
        .def("add_mesh",
             [](const std::shared_ptr<ScenePy>& s, const sss::Mesh& mesh, const std::optional<glm::mat4>& model,
                const py::object& options, const std::optional<sss::BlinnPhongMaterial>& material,
                const std::optional<sss::ScatteringMaterial>& scattering, const py::kwargs& kw) {
                 return addSceneMesh(s, mesh, model, optionsFrom<sss::MeshRenderOptions>(options, kw), material, scattering);
             },
             py::arg("mesh"), py::arg("model") = py::none(), py::arg("options") = py::none(), py::kw_only(),
             py::arg("material") = py::none(), py::arg("scattering_material") = py::none(),
             "Adds a mesh; MeshRenderOptions as `options` and/or keyword arguments. Returns its SceneMesh.")
        .def("add_isosurface",
             [](const std::shared_ptr<ScenePy>& s, const sss::Volume& volume, double value,
                const std::optional<glm::mat4>& model, const py::object& options,
                const std::optional<sss::BlinnPhongMaterial>& material,
                const std::optional<sss::ScatteringMaterial>& scattering, int smoothingIterations, int maxTriangles,
                double millimetresPerVolumeUnit, const py::kwargs& kw) {
                 sss::WorldIsosurface surface = sss::extractIsosurfaceInWorldBox(
                     volume, {value, smoothingIterations, maxTriangles}, millimetresPerVolumeUnit);
                 sss::MeshRenderOptions o = optionsFrom<sss::MeshRenderOptions>(options, kw);
                 o.millimetresPerUnit = surface.millimetresPerUnit;
                 return addSceneMesh(s, surface.mesh, model, o, material, scattering);
             },
             py::arg("volume"), py::arg("value"), py::arg("model") = py::none(), py::arg("options") = py::none(),
             py::kw_only(), py::arg("material") = py::none(), py::arg("scattering_material") = py::none(),
             py::arg("smoothing_iterations") = 15, py::arg("max_triangles") = 0,
             py::arg("millimetres_per_volume_unit") = 1.0,
             "Adds the surface where the volume's data cross `value` as a mesh where the volume lies under the same "
             "`model`, at its physical size (millimetres_per_unit from the volume's spacing, in "
             "millimetres_per_volume_unit mm); MeshRenderOptions as `options` and/or keyword arguments. Returns its "
             "SceneMesh.")
        .def("add_volume",
             [](const std::shared_ptr<ScenePy>& s, const sss::Volume& volume, const std::optional<glm::mat4>& model,
                const py::object& options, const std::optional<sss::TransferFunction>& tf, const py::kwargs& kw) {
                 const sss::VolumeRenderOptions o = optionsFrom<sss::VolumeRenderOptions>(options, kw);
                 SceneVolumeInfo info{volume.worldBounds(), model.value_or(glm::mat4(1.0f)), tf.value_or(sss::TransferFunction{})};
                 sss::VolumeScatteringRenderer& r = s->get().addVolume(volume, info.model, o);
                 r.setTransferFunction(info.transferFunction);
                 s->volumes.push_back(std::move(info));
                 return SceneVolumePy{{s, s->volumes.size() - 1, s->generation}};
             },
             py::arg("volume"), py::arg("model") = py::none(), py::arg("options") = py::none(), py::kw_only(),
             py::arg("transfer_function") = py::none(),
             "Adds a volume; VolumeRenderOptions as `options` and/or keyword arguments. Returns its SceneVolume.")
        .def_property_readonly("meshes", [](const std::shared_ptr<ScenePy>& s) {
            std::vector<SceneMeshPy> out;
            for (std::size_t i = 0; i < s->meshes.size(); ++i) out.push_back({{s, i, s->generation}});
            return out;
        })
        .def_property_readonly("volumes", [](const std::shared_ptr<ScenePy>& s) {
            std::vector<SceneVolumePy> out;
            for (std::size_t i = 0; i < s->volumes.size(); ++i) out.push_back({{s, i, s->generation}});
            return out;
        })
        .def("clear", [](ScenePy& s) {
            s.get().clear();
            s.meshes.clear();
            s.volumes.clear();
            ++s.generation;
        }, "Removes every mesh and volume.")
        .def_property("lights", [](ScenePy& s) { return s.get().lights(); },
                      [](ScenePy& s, std::vector<sss::Light> lights) { s.get().setLights(std::move(lights)); },
                      "list of DirectionalLight, PointLight, SpotLight shared by everything (at most 8)")
        .def_property("options", [](ScenePy& s) { return s.get().options(); },
                      [](ScenePy& s, const sss::HybridOptions& o) { s.get().setOptions(o); }, "HybridOptions")
        .def_property_readonly("bounds", [](ScenePy& s) { return s.get().bounds(); })
        .def_property_readonly("stats", [](ScenePy& s) { return statsDict(s.get().stats()); })
        .def("render",
             [](ScenePy& s, const std::optional<sss::Camera>& camera, int width, int height, int antialias, int frames,
                bool converge) {
                 sss::HybridCompositor& c = s.get();
                 sss::Camera cam;
                 if (camera) cam = *camera;
                 else if (c.options().cornellBox && (c.meshCount() || c.volumeCount()))
                     cam = autoCamera(boxCorners(sss::makeCornellBox(c.bounds()).bounds), width, height, true);
                 else cam = autoCamera(s.framingPoints(), width, height);
                 auto draw = [&c](const sss::Camera& cm, sss::RenderTarget& t) { c.render(cm, t); };
                 auto converged = [&c] {
                     for (std::size_t i = 0; i < c.meshCount(); ++i)
                         if (c.mesh(i).options().shading == sss::MeshShading::Scattering && !c.mesh(i).converged()) return false;
                     return true;
                 };
                 bool progressive = false;
                 for (std::size_t i = 0; i < c.volumeCount(); ++i) progressive = progressive || c.volume(i).options().multipleScattering;
                 return renderPicture(*s.context, cam, {width, height, antialias, frames, converge}, draw, converged, progressive);
             },
             py::arg("camera") = py::none(), py::kw_only(), py::arg("width") = 640, py::arg("height") = 480,
             py::arg("antialias") = 1, py::arg("frames") = 1, py::arg("converge") = true, kRenderDoc);
}

}  // namespace

ContextPtr defaultContext() {
    if (!g_defaultContext) g_defaultContext = makeContext(sss::EglPlatform::Auto, false, false);
    return g_defaultContext;
}

void releaseDefaultContext() { g_defaultContext.reset(); }

ContextPtr contextFrom(const py::object& context) {
    if (context.is_none()) return defaultContext();
    if (!py::isinstance<ContextHolder>(context)) throw py::type_error("context must be an sss.Context or None");
    return context.cast<ContextPtr>();
}

void bindRender(py::module_& m) {
    bindContext(m);
    bindOptions(m);
    bindRenderers(m);
    bindScene(m);
}

}  // namespace ssspy
