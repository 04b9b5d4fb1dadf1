#include "sss/stats.h"

namespace sss {

void RenderStats::record(std::string_view pass, double ms) {
    auto it = m_passes.find(pass);
    if (it == m_passes.end()) it = m_passes.emplace(std::string(pass), PassStats{}).first;
    ++it->second.runs;
    it->second.lastMs = ms;
    it->second.totalMs += ms;
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
