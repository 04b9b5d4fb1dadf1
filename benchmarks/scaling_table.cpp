// Time against viewport size and ray step: what a frame costs whatever its size (intercept) and
// per pixel or per ray sample (slope). Volume: emission-absorption and fixed scattering on the
// bonsai at 3 sizes x 3 steps, fitted against megapixels / step (millions of ray samples, up to
// early termination and skipping). Mesh: the bunny's change (light buffer, maps or estimate,
// combine) and fixed frames at the default combine, against megapixels.

#include "bench.h"

#include <sss/option_names.h>

#include <cmath>
#include <iostream>

namespace {

constexpr const char* kTable = "scaling";

struct Fit {
    double intercept = 0.0, slope = 0.0, r2 = 0.0;
};

Fit leastSquares(const std::vector<double>& x, const std::vector<double>& y) {
    const double n = static_cast<double>(x.size());
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (std::size_t i = 0; i < x.size(); ++i) sx += x[i], sy += y[i], sxx += x[i] * x[i], sxy += x[i] * y[i];
    Fit f;
    const double denominator = n * sxx - sx * sx;
    if (denominator == 0.0) return f;
    f.slope = (n * sxy - sx * sy) / denominator;
    f.intercept = (sy - f.slope * sx) / n;
    double residual = 0, total = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        residual += std::pow(y[i] - (f.intercept + f.slope * x[i]), 2.0);
        total += std::pow(y[i] - sy / n, 2.0);
    }
    f.r2 = total > 0.0 ? 1.0 - residual / total : 1.0;
    return f;
}

/// Rows of one series, fitted once all are measured: each row gets the series' fit.
class Series {
public:
    Series(std::string name, std::string xName) : m_name(std::move(name)), m_xName(std::move(xName)) {}
    void add(Record r, double x) {
        m_x.push_back(x);
        m_y.push_back(r.measurement.stats.medianMs);
        r.details[m_xName] = x;
        m_rows.push_back(std::move(r));
    }
    void addTo(BenchmarkContext& bench) {
        const Fit f = leastSquares(m_x, m_y);
        std::cerr << "sss-bench: scaling " << m_name << ": " << f.intercept << " ms + " << f.slope << " ms per "
                  << m_xName << " (r^2 " << f.r2 << ")\n";
        for (Record& r : m_rows) {
            r.details["series"] = m_name;
            r.details["fit"] = {{"x", m_xName}, {"intercept_ms", f.intercept}, {"slope_ms", f.slope}, {"r2", f.r2}};
            bench.addRecord(std::move(r));
        }
    }

private:
    std::string m_name, m_xName;
    std::vector<double> m_x, m_y;
    std::vector<Record> m_rows;
};

std::vector<glm::ivec2> viewports(bool quick) {
    if (quick) return {{160, 90}, {320, 180}};
    return {{600, 340}, {1200, 680}, {2400, 1360}};
}

Record row(const std::string& model, const std::string& mode, glm::ivec2 size, const std::string& params) {
    Record r;
    r.table = kTable;
    r.model = model;
    r.mode = mode;
    r.params = params;
    r.width = size.x;
    r.height = size.y;
    return r;
}

double megapixels(glm::ivec2 size) { return static_cast<double>(size.x) * static_cast<double>(size.y) * 1e-6; }

void volumeSeries(BenchmarkContext& bench, const std::string& model) {
    const std::optional<FramedVolume> scene = loadFramedVolume(bench, kTable, model);
    if (!scene) return;
    sss::VolumeScatteringRenderer renderer;
    showVolume(renderer, *scene);
    const glm::ivec3 d = scene->volume.dims();
    for (sss::VolumeShading shading : {sss::VolumeShading::EmissionAbsorption, sss::VolumeShading::Scattering}) {
        const std::string mode(sss::enumName(shading));
        Series series(model + " " + mode, "megasamples");
        for (float step : {1.0f, 0.5f, 0.25f})
            for (glm::ivec2 size : viewports(bench.options().quick)) {
                sss::VolumeRenderOptions o;  // the library's defaults (pre-integration), this step
                o.shading = shading;
                o.stepSize = step;
                o.rayCaster = bench.options().rayCaster;
                o.lightPropagation = bench.options().lightPropagation;
                renderer.setOptions(o);
                Record r = row(model, mode, size, "step " + std::to_string(step).substr(0, 4) + " (median = fixed)");
                r.dataSize = dimsText(d);
                r.measurement = bench.measure([&](sss::RenderTarget& t) { renderer.render(scene->camera, t); },
                                              std::string(kTable) + "-" + model + "-" + mode, size);
                r.details = {{"step_voxels", step}, {"megapixels", megapixels(size)}};
                series.add(std::move(r), megapixels(size) / step);
            }
        series.addTo(bench);
    }
}

void meshSeries(BenchmarkContext& bench, const std::string& model) {
    const std::optional<sss::Mesh> mesh = loadThesisMesh(bench, kTable, model);
    if (!mesh) return;
    const sss::Camera camera = framedCamera(mesh->bounds());
    const sss::DirectionalLight key = keyLight(camera);
    // One map frame per change, as Table 5.3 (the default accumulates 8, so a "fixed" frame would
    // still be adding map frames).
    sss::MeshRenderOptions options{.shading = sss::MeshShading::Scattering, .millimetresPerUnit = 1000.0,
                                   .accumulationFrames = 1};
    if (bench.options().quick) {  // ctest: the same code path, small maps and few samples
        options.cameras = 4;
        options.samples = 8;
        options.mapResolution = options.lightMapResolution = 128;
    }
    sss::MeshScatteringRenderer renderer(options);
    renderer.setMesh(*mesh);
    renderer.setScatteringMaterial(sss::materialPreset("cream"));
    renderer.setLights({key});
    const std::string combine(sss::enumName(renderer.activeCombine()));
    const std::string data = std::to_string(mesh->vertexCount()) + " v / " + std::to_string(mesh->triangleCount()) + " tri";
    Series change(model + " change", "megapixels"), fixed(model + " fixed", "megapixels");
    for (glm::ivec2 size : viewports(bench.options().quick)) {
        const sss::DirectionalLight other = nudged(key);
        bool useOther = false;
        Record c = row(model, "sss change", size, "combine " + combine);
        c.dataSize = data;
        c.measurement = bench.measure(
            [&](sss::RenderTarget& t) {
                useOther = !useOther;
                renderer.setLights({useOther ? other : key});
                renderer.render(camera, t);
            },
            std::string(kTable) + "-" + model + "-change", size);
        change.add(std::move(c), megapixels(size));
        renderer.setLights({key});
        Record f = row(model, "sss fixed", size, "combine " + combine);
        f.dataSize = data;
        f.measurement = bench.measure([&](sss::RenderTarget& t) { renderer.render(camera, t); },
                                      std::string(kTable) + "-" + model + "-fixed", size);
        fixed.add(std::move(f), megapixels(size));
    }
    change.addTo(bench);
    fixed.addTo(bench);
}

}  // namespace

void runScalingTable(BenchmarkContext& bench) {
    const bool quick = bench.options().quick;
    const std::string volume = quick ? "blobs" : "bonsai", mesh = quick ? "sphere" : "bunny";
    if (bench.wanted(volume)) volumeSeries(bench, volume);
    if (bench.wanted(mesh)) meshSeries(bench, mesh);
}
