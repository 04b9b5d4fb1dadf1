#include "sss/stats.h"

namespace sss {

namespace {

PassStats& entry(std::map<std::string, PassStats, std::less<>>& passes, std::string_view pass) {
    auto it = passes.find(pass);
    if (it == passes.end()) it = passes.emplace(std::string(pass), PassStats{}).first;
    return it->second;
}

}  // namespace

void RenderStats::record(std::string_view pass, double ms) {
    PassStats& s = entry(m_passes, pass);
    ++s.runs;
    s.lastMs = ms;
    s.totalMs += ms;
}

void RenderStats::recordGpu(std::string_view pass, double ms) {
    PassStats& s = entry(m_passes, pass);
    ++s.gpuRuns;
    s.lastGpuMs = ms;
    s.totalGpuMs += ms;
}

void RenderStats::recordDispatches(std::string_view pass, std::uint64_t dispatches) {
    entry(m_passes, pass).lastDispatches = dispatches;
}

std::uint64_t RenderStats::runs(std::string_view pass) const {
    const PassStats* s = find(pass);
    return s ? s->runs : 0;
}

const PassStats* RenderStats::find(std::string_view pass) const {
    auto it = m_passes.find(pass);
    return it == m_passes.end() ? nullptr : &it->second;
}

}  // namespace sss
