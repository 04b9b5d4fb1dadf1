// The scattering-off baselines: what the thesis compares its scattering times against.

#include "bench.h"

#include <algorithm>
#include <iostream>

namespace {

constexpr const char* kTable = "baseline";

// A mesh is either a file below the data directory or a procedural generator; both go through
// the same measurement code, which is what lets --quick test the full run's path.
struct MeshCase {
    std::string model;
    std::filesystem::path file;             // relative to the data directory; empty = procedural
    std::function<sss::Mesh()> procedural;  // used when file is empty
    std::string source;                     // shown in the JSON
    std::optional<double> thesisBlinnPhongMs;
};

struct VolumeCase {
    std::string model;
    std::filesystem::path file;
    sss::RawLoadOptions rawOptions;
    std::function<sss::Volume()> procedural;
    std::string source;
    std::string preset;  // TransferFunction::preset name
    std::optional<double> thesisEaMs;
    std::optional<double> thesisGradientMs;
};

// Thesis GTX 660 numbers: Table 5.3 "Blinn-Phong" column and Table 5.4 EA / EA + gradient.
std::vector<MeshCase> fullMeshCases() {
    return {
        {"bunny", "meshes/stanford-bunny.obj", {}, "", 0.87},
        {"dragon", "meshes/dragon_50k.obj", {}, "", 0.93},
        {"buddha", "meshes/happy_buddha_50k.obj", {}, "", 1.08},
        // The largest mesh we have; the thesis's large model (Hebe, 412k tri) is not available.
        {"dragon-vrip", "meshes/dragon_vrip_res2.obj", {}, "", std::nullopt},
        {"sphere", "", [] { return sss::makeUvSphere(); }, "procedural: makeUvSphere(20, 20)", 0.79},
    };
}

std::vector<VolumeCase> fullVolumeCases() {
    sss::RawLoadOptions ctSpacing;
    ctSpacing.spacing = glm::vec3(0.957f, 0.957f, 1.5f);  // mm, from the data manifest
    return {
        {"bucky", "volumes/bucky_32x32x32_uint8.raw", {}, {}, "", "bucky", 1.31, 1.61},
        {"bonsai", "volumes/bonsai_256x256x256_uint8.raw", {}, {}, "", "bonsai", 3.05, 9.49},
        {"engine", "volumes/engine_256x256x256_uint8.raw", {}, {}, "", "engine", 2.81, 8.88},
        {"cthead", "volumes/invesalius_cthead_256x256x108_uint8.raw", ctSpacing, {}, "", "ct-skin", std::nullopt,
         std::nullopt},
    };
}

std::vector<MeshCase> quickMeshCases() {
    return {
        {"sphere", "", [] { return sss::makeUvSphere(); }, "procedural: makeUvSphere(20, 20)", 0.79},
        {"torus", "", [] { return sss::makeTorus(); }, "procedural: makeTorus()", std::nullopt},
    };
}

std::vector<VolumeCase> quickVolumeCases() {
    return {
        {"blobs", "", {}, [] { return sss::makeBlobsVolume(40); }, "procedural: makeBlobsVolume(40)", "ramp",
         std::nullopt, std::nullopt},
    };
}

// Thesis numbers are for its 1200 x 680 viewport only; elsewhere they would mislead.
std::optional<double> thesisIfComparable(const BenchmarkContext& bench, std::optional<double> ms) {
    const Options& o = bench.options();
    return o.width == kThesisWidth && o.height == kThesisHeight ? ms : std::nullopt;
}

sss::TransferFunction presetOrRamp(const std::string& name) {
    const std::vector<std::string> names = sss::TransferFunction::presetNames();
    if (std::find(names.begin(), names.end(), name) != names.end()) return sss::TransferFunction::preset(name);
    std::cerr << "sss-bench: transfer-function preset \"" << name << "\" does not exist; using \"ramp\"\n";
    return sss::TransferFunction::preset("ramp");
}

void runMesh(BenchmarkContext& bench, const MeshCase& c) {
    std::string source = c.source;
    std::optional<sss::Mesh> mesh;
    if (c.file.empty()) {
        mesh = c.procedural();
    } else {
        const auto path = bench.findData(kTable, c.model, c.file);
        if (!path) return;
        mesh = sss::Mesh::load(*path);
        source = c.file.generic_string();
    }

    const sss::Camera camera = framedCamera(mesh->bounds());
    sss::MeshScatteringRenderer renderer({.shading = sss::MeshShading::BlinnPhong});
    renderer.setMesh(*mesh);
    renderer.setLights({keyLight(camera)});

    Record r;
    r.table = kTable;
    r.model = c.model;
    r.mode = "blinn-phong";
    r.dataSize = std::to_string(mesh->vertexCount()) + " v / " + std::to_string(mesh->triangleCount()) + " tri";
    r.width = bench.options().width;
    r.height = bench.options().height;
    r.measurement = bench.measure([&](sss::RenderTarget& target) { renderer.render(camera, target); },
                                  r.table + "-" + r.model + "-" + r.mode);
    r.details = {{"vertices", mesh->vertexCount()}, {"triangles", mesh->triangleCount()}, {"source", source}};
    r.thesisMs = thesisIfComparable(bench, c.thesisBlinnPhongMs);
    bench.addRecord(std::move(r));
}

void runVolume(BenchmarkContext& bench, const VolumeCase& c) {
    std::string source = c.source;
    std::optional<sss::Volume> volume;
    if (c.file.empty()) {
        volume = c.procedural();
    } else {
        const auto path = bench.findData(kTable, c.model, c.file);
        if (!path) return;
        volume = sss::Volume::loadRaw(*path, c.rawOptions);
        source = c.file.generic_string();
    }

    const sss::Camera camera = framedCamera(volume->worldBounds());
    sss::VolumeScatteringRenderer renderer;
    renderer.setVolume(*volume);
    renderer.setTransferFunction(presetOrRamp(c.preset));
    renderer.setLights({keyLight(camera)});

    const glm::ivec3 d = volume->dims();
    const glm::vec3 sp = volume->spacing();
    struct ModeCase {
        sss::VolumeShading shading;
        const char* name;
        std::optional<double> thesisMs;
    };
    for (const ModeCase& m : {ModeCase{sss::VolumeShading::EmissionAbsorption, "emission-absorption", c.thesisEaMs},
                              ModeCase{sss::VolumeShading::Gradient, "gradient", c.thesisGradientMs}}) {
        // The thesis's ray casting (step 1 voxel, post-classification), library defaults
        // otherwise (early termination 0.99, jitter), so the rows compare with the thesis's.
        const sss::VolumeRenderOptions options = thesisVolumeOptions(bench.options(), m.shading);
        renderer.setOptions(options);

        Record r;
        r.table = kTable;
        r.model = c.model;
        r.mode = m.name;
        r.dataSize = dimsText(d);
        r.params = "tf=" + c.preset;
        r.width = bench.options().width;
        r.height = bench.options().height;
        r.measurement = bench.measure([&](sss::RenderTarget& target) { renderer.render(camera, target); },
                                      r.table + "-" + r.model + "-" + r.mode);
        r.details = {{"dims", {d.x, d.y, d.z}},
                     {"spacing", {sp.x, sp.y, sp.z}},
                     {"transfer_function", c.preset},
                     {"step_voxels", options.stepSize},
                     {"early_termination", options.earlyTermination},
                     {"source", source}};
        r.thesisMs = thesisIfComparable(bench, m.thesisMs);
        bench.addRecord(std::move(r));
    }
}

}  // namespace

void runBaselineTable(BenchmarkContext& bench) {
    const bool quick = bench.options().quick;
    for (const MeshCase& c : quick ? quickMeshCases() : fullMeshCases())
        if (bench.wanted(c.model)) runMesh(bench, c);
    for (const VolumeCase& c : quick ? quickVolumeCases() : fullVolumeCases())
        if (bench.wanted(c.model)) runVolume(bench, c);
}
