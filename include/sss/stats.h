#pragma once
/// @file
/// Per-pass statistics every renderer keeps, so applications, tests and the benchmark can see
/// which passes ran (and which were skipped because nothing they depend on changed).

#include "sss/api.h"
#include <cstdint>
#include <map>
#include <string>
#include <string_view>

SSS_BEGIN_API

namespace sss {

struct PassStats {
    std::uint64_t runs = 0;    ///< times the pass was executed
    double lastMs = 0.0;       ///< CPU time of the last run (submission only unless the
                               ///< renderer's `finishEachPass` option waits for the GPU)
    double totalMs = 0.0;
    /// GPU times, with the renderer's `gpuPassTimes` option on: the time between timestamps
    /// written before and after the pass, read without waiting once the GPU has passed them, so
    /// they lag the CPU times by a frame or more (gpuRuns <= runs).
    std::uint64_t gpuRuns = 0;
    double lastGpuMs = 0.0;
    double totalGpuMs = 0.0;
    /// Compute dispatches of the last run, for passes that count them (the light volume: one
    /// GPU-wide wait each).
    std::uint64_t lastDispatches = 0;
};

class RenderStats {
public:
    void record(std::string_view pass, double ms);
    void recordGpu(std::string_view pass, double ms);
    void recordDispatches(std::string_view pass, std::uint64_t dispatches);
    /// Runs of `pass` so far (0 for a pass that never ran).
    std::uint64_t runs(std::string_view pass) const;
    const PassStats* find(std::string_view pass) const;
    const std::map<std::string, PassStats, std::less<>>& passes() const { return m_passes; }
    void reset() { m_passes.clear(); }

private:
    std::map<std::string, PassStats, std::less<>> m_passes;
};

}  // namespace sss

SSS_END_API
