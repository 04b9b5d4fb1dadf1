#pragma once
// Shared pieces of sss-bench: options, statistics, records and the BenchmarkContext that owns
// the GL context. Each thesis table is one run*Table(BenchmarkContext&) function that appends
// Records; the report writers know nothing about individual tables.

#include <sss/sss.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

// The thesis measured everything in a 1200 x 680 viewport (digest §1).
inline constexpr int kThesisWidth = 1200;
inline constexpr int kThesisHeight = 680;

struct Options {
    bool quick = false;
    bool glInfoOnly = false;  // --gl-info: print the GL device and the timing method, run nothing
    std::optional<std::filesystem::path> jsonPath;
    std::optional<std::filesystem::path> markdownPath;  // default: jsonPath with .md
    std::filesystem::path dataDir;                       // empty: no data sets available
    int warmup = 3;
    int runs = 10;
    int width = kThesisWidth;
    int height = kThesisHeight;
    bool sizeGiven = false;  // --size was given
    std::vector<std::string> only;  // model names to run; empty = all
    std::string note;               // free text about the machine, copied into the reports
    std::filesystem::path imageDir; // if set, the verified image of each row is saved there
    std::vector<std::string> tables;      // --table: "baseline", "5.3", "5.4", "5.5"; empty = baseline
    std::optional<std::string> errorSweep;  // --error-sweep: "mesh" or "volume"
    std::optional<std::string> accuracy;    // --accuracy: "slab"
    std::optional<std::filesystem::path> plotPath;  // default: the JSON path with .png
    std::filesystem::path referenceCache;  // --reference-cache: CPU references kept as EXR (empty: none)
    std::string scene;  // --scene: time this scene file instead of the tables
    sss::RayCaster rayCaster = sss::RayCaster::Auto;  // --ray-caster: the volume rows' ray caster
    sss::LightPropagation lightPropagation = sss::LightPropagation::Auto;  // --light-propagation: the volume rows'
    sss::VolumeModel volumeModel = sss::VolumeModel::Paper;  // --volume-model: the thesis rows' shading model
    bool passes = false;  // --passes: GPU timestamps per pass; records with pass, gpu_ms, cpu_ms
};

struct Stats {
    double medianMs = 0.0;
    double minMs = 0.0;
    double maxMs = 0.0;
    double meanMs = 0.0;
    double stddevMs = 0.0;  // sample standard deviation (n - 1); 0 for a single run
    int runs = 0;
};

/// Summary of frame times in milliseconds. Throws std::invalid_argument if samples is empty.
Stats summarize(std::vector<double> samples);

/// One timed configuration and the image check that followed it.
struct Measurement {
    Stats stats;
    std::vector<double> samplesMs;
    double coverage = 0.0;  // fraction of pixels that differ from the background
};

/// One row of a results table. Table-specific values (mesh size, K, ...) go in `details`,
/// which the JSON writer merges into the record, and in the short `dataSize`/`params` strings
/// the Markdown writer shows.
struct Record {
    std::string table;  // "baseline", later "5.3", "5.4", "5.5"
    std::string model;  // "bunny", "bonsai", ...
    std::string mode;   // "blinn-phong", "emission-absorption", "gradient", ...
    std::string dataSize;  // "35947 v / 69451 tri", "256x256x256"
    std::string params;    // e.g. "tf=bonsai"
    int width = 0;
    int height = 0;
    Measurement measurement;
    nlohmann::ordered_json details = nlohmann::ordered_json::object();
    std::optional<double> thesisMs;  // GTX 660 time of the same row (thesis viewport only)
};

/// A data set the run could not use; reported, never a failure.
struct Skipped {
    std::string table;
    std::string model;
    std::string path;
    std::string reason;
};

/// A measurement whose output failed verification (empty image, GL errors): exit code 1.
class BenchFailure : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Owns the headless GL context, the render target and the timer that every table shares,
/// and collects the results.
class BenchmarkContext {
public:
    /// Creates a non-debug EGL context (debug output slows drivers down) unless SSS_GL_DEBUG=1.
    explicit BenchmarkContext(Options options);
    ~BenchmarkContext();

    const Options& options() const { return m_options; }
    const sss::ContextInfo& glInfo() const { return m_gl->info(); }
    sss::TimingMethod timingMethod() const { return m_timer->method(); }
    std::string timingMethodName() const;
    /// When the run started, ISO 8601 UTC (shared by both reports).
    const std::string& startedAt() const { return m_startedAt; }

    /// True if --only is empty or names `model`.
    bool wanted(std::string_view model) const;
    /// Path of a data set below the data directory, or nullopt (and a Skipped entry, with a
    /// note on stderr) if it does not exist.
    std::optional<std::filesystem::path> findData(const std::string& table, const std::string& model,
                                                  const std::filesystem::path& relative);

    /// Times `render` (which draws into the target it is given) after clearing the target to
    /// the background: options().warmup untimed frames, then options().runs timed ones. Then
    /// reads the image back once and throws BenchFailure if it is empty, has non-finite
    /// pixels, or the debug context saw GL errors. `id` names the case in messages and in the
    /// file name of the saved image (--images), e.g. "baseline-bunny-blinn-phong".
    /// `size`, if given, replaces the viewport for this measurement (the scaling runs).
    /// `timedRuns`, if given, is called with true before the first timed frame and with false
    /// after the last (the per-pass records take the renderer's statistics there).
    Measurement measure(const std::function<void(sss::RenderTarget&)>& render, const std::string& id,
                        std::optional<glm::ivec2> size = std::nullopt,
                        const std::function<void(bool starting)>& timedRuns = {});

    /// Times several renders as measure() does, their timed frames interleaved (one of each in
    /// turn, options().runs rounds), so that this machine's drift in speed falls on all of them
    /// alike: for ratios between them. One Measurement per render, in order; each image checked.
    std::vector<Measurement> measureInterleaved(const std::vector<std::function<void(sss::RenderTarget&)>>& renders,
                                                const std::vector<std::string>& ids);

    /// The frame's floor: the target's clear alone (RenderTarget::clear, or `clear` if given),
    /// timed as measure() times a frame (no image check: nothing is drawn).
    Measurement measureClearOnly(const std::function<void(sss::RenderTarget&)>& clear = {});

    void addRecord(Record record);
    void addSkipped(Skipped skipped);
    const std::vector<Record>& records() const { return m_records; }
    const std::vector<Skipped>& skipped() const { return m_skipped; }

private:
    // Reads `target` back once, saves it under `id` (--images) and throws BenchFailure if it is
    // empty or the debug context saw GL errors; sets m.coverage.
    void verify(sss::RenderTarget& target, const std::string& id, Measurement& m);

    Options m_options;
    std::string m_startedAt;
    // Declared first so it is destroyed last: the target and timer hold GL objects.
    std::unique_ptr<sss::EglContext> m_gl;
    std::unique_ptr<sss::RenderTarget> m_target;
    std::unique_ptr<sss::GpuTimer> m_timer;
    std::vector<Record> m_records;
    std::vector<Skipped> m_skipped;
};

/// Fixed view set-up shared by all tables: a camera framed on `bounds` from slightly above and
/// to the side, and one directional light coming from over the viewer's left shoulder.
sss::Camera framedCamera(const sss::Bounds& bounds);
sss::DirectionalLight keyLight(const sss::Camera& camera);
/// `light` turned 3 degrees about +y: alternating the two forces a "change" frame (every
/// view-independent pass reruns) at almost the same image.
sss::DirectionalLight nudged(const sss::DirectionalLight& light);
/// `camera` orbited half a degree to one side on even frames, to the other on odd ones: frame
/// after frame, a camera move (every view-dependent pass reruns) at almost the same image.
sss::Camera moved(const sss::Camera& camera, int frame);
/// The thesis's ray casting, which its tables measured: step 1 voxel, post-classification (the
/// library's defaults since are step 0.5 with pre-integration); with the run's --ray-caster,
/// --light-propagation and --passes.
sss::VolumeRenderOptions thesisVolumeOptions(const Options& run, sss::VolumeShading shading);

/// Renders into `target` (cleared each frame) until the renderer has converged: the scattering
/// maps' or the estimate's accumulation after a change. Returns the wall time with the GPU
/// finished, ms.
double renderUntilConverged(sss::MeshScatteringRenderer& renderer, const sss::Camera& camera, sss::RenderTarget& target);

/// --passes: what one renderer's passes cost over the timed frames of one measurement.
class PassRecorder {
public:
    explicit PassRecorder(const sss::RenderStats& stats) : m_stats(stats) {}
    /// For BenchmarkContext::measure's timedRuns.
    std::function<void(bool)> hook();
    /// One record per pass that ran: `row`'s table, model and size, mode "pass", and pass,
    /// frame, gpu_ms, cpu_ms (means over the timed frames; gpu_ms null without timestamps).
    void addRecords(BenchmarkContext& bench, const Record& row, const std::string& frame) const;
    /// `pass`'s mean GPU time over the timed frames; nullopt where it did not run or was not timed.
    std::optional<double> gpuMs(std::string_view pass) const;

private:
    struct Cost {
        std::uint64_t runs = 0, gpuRuns = 0;
        double cpuMs = 0.0, gpuMs = 0.0;  // means
    };
    Cost cost(const std::string& pass, const sss::PassStats& after) const;
    const sss::RenderStats& m_stats;
    std::map<std::string, sss::PassStats, std::less<>> m_before, m_after;
};

/// Times `renderer` (a mesh or volume renderer) in two ways: "change" frames alternate `key` and
/// its nudged twin, so every view-independent pass reruns; "fixed" frames change nothing. With
/// `passes` (--passes), the renderer's per-pass costs of each go to passes->change / ->fixed.
struct ChangeAndFixedPasses {
    PassRecorder change, fixed;
};
template <typename Renderer>
std::pair<Measurement, Measurement> measureChangeAndFixed(BenchmarkContext& bench, Renderer& renderer,
                                                          const sss::Camera& camera, const sss::DirectionalLight& key,
                                                          const std::string& id, ChangeAndFixedPasses* passes = nullptr) {
    const sss::DirectionalLight other = nudged(key);
    bool useOther = false;
    Measurement change = bench.measure(
        [&](sss::RenderTarget& t) {
            useOther = !useOther;
            renderer.setLights({useOther ? other : key});
            renderer.render(camera, t);
        },
        id + "-change", std::nullopt, passes ? passes->change.hook() : std::function<void(bool)>{});
    renderer.setLights({key});
    Measurement fixed = bench.measure([&](sss::RenderTarget& t) { renderer.render(camera, t); }, id + "-fixed",
                                      std::nullopt, passes ? passes->fixed.hook() : std::function<void(bool)>{});
    return {std::move(change), std::move(fixed)};
}

// ---- tables -----------------------------------------------------------------------------------

/// Scattering-off baselines: Blinn-Phong meshes and emission-absorption / gradient volumes
/// (the "Blinn-Phong" column of Table 5.3 and the EA columns of Table 5.4).
void runBaselineTable(BenchmarkContext& bench);
/// Thesis Table 5.3: mesh subsurface scattering, K = 4/8/16 with N = 12/24/48 per model:
/// "change" (light buffer + maps + combine), "fixed" (combine only), Blinn-Phong.
void runTable53(BenchmarkContext& bench);
/// Thesis Table 5.4: volume scattering: change (light volume + ray cast), fixed, emission-
/// absorption, EA + gradient, fixed + gradient.
void runTable54(BenchmarkContext& bench);
/// Fragment against compute ray casting, side by side, per volume and mode.
void runCastersTable(BenchmarkContext& bench);
/// The light-volume rebuild against the slices each dispatch advances, side by side, per volume and model.
void runLightSweepTable(BenchmarkContext& bench);
/// The ways to clear a render target, side by side (the floor under every frame's time).
void runClearTable(BenchmarkContext& bench);
/// Textured translucent meshes against the same mesh untextured: change and fixed frames per combine.
void runTexturedTable(BenchmarkContext& bench);
/// Time against viewport size and step: EA and fixed scattering on the bonsai, the mesh change
/// and fixed frames on the bunny, with the intercept and slope of a line through each series.
void runScalingTable(BenchmarkContext& bench);
/// Thesis Table 5.5: hybrid scenes (volume + mesh in a Cornell box), whole frame and parts.
void runTable55(BenchmarkContext& bench);
namespace sss { struct SceneDescription; }
/// --scene: the "change" and "fixed" frames of a scene file (`name` labels the rows).
void runSceneTable(BenchmarkContext& bench, const sss::SceneDescription& scene, const std::string& name);
/// Time against error: sweeps against the CPU references; returns the plot to draw.
struct PlotSpec;
PlotSpec runErrorSweep(BenchmarkContext& bench, const std::string& which);
/// Records of the real meshes at 2 cm, 20 cm and 2 m in marble and skin1, every method at its
/// defaults against the CPU reference (benchmarks/mesh_scale_sweep.cpp); with a plot, one series
/// per method of its scenes' regeneration time against error.
void meshScaleSweep(BenchmarkContext& bench, PlotSpec* plot = nullptr);

// ---- data sets shared by the tables -------------------------------------------------------------

/// A thesis mesh by model name (bunny, dragon, buddha, dragon-vrip, sphere), uniformly scaled to
/// the Stanford bunny's size (bounding radius 0.1 units, i.e. 10 cm at 1000 mm per unit) so one
/// set of scattering parameters fits all, as in the thesis. nullopt (and a skip) if missing.
std::optional<sss::Mesh> loadThesisMesh(BenchmarkContext& bench, const std::string& table, const std::string& model);
/// A thesis volume by model name (bucky, bonsai, engine, cthead) and its TF preset name.
std::optional<std::pair<sss::Volume, std::string>> loadThesisVolume(BenchmarkContext& bench, const std::string& table,
                                                                    const std::string& model);

/// "256x256x256": a volume's size in the reports.
std::string dimsText(glm::ivec3 dims);
/// A thesis volume set up as every volume table shows it: framed by framedCamera(), lit by
/// keyLight(), with its transfer-function preset.
struct FramedVolume {
    sss::Volume volume;
    std::string preset;
    sss::Camera camera;
    sss::DirectionalLight key;
};
/// loadThesisVolume(), framed; nullopt (and a skip) if the data is missing.
std::optional<FramedVolume> loadFramedVolume(BenchmarkContext& bench, const std::string& table, const std::string& model);
/// Gives `renderer` the volume, its transfer function and the key light.
void showVolume(sss::VolumeScatteringRenderer& renderer, const FramedVolume& scene);
/// For each of `models` (--quick: the procedural "blobs" instead) that --only wants and that
/// loads: `measure` with its name, the framed volume and a renderer showing it.
using ShownVolumeMeasure =
    std::function<void(const std::string& model, const FramedVolume& scene, sss::VolumeScatteringRenderer& renderer)>;
void forEachShownVolume(BenchmarkContext& bench, const std::string& table, const std::vector<std::string>& models,
                        const ShownVolumeMeasure& measure);

/// A CPU reference image: read from --reference-cache DIR/name if it is there, else rendered
/// (timed on stderr) and kept there.
sss::Image cachedReference(const Options& o, const std::string& name, const std::function<sss::Image()>& render);

/// Eight hex digits that change with the camera and the light a reference is rendered for. Cache
/// names end in it, so a reference kept for another view or light is rendered anew, not reused.
std::string viewAndLightTag(const sss::Camera& camera, const sss::DirectionalLight& light);

// ---- reports ----------------------------------------------------------------------------------

/// v with `digits` decimals, for the tables.
std::string fixed(double v, int digits = 2);
nlohmann::ordered_json toJson(const BenchmarkContext& bench);
std::string toMarkdown(const BenchmarkContext& bench);
