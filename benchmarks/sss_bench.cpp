// sss-bench: times libsss renderers the way the thesis did (chapter 5) and writes JSON + Markdown.
// Exit codes: 0 success, 1 a measurement failed (error, empty image), 2 bad command line.

#include "accuracy.h"
#include "bench.h"
#include "plot.h"

#include <charconv>
#include <cstdlib>
#include <fstream>
#include <iostream>

namespace {

constexpr const char* kUsage = R"(usage: sss-bench [options]

Times the libsss renderers (median of several frames, after warm-up frames) and writes
the results as JSON and as a Markdown table (also printed to stdout).

options:
  --quick             procedural data only, small viewport, 1 warm-up + 3 runs (for ctest)
  --gl-info           print the GL vendor, renderer and version and the timing method (one
                      "key: value" per line), then exit; benchmarks/run-gpu.sh checks with it
                      that the EGL device is the GPU it means to measure
  --json FILE         write the results as JSON to FILE
  --markdown FILE     write the Markdown table to FILE (default: the JSON path with .md)
  --data-dir DIR      data sets (meshes/, volumes/); default $SSS_DATA_DIR, else ../shared/data
  --runs N            timed frames per row, N >= 1 (default 10; quick 3)
  --warmup N          untimed frames before timing, N >= 0 (default 3; quick 1)
  --size WxH          viewport (default 1200x680, the thesis viewport; quick 320x180)
  --only A,B,...      only these models (e.g. bunny,bonsai)
  --note TEXT         free text about the machine, copied into the reports
  --images DIR        save each row's verified image as DIR/<table>-<model>-<mode>.png
  --table T[,T...]    thesis tables to reproduce: baseline (default), 5.3 (mesh scattering),
                      5.4 (volume scattering), 5.5 (hybrid scenes)
  --error-sweep S     time against error for S = mesh or volume, against the CPU reference;
                      records with sweep, the swept parameters, ms and rel_rmse, and a plot
  --accuracy A        accuracy against physical ground truth. A = slab: presets x channels x
                      incidence 0/45/75 degrees, the random walk against the dipole, the
                      calibrated profile and a GPU render (JSON records with material, channel,
                      incidence_deg, random_walk, random_walk_stderr, dipole, calibrated, gpu,
                      rel_error_gpu). A = mesh: GPU images with both profiles against the mesh
                      random walk (records with scene, profile, rel_rmse); --size sets the image
                      (default 96x72), --images DIR keeps them. A = volume: the light volume and
                      physical single scattering against path-traced single and multiple
                      scattering (records with scene, method, rel_rmse_single, rel_rmse_multiple,
                      mean_ratio, ms). Markdown and a plot as well
  --plot FILE         where the sweep's PNG plot goes (default: the JSON path with .png)
  --reference-cache DIR
                      keep the sweeps' CPU references there as OpenEXR and reuse them when the
                      scene is the same (the file name holds every parameter)
  --help              show this help
)";

// Command-line mistakes: reported with the option's name, exit code 2.
struct UsageError {
    std::string message;
};

int parseInt(const std::string& option, const std::string& text, int minValue) {
    int value = 0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (ec != std::errc() || ptr != end || value < minValue)
        throw UsageError{option + " expects an integer >= " + std::to_string(minValue) + ", got \"" + text + "\""};
    return value;
}

void parseSize(const std::string& text, int& width, int& height) {
    const std::size_t x = text.find_first_of("xX");
    if (x == std::string::npos) throw UsageError{"--size expects WxH (e.g. 1200x680), got \"" + text + "\""};
    try {
        width = parseInt("--size", text.substr(0, x), 1);
        height = parseInt("--size", text.substr(x + 1), 1);
    } catch (const UsageError&) {
        throw UsageError{"--size expects WxH with positive integers (e.g. 1200x680), got \"" + text + "\""};
    }
    if (width > sss::kMaxImageSide || height > sss::kMaxImageSide)
        throw UsageError{"--size: each side must be at most " + std::to_string(sss::kMaxImageSide)};
}

std::vector<std::string> splitList(const std::string& text) {
    std::vector<std::string> out;
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t comma = std::min(text.find(',', start), text.size());
        if (comma > start) out.push_back(text.substr(start, comma - start));
        start = comma + 1;
    }
    return out;
}

std::filesystem::path defaultDataDir() {
    if (const char* env = std::getenv("SSS_DATA_DIR"); env && *env) return env;
    std::error_code ec;
    if (std::filesystem::is_directory("../shared/data", ec)) return "../shared/data";
    return {};
}

// Returns nullopt when --help was asked for.
std::optional<Options> parseArgs(int argc, char** argv) {
    Options o;
    std::optional<int> runs, warmup;
    std::optional<std::pair<int, int>> size;
    std::optional<std::filesystem::path> dataDir;

    for (int i = 1; i < argc; ++i) {
        std::string arg = argv[i];
        std::optional<std::string> inlineValue;  // --opt=value
        if (const std::size_t eq = arg.find('='); arg.rfind("--", 0) == 0 && eq != std::string::npos) {
            inlineValue = arg.substr(eq + 1);
            arg = arg.substr(0, eq);
        }
        auto value = [&]() -> std::string {
            if (!inlineValue && i + 1 >= argc) throw UsageError{arg + " needs a value"};
            std::string v = inlineValue ? *inlineValue : argv[++i];
            if (v.empty() && arg != "--note") throw UsageError{arg + " needs a non-empty value"};
            return v;
        };
        auto flag = [&] {
            if (inlineValue) throw UsageError{arg + " takes no value"};
        };

        if (arg == "--help" || arg == "-h") {
            flag();
            return std::nullopt;
        } else if (arg == "--quick") {
            flag();
            o.quick = true;
        } else if (arg == "--gl-info") {
            flag();
            o.glInfoOnly = true;
        } else if (arg == "--json") {
            o.jsonPath = value();
        } else if (arg == "--markdown") {
            o.markdownPath = value();
        } else if (arg == "--data-dir") {
            dataDir = value();
        } else if (arg == "--runs") {
            runs = parseInt(arg, value(), 1);
        } else if (arg == "--warmup") {
            warmup = parseInt(arg, value(), 0);
        } else if (arg == "--size") {
            int w = 0, h = 0;
            parseSize(value(), w, h);
            size = {w, h};
        } else if (arg == "--only") {
            o.only = splitList(value());
            if (o.only.empty()) throw UsageError{"--only needs at least one model name"};
        } else if (arg == "--note") {
            o.note = value();
        } else if (arg == "--images") {
            o.imageDir = value();
        } else if (arg == "--table") {
            for (const std::string& t : splitList(value())) {
                if (t != "baseline" && t != "5.3" && t != "5.4" && t != "5.5")
                    throw UsageError{"--table: unknown table \"" + t + "\" (baseline, 5.3, 5.4, 5.5)"};
                o.tables.push_back(t);
            }
        } else if (arg == "--error-sweep") {
            const std::string which = value();
            if (which != "mesh" && which != "volume")
                throw UsageError{"--error-sweep: expected mesh or volume, got \"" + which + "\""};
            o.errorSweep = which;
        } else if (arg == "--accuracy") {
            const std::string which = value();
            if (which != "slab" && which != "mesh" && which != "volume")
                throw UsageError{"--accuracy: expected slab, mesh or volume, got \"" + which + "\""};
            o.accuracy = which;
        } else if (arg == "--plot") {
            o.plotPath = value();
        } else if (arg == "--reference-cache") {
            o.referenceCache = value();
        } else {
            throw UsageError{"unknown option \"" + arg + "\" (see --help)"};
        }
    }

    o.sizeGiven = size.has_value();
    // Quick mode only changes defaults; explicit options still win.
    o.runs = runs.value_or(o.quick ? 3 : 10);
    o.warmup = warmup.value_or(o.quick ? 1 : 3);
    // Error sweeps compare with CPU references, whose cost grows with the pixel count.
    o.width = size ? size->first : (o.errorSweep ? 128 : (o.quick ? 320 : kThesisWidth));
    o.height = size ? size->second : (o.errorSweep ? 96 : (o.quick ? 180 : kThesisHeight));
    if (dataDir) {
        std::error_code ec;
        if (!std::filesystem::is_directory(*dataDir, ec))
            throw UsageError{"--data-dir: \"" + dataDir->string() + "\" is not a directory"};
        o.dataDir = *dataDir;
    } else {
        o.dataDir = defaultDataDir();
    }
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
    try {
        options = parseArgs(argc, argv);
    } catch (const UsageError& e) {
        std::cerr << "sss-bench: " << e.message << "\n";
        return 2;
    }
    if (!options) {
        std::cout << kUsage;
        return 0;
    }

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
                                                                         : runVolumeAccuracy(bench, a);
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
        if (options->errorSweep) {
            plot = runErrorSweep(bench, *options->errorSweep);
        } else {
            const std::vector<std::string> tables =
                options->tables.empty() ? std::vector<std::string>{"baseline"} : options->tables;
            for (const std::string& t : tables) {
                if (t == "baseline") runBaselineTable(bench);
                if (t == "5.3") runTable53(bench);
                if (t == "5.4") runTable54(bench);
                if (t == "5.5") runTable55(bench);
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
