#pragma once
/// @file
/// Timing GPU work honestly on both kinds of renderer:
///  - hardware GPUs: GL_TIME_ELAPSED timer queries (GPU time, no pipeline stall);
///  - software rasterisers (llvmpipe): a CPU steady clock around glFinish(), because llvmpipe
///    rasterises at flush time and its timer queries only see the front end.

#include "sss/api.h"
#include "sss/context.h"

#include <chrono>
#include <memory>

SSS_BEGIN_API

namespace sss {

/// Blocks until all submitted GL work has finished (glFinish).
void finishGpuWork();

enum class TimingMethod { CpuClockAroundFinish, GlTimerQuery };

/// Measures one section of GL work at a time: begin(), issue work, endMilliseconds().
class GpuTimer {
public:
    /// Picks GlTimerQuery on hardware and CpuClockAroundFinish on software renderers
    /// (ContextInfo::software); `forceCpuClock` always uses the CPU clock.
    explicit GpuTimer(const GlContext& context, bool forceCpuClock = false);
    ~GpuTimer();
    GpuTimer(const GpuTimer&) = delete;
    GpuTimer& operator=(const GpuTimer&) = delete;

    TimingMethod method() const { return m_method; }
    void begin();
    /// Ends the section and returns its duration in milliseconds (waits for the result).
    double endMilliseconds();

private:
    TimingMethod m_method;
    std::chrono::steady_clock::time_point m_start;
    struct Query;
    std::unique_ptr<Query> m_query;
};

}  // namespace sss

SSS_END_API
