// JSON and Markdown reports. Both are built only from Records, so new tables need no changes here.

#include "bench.h"

#include <cstdio>
#include <sstream>
#include <thread>

std::string fixed(double v, int digits) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", digits, v);
    return buf;
}

nlohmann::ordered_json toJson(const BenchmarkContext& bench) {
    const Options& o = bench.options();
    const sss::ContextInfo& gl = bench.glInfo();
    nlohmann::ordered_json records = nlohmann::ordered_json::array();
    for (const Record& r : bench.records()) {
        const Stats& s = r.measurement.stats;
        nlohmann::ordered_json j = {
            {"table", r.table},
            {"model", r.model},
            {"mode", r.mode},
            {"median_ms", s.medianMs},
            {"min_ms", s.minMs},
            {"max_ms", s.maxMs},
            {"mean_ms", s.meanMs},
            {"stddev_ms", s.stddevMs},
            {"runs", s.runs},
            {"warmup", o.warmup},
            {"samples_ms", r.measurement.samplesMs},
            {"coverage", r.measurement.coverage},
            {"renderer", gl.renderer},
            {"width", r.width},
            {"height", r.height},
            {"thesis_gtx660_ms", r.thesisMs ? nlohmann::ordered_json(*r.thesisMs) : nlohmann::ordered_json(nullptr)},
        };
        j.update(r.details);  // vertices/triangles, dims, ... at the top level of the record
        records.push_back(std::move(j));
    }
    nlohmann::ordered_json skipped = nlohmann::ordered_json::array();
    for (const Skipped& s : bench.skipped())
        skipped.push_back({{"table", s.table}, {"model", s.model}, {"path", s.path}, {"reason", s.reason}});

    return {
        {"renderer", gl.renderer},
        {"vendor", gl.vendor},
        {"gl_version", gl.version},
        {"gl_backend", gl.backend},
        {"software_renderer", gl.software},
        {"timing_method", bench.timingMethodName()},
        {"viewport", {o.width, o.height}},
        {"date", bench.startedAt()},
        {"quick", o.quick},
        {"warmup", o.warmup},
        {"runs", o.runs},
        {"data_dir", o.dataDir.string()},
        {"hardware_threads", std::thread::hardware_concurrency()},
        {"note", o.note},
        {"records", std::move(records)},
        {"skipped", std::move(skipped)},
    };
}

std::string toMarkdown(const BenchmarkContext& bench) {
    const Options& o = bench.options();
    const sss::ContextInfo& gl = bench.glInfo();
    std::ostringstream md;
    md << "# sss-bench results\n\n";
    md << "- renderer: " << gl.renderer << " (" << gl.version << ")\n";
    md << "- timing: " << bench.timingMethodName() << "; " << o.warmup << " warm-up frame(s), " << o.runs
       << " timed run(s) per row; each run = clear + render\n";
    md << "- viewport: " << o.width << " x " << o.height << (o.quick ? " (quick mode)" : "") << "\n";
    md << "- date: " << bench.startedAt() << "\n";
    if (!o.note.empty()) md << "- machine: " << o.note << "\n";
    md << "\n| table | model | mode | data | params | median ms | min ms | max ms | mean ms | stddev ms | runs "
          "| thesis GTX 660 ms |\n";
    md << "|---|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const Record& r : bench.records()) {
        const Stats& s = r.measurement.stats;
        md << "| " << r.table << " | " << r.model << " | " << r.mode << " | " << r.dataSize << " | " << r.params
           << " | " << fixed(s.medianMs) << " | " << fixed(s.minMs) << " | " << fixed(s.maxMs) << " | "
           << fixed(s.meanMs) << " | " << fixed(s.stddevMs) << " | " << s.runs << " | "
           << (r.thesisMs ? fixed(*r.thesisMs) : std::string("–")) << " |\n";
    }
    if (!bench.skipped().empty()) {
        md << "\nSkipped (data missing):\n\n";
        for (const Skipped& s : bench.skipped()) md << "- " << s.model << ": `" << s.path << "` (" << s.reason << ")\n";
    }
    return md.str();
}
