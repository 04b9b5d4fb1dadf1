// sss-bench: times libsss renderers the way the thesis did (chapter 5) and writes JSON + Markdown.
// Exit codes: 0 success, 1 a measurement failed (error, empty image), 2 bad command line.

#include "accuracy.h"
#include "bench.h"
#include "plot.h"

#include "common/cli_options.h"

#include <sss/scene.h>

#include <charconv>
#include <cstdlib>
#include <fstream>
#include <iostream>

namespace {

using namespace examples;

constexpr const char* kDescription = R"(usage: sss-bench [options]

Times the libsss renderers (median of several frames, after warm-up frames) and writes
the results as JSON and as a Markdown table (also printed to stdout): the thesis's tables,
time against error, accuracy against physical ground truth, or the frames of a scene file.
)";

/// Checks a choice from a fixed list, naming the option.
std::string oneOf(const std::string& option, const std::string& value, std::initializer_list<const char*> choices) {
    std::string list;
    for (const char* c : choices) {
        if (value == c) return value;
        list += (list.empty() ? "" : ", ") + std::string(c);
    }
    throw UsageError(option + ": expected " + list + ", got \"" + value + "\"");
}

std::vector<std::string> splitList(const std::string& text) {
    std::vector<std::string> out;
    for (const std::string& part : split(text, ','))
        if (!part.empty()) out.push_back(part);
    return out;
}

Options parseArgs(int argc, char** argv) {
    Options o;
    CLI::App app(kDescription, "sss-bench");
    std::string dataDir;
    int runs = o.runs, warmup = o.warmup, width = kThesisWidth, height = kThesisHeight;
    app.add_flag("--quick", o.quick, "procedural data only, small viewport, 1 warm-up + 3 runs (for ctest)");
    app.add_flag("--gl-info", o.glInfoOnly,
                 "print the GL vendor, renderer and version and the timing method (one \"key: value\" per line), "
                 "then exit; benchmarks/run-gpu.sh checks with it that the EGL device is the GPU it means to measure");
    addParsed(app, "--json", o.jsonPath,
              [](const std::string& name, const std::string& text) {
                  if (text.empty()) throw UsageError(name + " needs a non-empty value");
                  return std::optional<std::filesystem::path>(text);
              },
              "write the results as JSON to FILE", "FILE")
        ->group("output");
    addParsed(app, "--markdown", o.markdownPath,
              [](const std::string&, const std::string& text) { return std::optional<std::filesystem::path>(text); },
              "write the Markdown table to FILE (default: the JSON path with .md)", "FILE")
        ->group("output");
    addDataDirOption(app, dataDir);
    addSceneOption(app, o.scene, "time the frames of this scene file (\"change\": its lights turn, \"fixed\": "
                                 "nothing changes) instead of the tables; its output size unless --size");
    addParsed(app, "--runs", runs,
              [](const std::string& name, const std::string& text) {
                  const int n = parseInt(name, text);
                  if (n < 1) throw UsageError(name + " expects an integer >= 1, got \"" + text + "\"");
                  return n;
              },
              "timed frames per row", "N", "10; quick 3");
    addParsed(app, "--warmup", warmup,
              [](const std::string& name, const std::string& text) {
                  const int n = parseInt(name, text);
                  if (n < 0) throw UsageError(name + " expects an integer >= 0, got \"" + text + "\"");
                  return n;
              },
              "untimed frames before timing", "N", "3; quick 1");
    addSizeOption(app, width, height, "viewport")->default_str("1200x680, the thesis viewport; quick 320x180; sweeps 128x96");
    addParsed(app, "--only", o.only,
              [](const std::string& name, const std::string& text) {
                  auto models = splitList(text);
                  if (models.empty()) throw UsageError(name + " needs at least one model name");
                  return models;
              },
              "only these models (e.g. bunny,bonsai); --error-sweep mesh also takes its scenes and methods "
              "(buddha-marble-2000mm, head-skin1-241mm, defaults, maps)", "A,B,...");
    app.add_option("--note", o.note, "free text about the machine, copied into the reports")->type_name("TEXT");
    app.add_option("--images", o.imageDir, "save each row's verified image as DIR/<table>-<model>-<mode>.png")
        ->type_name("DIR")
        ->group("output");
    addParsed(app, "--table", o.tables,
              [](const std::string& name, const std::string& text) {
                  std::vector<std::string> tables;
                  for (const std::string& t : splitList(text)) {
                      if (t != "baseline" && t != "5.3" && t != "5.4" && t != "5.5" && t != "casters" && t != "scaling" &&
                          t != "clear" && t != "textured" && t != "light-sweep")
                          throw UsageError(name + ": unknown table \"" + t +
                                           "\" (baseline, 5.3, 5.4, 5.5, casters, scaling, clear, textured, light-sweep)");
                      tables.push_back(t);
                  }
                  return tables;
              },
              "thesis tables to reproduce: baseline (default), 5.3 (mesh scattering), 5.4 (volume scattering), 5.5 "
              "(hybrid scenes); casters: fragment against compute ray casting side by side; scaling: time against "
              "viewport size and ray step, with the fixed and per-pixel costs fitted; clear: the ways to clear a target; "
              "textured: a textured translucent mesh against the same mesh untextured; light-sweep: the light-volume rebuild "
              "against the slices each dispatch advances (1-16) and by ray doubling, with its dispatches",
              "T[,T...]");
    addEnum(app, "--ray-caster", o.rayCaster, "the ray caster of every volume row (casters: both)");
    addEnum(app, "--light-propagation", o.lightPropagation,
            "how the volume rows' light volumes are propagated (light-sweep: every way side by side)");
    addEnum(app, "--volume-model", o.volumeModel,
            "the shading model of the thesis tables' volume rows: paper (the thesis) or physical (its light volume "
            "carries the intensity alone, one lookup per voxel instead of nine)");
    app.add_flag("--passes", o.passes,
                 "GL timestamps around each pass (non-blocking): tables 5.3 and 5.4 add one record per pass and frame "
                 "(change, fixed) with pass, gpu_ms and cpu_ms, means over the timed frames");
    addParsed(app, "--error-sweep", o.errorSweep,
              [](const std::string& name, const std::string& text) {
                  return std::optional(oneOf(name, text, {"mesh", "volume"}));
              },
              "time against error for S = mesh or volume, against the CPU reference; records with sweep, the swept "
              "parameters, ms and rel_rmse, and a plot",
              "S");
    addParsed(app, "--accuracy", o.accuracy,
              [](const std::string& name, const std::string& text) {
                  return std::optional(oneOf(name, text, {"slab", "mesh", "volume", "light-volume", "surfaces"}));
              },
              "accuracy against physical ground truth. A = slab: presets x channels x incidence 0/45/75 degrees, the "
              "random walk against the dipole, the calibrated profile and a GPU render (JSON records with material, "
              "channel, incidence_deg, random_walk, random_walk_stderr, dipole, calibrated, gpu, rel_error_gpu). A = "
              "mesh: GPU images with both profiles against the mesh random walk (records with scene, profile, "
              "rel_rmse); --size sets the image (default 96x72), --images DIR keeps them. A = volume: the light "
              "volume and physical single scattering against path-traced single and multiple scattering (records "
              "with scene, method, rel_rmse_single, rel_rmse_multiple, mean_ratio, ms). A = light-volume: the light "
              "volume (paper and physical models) against the CPU reference of the same model, whose shadow rays "
              "replace it (records with scene, method, model, settings, rel_rmse, mean_ratio, ms). A = surfaces: "
              "opaque surfaces under a side light (the shell at 64^3 and 128^3, the bonsai), both models against "
              "path-traced single scattering (records with scene, model, settings, rel_rmse, truth_noise, "
              "ring_contrast, truth_ring_contrast, ms). "
              "Markdown and a plot as well",
              "A");
    addParsed(app, "--plot", o.plotPath,
              [](const std::string&, const std::string& text) { return std::optional<std::filesystem::path>(text); },
              "where the sweep's PNG plot goes (default: the JSON path with .png)", "FILE")
        ->group("output");
    app.add_option("--reference-cache", o.referenceCache,
                   "keep the sweeps' and the volume accuracy tables' CPU references there as OpenEXR and reuse them "
                   "when the scene is the same (the file name holds every parameter)")
        ->type_name("DIR");
    parseCommandLine(app, argc, argv);

    o.sizeGiven = given(app, "--size");
    // Quick mode only changes defaults; explicit options still win.
    o.runs = given(app, "--runs") ? runs : (o.quick ? 3 : 10);
    o.warmup = given(app, "--warmup") ? warmup : (o.quick ? 1 : 3);
    // Error sweeps compare with CPU references, whose cost grows with the pixel count.
    o.width = o.sizeGiven ? width : (o.errorSweep ? 128 : (o.quick ? 320 : kThesisWidth));
    o.height = o.sizeGiven ? height : (o.errorSweep ? 96 : (o.quick ? 180 : kThesisHeight));
    if (!dataDir.empty()) {
        std::error_code ec;
        if (!std::filesystem::is_directory(dataDir, ec))
            throw UsageError("--data-dir: \"" + dataDir + "\" is not a directory");
    }
    o.dataDir = dataDirectory(dataDir);
    if (o.jsonPath && !o.markdownPath) o.markdownPath = std::filesystem::path(*o.jsonPath).replace_extension(".md");
    return o;
}

void writeFile(const std::filesystem::path& path, const std::string& text) {
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
    std::ofstream out(path, std::ios::binary);
    out << text;
    out.close();
    if (!out) throw sss::Error(sss::ErrorKind::Io, path.string() + ": cannot write");
}

}  // namespace

int main(int argc, char** argv) {
    std::optional<Options> options;
    std::optional<sss::SceneDescription> scene;
    const int usage = runReportingErrors("sss-bench", [&] {
        options = parseArgs(argc, argv);
        if (!options->scene.empty()) {
            scene = sss::loadSceneFile(options->scene);
            if (!options->sizeGiven) options->width = scene->output.width, options->height = scene->output.height;
        }
        return 0;
    });
    if (usage != 0) return usage;

    try {
        BenchmarkContext bench(*options);
        if (options->glInfoOnly) {
            const sss::ContextInfo& gl = bench.glInfo();
            std::cout << "vendor: " << gl.vendor << "\nrenderer: " << gl.renderer << "\nversion: " << gl.version
                      << "\nbackend: " << gl.backend << "\nsoftware: " << (gl.software ? "yes" : "no")
                      << "\ntiming: " << bench.timingMethodName() << "\n";
            return 0;
        }
        std::cerr << "sss-bench: " << bench.glInfo().renderer << ", " << bench.timingMethodName() << ", "
                  << options->width << "x" << options->height << ", " << options->warmup << " warm-up + "
                  << options->runs << " runs\n";

        if (options->accuracy) {
            AccuracyOptions a;
            a.quick = options->quick;
            a.renderer = bench.glInfo().renderer;
            a.imageDir = options->imageDir;
            if (options->sizeGiven) {
                a.width = options->width;
                a.height = options->height;
            }
            const AccuracyReport report = *options->accuracy == "slab"   ? runSlabAccuracy(a)
                                          : *options->accuracy == "mesh" ? runMeshAccuracy(bench, a)
                                          : *options->accuracy == "volume" ? runVolumeAccuracy(bench, a)
                                          : *options->accuracy == "surfaces" ? runSurfaceAccuracy(bench, a)
                                                                             : runLightVolumeAccuracy(bench, a);
            const nlohmann::ordered_json json = {{"accuracy", *options->accuracy},
                                                 {"renderer", bench.glInfo().renderer},
                                                 {"date", bench.startedAt()},
                                                 {"quick", options->quick},
                                                 {"note", options->note},
                                                 {"records", report.json}};
            std::cout << report.markdown;
            if (options->jsonPath) writeFile(*options->jsonPath, json.dump(2) + "\n");
            if (options->markdownPath) writeFile(*options->markdownPath, report.markdown);
            const std::filesystem::path plotPath =
                options->plotPath ? *options->plotPath
                                  : (options->jsonPath ? std::filesystem::path(*options->jsonPath).replace_extension(".png")
                                                       : std::filesystem::path("accuracy.png"));
            if (plotPath.has_parent_path()) std::filesystem::create_directories(plotPath.parent_path());
            savePlot(report.plot, plotPath);
            std::cerr << "sss-bench: wrote " << plotPath.string() << "\n";
            return 0;
        }
        std::optional<PlotSpec> plot;
        if (scene) {
            runSceneTable(bench, *scene, std::filesystem::path(options->scene).stem().string());
        } else if (options->errorSweep) {
            plot = runErrorSweep(bench, *options->errorSweep);
        } else {
            const std::vector<std::string> tables =
                options->tables.empty() ? std::vector<std::string>{"baseline"} : options->tables;
            for (const std::string& t : tables) {
                if (t == "baseline") runBaselineTable(bench);
                if (t == "5.3") runTable53(bench);
                if (t == "5.4") runTable54(bench);
                if (t == "5.5") runTable55(bench);
                if (t == "casters") runCastersTable(bench);
                if (t == "scaling") runScalingTable(bench);
                if (t == "clear") runClearTable(bench);
                if (t == "textured") runTexturedTable(bench);
                if (t == "light-sweep") runLightSweepTable(bench);
            }
        }

        if (bench.records().empty()) {
            std::cerr << "sss-bench: nothing was measured (all data sets skipped or filtered out by --only)\n";
            return 1;
        }
        const std::string markdown = toMarkdown(bench);
        std::cout << markdown;
        if (options->jsonPath) writeFile(*options->jsonPath, toJson(bench).dump(2) + "\n");
        if (options->markdownPath) writeFile(*options->markdownPath, markdown);
        if (plot) {
            const std::filesystem::path plotPath =
                options->plotPath ? *options->plotPath
                                  : (options->jsonPath ? std::filesystem::path(*options->jsonPath).replace_extension(".png")
                                                       : std::filesystem::path("error-sweep.png"));
            if (plotPath.has_parent_path()) std::filesystem::create_directories(plotPath.parent_path());
            savePlot(*plot, plotPath);
            std::cerr << "sss-bench: wrote " << plotPath.string() << "\n";
        }
    } catch (const BenchFailure& e) {
        std::cerr << "sss-bench: verification failed: " << e.what() << "\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "sss-bench: error: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
