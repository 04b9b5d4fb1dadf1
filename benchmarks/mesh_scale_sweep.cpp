// Translucency at every scale (sss-bench --error-sweep mesh): the real meshes at 2 cm, 20 cm and
// 2 m largest extent, in marble and in skin1, each method at its defaults against the CPU
// reference. The same mesh file at a hundred times the size has triangles a hundred times as
// many diffusion lengths wide: the regime of life-size statues and skin.

#include "bench.h"
#include "plot.h"
#include "sss/procedural.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <fstream>
#include <iostream>

namespace {

constexpr int kWidth = 400, kHeight = 226;
// The references' per-pixel target (standard error / mean). At 3 % their own relRMSE was
// 2.1-2.5 %, which added about a point to every measured error.
constexpr double kReferenceTarget = 0.01;

// The mesh centred with its largest extent 1 unit, so millimetres per unit is its size in mm.
std::optional<sss::Mesh> unitMesh(BenchmarkContext& bench, const std::string& model) {
    std::optional<sss::Mesh> mesh = loadThesisMesh(bench, "error-sweep", model);
    if (!mesh) return std::nullopt;
    const sss::Bounds b = mesh->bounds();
    const glm::vec3 extent = b.max - b.min;
    const float scale = 1.0f / std::max({extent.x, extent.y, extent.z, 1e-9f});
    return mesh->transformed(glm::scale(glm::mat4(1.0f), glm::vec3(scale)) *
                             glm::translate(glm::mat4(1.0f), -b.center()));
}

struct Reference {
    sss::Image image{1, 1};
    sss::Image standardError{1, 1};  // per pixel (MeshReferenceResult::standardError)
    double ownRelRmse = 0.0;         // the reference's own expected relRMSE (MeshReferenceResult)
};

// The reference, kept in --reference-cache with its standard errors and own error estimate beside it.
Reference cachedMeshReference(const Options& o, const std::string& name,
                              const std::function<sss::MeshReferenceResult()>& render) {
    const std::filesystem::path image = o.referenceCache / (name + ".exr"),
                                standardError = o.referenceCache / (name + "-standard-error.exr"),
                                estimate = o.referenceCache / (name + ".txt");
    std::error_code ec;
    if (!o.referenceCache.empty() && std::filesystem::is_regular_file(image, ec) &&
        std::filesystem::is_regular_file(standardError, ec) && std::filesystem::is_regular_file(estimate, ec)) {
        Reference cached{sss::Image::loadExr(image), sss::Image::loadExr(standardError)};
        std::ifstream(estimate) >> cached.ownRelRmse;
        return cached;
    }
    const auto start = std::chrono::steady_clock::now();
    const sss::MeshReferenceResult result = render();
    std::cerr << "sss-bench: reference " << name << " in "
              << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
              << " s, its own relRMSE ~" << result.relativeRmseEstimate << "\n";
    if (!o.referenceCache.empty()) {
        std::filesystem::create_directories(o.referenceCache);
        result.image.saveExr(image);
        result.standardError.saveExr(standardError);
        std::ofstream(estimate) << result.relativeRmseEstimate << "\n";
    }
    return {result.image, result.standardError, result.relativeRmseEstimate};
}

struct Method {
    std::string name;
    std::function<void(sss::MeshRenderOptions&)> set;
};

const std::vector<Method>& methods() {
    static const std::vector<Method> all = {
        {"defaults", [](sss::MeshRenderOptions&) {}},
        // The vertex estimate with its near field (docs/near-field.md).
        {"near-field",
         [](sss::MeshRenderOptions& o) {
             o.combine = sss::MeshCombine::VertexEstimate;
             o.nearField = 1.0f;
         }},
        // The near field where it is evaluated (defaults: points 2 light-buffer texels apart,
        // once per light change): at every pixel of every frame, or at points 1 or 4 texels apart.
        {"near-field-per-pixel", [](sss::MeshRenderOptions& o) { o.nearFieldSpacing = 0.0f; }},
        {"near-field-points-1", [](sss::MeshRenderOptions& o) { o.nearFieldSpacing = 1.0f; }},
        {"near-field-points-4", [](sss::MeshRenderOptions& o) { o.nearFieldSpacing = 4.0f; }},
        // The vertex estimate without the near field: the previous defaults below 2
        // diffusion lengths per edge.
        {"vertex-estimate-no-near-field",
         [](sss::MeshRenderOptions& o) {
             o.combine = sss::MeshCombine::VertexEstimate;
             o.nearField = 0.0f;
         }},
        // The paper's maps (K 8, N 24): the previous defaults above 2 diffusion lengths.
        {"maps", [](sss::MeshRenderOptions& o) { o.combine = sss::MeshCombine::PerPixel; }},
    };
    return all;
}

std::string combineName(sss::MeshCombine c) {
    switch (c) {
        case sss::MeshCombine::PerPixel: return "maps";
        case sss::MeshCombine::PerVertex: return "per-vertex";
        case sss::MeshCombine::VertexEstimate: return "vertex-estimate";
        default: return "automatic";
    }
}

// Mean brightness of `image` over the reference's covered pixels, relative to the reference's.
double meanRatio(const sss::Image& image, const sss::Image& reference) {
    double sum = 0.0, referenceSum = 0.0;
    for (int y = 0; y < reference.height(); ++y)
        for (int x = 0; x < reference.width(); ++x) {
            if (!(reference.at(x, y).a > 0.0f)) continue;
            const glm::vec4 t = image.at(x, y), r = reference.at(x, y);
            sum += t.r + t.g + t.b;
            referenceSum += r.r + r.g + r.b;
        }
    return referenceSum > 0.0 ? sum / referenceSum : 0.0;
}

void saveImages(const Options& o, const std::string& id, const sss::Image& image, const sss::Image& reference,
                const std::string& referenceId) {
    if (o.imageDir.empty()) return;
    std::filesystem::create_directories(o.imageDir);
    sss::toDisplay(image).savePng(o.imageDir / (id + ".png"));
    image.saveExr(o.imageDir / (id + ".exr"));
    sss::toDisplay(reference).savePng(o.imageDir / (referenceId + ".png"));
}

// The CT head's skin at its real size: the isosurface at -500 HU (between air and soft tissue)
// of the InVesalius head, decimated to 100 000 triangles, in millimetres.
std::optional<sss::Mesh> headSkin(BenchmarkContext& bench) {
    const auto path = bench.findData("error-sweep", "head", "volumes/invesalius_cthead_256x256x108_uint16.raw");
    if (!path) return std::nullopt;
    sss::RawLoadOptions raw;
    raw.spacing = glm::vec3(0.957f, 0.957f, 1.5f);  // mm, from the data manifest
    const sss::Volume volume = sss::Volume::loadRaw(*path, raw);
    sss::IsosurfaceOptions iso;
    iso.value = 1024.0 - 500.0;  // stored as HU + 1024
    iso.maxTriangles = 100000;
    return sss::extractIsosurface(volume, iso);
}

struct SweepScene {
    std::string model, material;
    const sss::Mesh* mesh;
    double sizeMm;            // the mesh's largest extent in millimetres
    double millimetresPerUnit;
};

// The method "second-reference", only when --only lists it: the reference again from other random
// streams, against the first. Its relRMSE and specks are what the references' own noise puts into
// every method's numbers (a perfect renderer would measure as much).
bool secondReferenceWanted(const Options& o) {
    return std::find(o.only.begin(), o.only.end(), "second-reference") != o.only.end();
}

// The record of `method`'s image of scene `s` against its reference: error, specks and `ms`
// (what it took to make). The methods add their own fields (combine, timings).
Record sweepRecord(const SweepScene& s, const std::string& method, const sss::Image& image,
                   const Reference& reference, double ms) {
    const sss::ErrorMetrics error = sss::computeErrorMetrics(image, reference.image);
    Record r;
    r.table = "error-sweep";
    r.model = s.model;
    r.mode = "sss";
    r.dataSize = std::to_string(s.mesh->triangleCount()) + " tri";
    r.params = method + " " + s.material + " " + std::to_string(static_cast<int>(s.sizeMm)) +
               " mm relRMSE=" + std::to_string(error.relRmse);
    r.width = kWidth;
    r.height = kHeight;
    r.details = {{"sweep", "mesh-scale"},
                 {"model", s.model},
                 {"size_mm", s.sizeMm},
                 {"millimetres_per_unit", s.millimetresPerUnit},
                 {"material", s.material},
                 {"method", method},
                 {"rel_rmse", error.relRmse},
                 {"specks", sss::resolvedSpeckShare(image, reference.image, reference.standardError)},
                 {"specks_all", error.speckShare},
                 {"specks_visible", error.visibleSpeckShare},
                 {"mean_ratio", meanRatio(image, reference.image)},
                 {"ms", ms},
                 {"reference_rel_rmse", reference.ownRelRmse}};
    return r;
}

void compareSecondReference(BenchmarkContext& bench, const SweepScene& s, const std::string& scene,
                            const std::string& referenceName, const Reference& reference,
                            const std::function<sss::MeshReferenceResult()>& render) {
    const auto start = std::chrono::steady_clock::now();
    const Reference second = cachedMeshReference(bench.options(), referenceName + "-seed2", render);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    Record r = sweepRecord(s, "second-reference", second.image, reference, ms);
    std::cerr << "sss-bench: " << scene << " second-reference relRMSE " << r.details["rel_rmse"] << " specks "
              << r.details["specks"] << " (all " << r.details["specks_all"] << ", visible "
              << r.details["specks_visible"] << ")\n";
    bench.addRecord(std::move(r));
}

}  // namespace

// Besides model names, --only takes scene names (buddha-marble-2000mm) and method names (maps):
// a scene runs if its model or its name is listed, a method if it is listed or no method is.
bool namesScene(const Options& o, const std::string& model) {
    return std::any_of(o.only.begin(), o.only.end(), [&](const std::string& n) { return n.rfind(model + "-", 0) == 0; });
}

bool methodWanted(BenchmarkContext& bench, const std::string& method) {
    const auto& only = bench.options().only;
    const bool anyListed = secondReferenceWanted(bench.options()) ||
                           std::any_of(methods().begin(), methods().end(), [&](const Method& m) {
                               return std::find(only.begin(), only.end(), m.name) != only.end();
                           });
    return !anyListed || std::find(only.begin(), only.end(), method) != only.end();
}

void meshScaleSweep(BenchmarkContext& bench, PlotSpec* plot) {
    const Options& o = bench.options();
    std::vector<std::pair<std::string, sss::Mesh>> meshes;
    for (const std::string model : {"bunny", "buddha", "dragon"})
        if (bench.wanted(model) || namesScene(o, model))
            if (std::optional<sss::Mesh> mesh = unitMesh(bench, model)) meshes.emplace_back(model, std::move(*mesh));
    // A sphere (64 x 32 quads), only when --only names it: the terminator without folds or cast
    // shadows, where the near field's rings are checked against the reference.
    if (namesScene(o, "sphere") || std::find(o.only.begin(), o.only.end(), "sphere") != o.only.end())
        meshes.emplace_back("sphere", sss::makeUvSphere(64, 32, 0.5f));
    std::optional<sss::Mesh> head;
    if (bench.wanted("head") || namesScene(o, "head")) head = headSkin(bench);
    std::vector<SweepScene> scenes;
    for (const auto& [model, mesh] : meshes)
        for (const std::string material : {"marble", "skin1"})
            for (const double sizeMm : {20.0, 200.0, 2000.0}) scenes.push_back({model, material, &mesh, sizeMm, sizeMm});
    if (head) {
        const glm::vec3 extent = head->bounds().max - head->bounds().min;
        scenes.push_back({"head", "skin1", &*head, std::max({extent.x, extent.y, extent.z}), 1.0});
    }
    std::vector<PlotSeries> series;  // per method: (regeneration ms, relRMSE) of every scene
    for (const Method& method : methods())
        series.push_back({method.name, {}, kPlotPalette[series.size() % std::size(kPlotPalette)], false});
    for (const SweepScene& s : scenes) {
        const sss::Mesh& mesh = *s.mesh;
        const sss::Camera camera = framedCamera(mesh.bounds());
        const sss::DirectionalLight key = keyLight(camera);
        const sss::ScatteringMaterial material = sss::materialPreset(s.material);
        const std::string scene = s.model + "-" + s.material + "-" + std::to_string(static_cast<int>(s.sizeMm)) + "mm";
        if (!bench.wanted(s.model) && !bench.wanted(scene)) continue;
        const std::string referenceName =
            "mesh-scale-reference-" + scene + "-target" + std::to_string(static_cast<int>(kReferenceTarget * 1000)) +
            "permille-" + viewAndLightTag(camera, key);
        auto renderReference = [&](std::uint64_t seed) {
            sss::MeshReferenceOptions ro;
            ro.millimetresPerUnit = s.millimetresPerUnit;
            ro.targetRelativeError = kReferenceTarget;
            ro.absoluteError = 1e-4;
            ro.seed = seed;
            return sss::renderMeshReference(mesh, glm::mat4(1.0f), material, {key}, camera, kWidth, kHeight, ro);
        };
        const Reference reference = cachedMeshReference(o, referenceName, [&] { return renderReference(1); });
        if (secondReferenceWanted(o))
            compareSecondReference(bench, s, scene, referenceName, reference, [&] { return renderReference(2); });
        // The baseline of the fixed frames' cost, timed next to each of them (this machine is noisy).
        sss::MeshScatteringRenderer blinnPhong;
        blinnPhong.setMesh(mesh);
        blinnPhong.setLights({key});
        for (std::size_t m = 0; m < methods().size(); ++m) {
            const Method& method = methods()[m];
            if (!methodWanted(bench, method.name)) continue;
            sss::MeshRenderOptions mo;
            mo.shading = sss::MeshShading::Scattering;
            mo.millimetresPerUnit = s.millimetresPerUnit;
            mo.specular = 0.0f;
            method.set(mo);
            sss::MeshScatteringRenderer renderer(mo);
            renderer.setMesh(mesh);
            renderer.setScatteringMaterial(material);
            renderer.setLights({key});
            sss::RenderTarget target(kWidth, kHeight);
            const double regenerateMs = renderUntilConverged(renderer, camera, target);
            const sss::Image image = target.readColor();
            const std::string id = "scale-" + scene + "-" + method.name;
            saveImages(o, id, image, reference.image, "scale-" + scene + "-reference");
            // Side by side, frame for frame: the ratio is the goal (this machine's speed drifts).
            const std::vector<Measurement> timed =
                bench.measureInterleaved({[&](sss::RenderTarget& t) { renderer.render(camera, t); },
                                          [&](sss::RenderTarget& t) { blinnPhong.render(camera, t); }},
                                         {id + "-fixed", id + "-blinn-phong"});
            const Measurement& fixed = timed[0];
            const Measurement& baseline = timed[1];
            Record r = sweepRecord(s, method.name, image, reference, regenerateMs);
            r.measurement = fixed;
            r.details["combine"] = combineName(renderer.activeCombine());
            r.details["near_field"] = mo.nearField;
            r.details["edge_diffusion_lengths"] = renderer.edgeToDiffusionLength();
            r.details["fixed_ms"] = fixed.stats.medianMs;
            r.details["blinn_phong_ms"] = baseline.stats.medianMs;
            r.details["fixed_over_blinn_phong"] = fixed.stats.medianMs / baseline.stats.medianMs;
            std::cerr << "sss-bench: " << scene << " " << method.name << " (" << combineName(renderer.activeCombine())
                      << ", edges " << renderer.edgeToDiffusionLength() << " diffusion lengths) relRMSE "
                      << r.details["rel_rmse"] << " specks " << r.details["specks"] << " (all "
                      << r.details["specks_all"] << ") regenerated in " << regenerateMs << " ms\n";
            series[m].points.emplace_back(regenerateMs, r.details["rel_rmse"].get<double>());
            bench.addRecord(std::move(r));
        }
    }
    if (plot)
        for (PlotSeries& line : series)
            if (!line.points.empty()) plot->series.push_back(std::move(line));
}
