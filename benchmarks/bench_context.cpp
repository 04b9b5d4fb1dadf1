#include "bench.h"

#include <glm/gtc/matrix_transform.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <iostream>

namespace {

// A dark, opaque background that no lit surface or classified voxel reproduces exactly, so
// "differs from the background" means "something was drawn".
constexpr glm::vec4 kBackground{0.08f, 0.08f, 0.10f, 1.0f};

// Below this fraction of drawn pixels the object is considered missing; a framed object
// covers far more than this even at 320 x 180.
constexpr double kMinCoverage = 0.001;

double drawnFraction(const sss::Image& image, const std::string& what) {
    const std::vector<float>& px = image.data();
    std::size_t drawn = 0;
    for (std::size_t i = 0; i < px.size(); i += 4) {
        bool differs = false;
        for (std::size_t c = 0; c < 4; ++c) {
            if (!std::isfinite(px[i + c]))
                throw BenchFailure(what + ": the image has non-finite pixels");
            differs = differs || std::abs(px[i + c] - kBackground[static_cast<glm::length_t>(c)]) > 1.0f / 255.0f;
        }
        drawn += differs ? 1 : 0;
    }
    return static_cast<double>(drawn) / static_cast<double>(px.size() / 4);
}

std::string isoDateUtc() {
    const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
    std::tm utc{};
    gmtime_r(&now, &utc);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &utc);
    return buf;
}

}  // namespace

BenchmarkContext::BenchmarkContext(Options options) : m_options(std::move(options)), m_startedAt(isoDateUtc()) {
    // Not a debug context: KHR_debug output slows drivers and would be billed to the frames.
    // SSS_GL_DEBUG=1 still switches it on, and then measure() also checks the error count.
    m_gl = sss::EglContext::create({.debug = false});
    m_target = std::make_unique<sss::RenderTarget>(m_options.width, m_options.height);
    m_timer = std::make_unique<sss::GpuTimer>(*m_gl);
}

BenchmarkContext::~BenchmarkContext() = default;

std::string BenchmarkContext::timingMethodName() const {
    return timingMethod() == sss::TimingMethod::GlTimerQuery ? "gl-timer-query" : "cpu-clock-around-glFinish";
}

bool BenchmarkContext::wanted(std::string_view model) const {
    return m_options.only.empty() ||
           std::find(m_options.only.begin(), m_options.only.end(), model) != m_options.only.end();
}

std::optional<std::filesystem::path> BenchmarkContext::findData(const std::string& table, const std::string& model,
                                                                const std::filesystem::path& relative) {
    const std::filesystem::path path = m_options.dataDir.empty() ? relative : m_options.dataDir / relative;
    std::error_code ec;
    if (!m_options.dataDir.empty() && std::filesystem::is_regular_file(path, ec)) return path;
    const std::string reason = m_options.dataDir.empty() ? "no data directory (use --data-dir or SSS_DATA_DIR)"
                                                         : "file not found";
    std::cerr << "sss-bench: skipping " << model << " (" << path.string() << "): " << reason << "\n";
    addSkipped({table, model, path.string(), reason});
    return std::nullopt;
}

Measurement BenchmarkContext::measure(const std::function<void(sss::RenderTarget&)>& render, const std::string& id,
                                      std::optional<glm::ivec2> size, const std::function<void(bool)>& timedRuns) {
    std::optional<sss::RenderTarget> resized;
    if (size && *size != glm::ivec2(m_target->width(), m_target->height())) resized.emplace(size->x, size->y);
    sss::RenderTarget& target = resized ? *resized : *m_target;
    // Warm-up frames are not timed: the first one compiles shaders and uploads lookup tables.
    for (int i = 0; i < m_options.warmup; ++i) {
        target.clear(kBackground);
        render(target);
    }
    sss::finishGpuWork();

    Measurement m;
    m.samplesMs.reserve(static_cast<std::size_t>(m_options.runs));
    if (timedRuns) timedRuns(true);
    for (int i = 0; i < m_options.runs; ++i) {
        m_timer->begin();
        target.clear(kBackground);
        render(target);
        m.samplesMs.push_back(m_timer->endMilliseconds());
    }
    if (timedRuns) timedRuns(false);
    m.stats = summarize(m.samplesMs);
    verify(target, id, m);  // once, after timing, so the read-back is not billed to any frame
    return m;
}

std::vector<Measurement> BenchmarkContext::measureInterleaved(
    const std::vector<std::function<void(sss::RenderTarget&)>>& renders, const std::vector<std::string>& ids) {
    sss::RenderTarget& target = *m_target;
    for (const auto& render : renders)
        for (int i = 0; i < m_options.warmup; ++i) {
            target.clear(kBackground);
            render(target);
        }
    sss::finishGpuWork();
    std::vector<Measurement> measurements(renders.size());
    for (int i = 0; i < m_options.runs; ++i)
        for (std::size_t r = 0; r < renders.size(); ++r) {
            m_timer->begin();
            target.clear(kBackground);
            renders[r](target);
            measurements[r].samplesMs.push_back(m_timer->endMilliseconds());
        }
    for (std::size_t r = 0; r < renders.size(); ++r) {
        measurements[r].stats = summarize(measurements[r].samplesMs);
        target.clear(kBackground);
        renders[r](target);  // the image to check, after timing
        verify(target, ids.at(r), measurements[r]);
    }
    return measurements;
}

void BenchmarkContext::verify(sss::RenderTarget& target, const std::string& id, Measurement& m) {
    const sss::Image image = target.readColor();
    if (!m_options.imageDir.empty()) {
        std::filesystem::create_directories(m_options.imageDir);
        sss::toDisplay(image).savePng(m_options.imageDir / (id + ".png"));  // the display image (sRGB)
    }
    m.coverage = drawnFraction(image, id);
    if (m.coverage < kMinCoverage)
        throw BenchFailure(id + ": the rendered image is empty (" + std::to_string(m.coverage * 100.0) +
                           "% of pixels differ from the background)");
    if (m_gl->info().debug && m_gl->debugMessages().errors > 0)
        throw BenchFailure(id + ": OpenGL reported errors: " + m_gl->lastDebugError());
}

Measurement BenchmarkContext::measureClearOnly(const std::function<void(sss::RenderTarget&)>& clear) {
    const auto run = [&] { clear ? clear(*m_target) : m_target->clear(kBackground); };
    for (int i = 0; i < m_options.warmup; ++i) run();
    sss::finishGpuWork();
    Measurement m;
    for (int i = 0; i < m_options.runs; ++i) {
        m_timer->begin();
        run();
        m.samplesMs.push_back(m_timer->endMilliseconds());
    }
    m.stats = summarize(m.samplesMs);
    return m;
}

void BenchmarkContext::addRecord(Record record) {
    const Stats& s = record.measurement.stats;
    std::cerr << "sss-bench: " << record.table << " " << record.model << " " << record.mode << ": median "
              << s.medianMs << " ms (min " << s.minMs << ", max " << s.maxMs << ", " << s.runs << " runs)\n";
    m_records.push_back(std::move(record));
}

void BenchmarkContext::addSkipped(Skipped skipped) { m_skipped.push_back(std::move(skipped)); }

sss::Camera framedCamera(const sss::Bounds& bounds) {
    sss::Camera camera;
    camera.setYaw(25.0f);
    camera.setPitch(15.0f);
    camera.frame(bounds);
    return camera;
}

sss::DirectionalLight keyLight(const sss::Camera& camera) {
    sss::DirectionalLight light;
    // Travels away from the viewer, rightwards and downwards: lit from the upper left.
    light.direction = glm::normalize(camera.forward() + 0.5f * camera.right() - 0.6f * camera.up());
    return light;
}

sss::DirectionalLight nudged(const sss::DirectionalLight& light) {
    sss::DirectionalLight other = light;
    other.direction = glm::vec3(glm::rotate(glm::mat4(1.0f), glm::radians(3.0f), glm::vec3(0, 1, 0)) *
                                glm::vec4(light.direction, 0.0f));
    return other;
}

sss::Camera moved(const sss::Camera& camera, int frame) {
    sss::Camera other = camera;
    other.setYaw(camera.yaw() + (frame % 2 == 0 ? -0.5f : 0.5f));
    return other;
}

double renderUntilConverged(sss::MeshScatteringRenderer& renderer, const sss::Camera& camera, sss::RenderTarget& target) {
    const auto start = std::chrono::steady_clock::now();
    do {
        target.clear({0, 0, 0, 0});
        renderer.render(camera, target);
    } while (!renderer.converged());
    sss::finishGpuWork();
    return 1000.0 * std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

sss::VolumeRenderOptions thesisVolumeOptions(const Options& run, sss::VolumeShading shading) {
    sss::VolumeRenderOptions o;
    o.shading = shading;
    o.stepSize = 1.0f;
    o.preintegration = false;
    o.rayCaster = run.rayCaster;
    o.lightPropagation = run.lightPropagation;
    o.model = run.volumeModel;
    o.gpuPassTimes = run.passes;
    return o;
}

std::function<void(bool)> PassRecorder::hook() {
    return [this](bool starting) { (starting ? m_before : m_after) = m_stats.passes(); };
}

PassRecorder::Cost PassRecorder::cost(const std::string& pass, const sss::PassStats& after) const {
    const auto it = m_before.find(pass);
    const sss::PassStats before = it == m_before.end() ? sss::PassStats{} : it->second;
    Cost c{after.runs - before.runs, after.gpuRuns - before.gpuRuns};
    if (c.runs > 0) c.cpuMs = (after.totalMs - before.totalMs) / static_cast<double>(c.runs);
    if (c.gpuRuns > 0) c.gpuMs = (after.totalGpuMs - before.totalGpuMs) / static_cast<double>(c.gpuRuns);
    return c;
}

std::optional<double> PassRecorder::gpuMs(std::string_view pass) const {
    const auto it = m_after.find(pass);
    if (it == m_after.end()) return std::nullopt;
    const Cost c = cost(it->first, it->second);
    return c.gpuRuns > 0 ? std::optional(c.gpuMs) : std::nullopt;
}

void PassRecorder::addRecords(BenchmarkContext& bench, const Record& row, const std::string& frame) const {
    for (const auto& [pass, after] : m_after) {
        const Cost c = cost(pass, after);
        if (c.runs == 0) continue;  // the pass did not run in these frames (its inputs were cached)
        const auto runs = c.runs;
        const auto gpuRuns = c.gpuRuns;
        const double cpuMs = c.cpuMs, gpuMs = c.gpuMs;
        const bool timed = gpuRuns > 0;
        Record r;
        r.table = row.table;
        r.model = row.model;
        r.mode = "pass";
        r.dataSize = row.dataSize;
        r.params = pass + " (" + frame + "; median = " + (timed ? "GPU" : "CPU") + " mean)";
        r.width = row.width;
        r.height = row.height;
        r.measurement.stats = summarize({timed ? gpuMs : cpuMs});
        r.measurement.stats.runs = static_cast<int>(runs);
        r.details = {{"pass", pass}, {"frame", frame}, {"gpu_ms", timed ? nlohmann::ordered_json(gpuMs) : nullptr},
                     {"cpu_ms", cpuMs}, {"gpu_samples", gpuRuns}};
        bench.addRecord(std::move(r));
    }
}
