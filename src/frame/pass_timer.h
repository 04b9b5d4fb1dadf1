#pragma once
// A renderer's pass clock. Every pass's CPU time (its submission, or with finishEachPass its
// completion) goes to RenderStats; with GPU times on, GL timestamps written before and after the
// pass give its GPU time, collected without waiting once the GPU has passed them.
#include "gl/query.h"
#include "sss/stats.h"

#include <chrono>
#include <string>
#include <string_view>
#include <vector>

namespace sss::detail {

struct PassTiming {
    bool finishEachPass = false;  ///< wait for the GPU after the pass (CPU time = GPU completion)
    bool gpuTimes = false;        ///< write timestamps around the pass
};

class PassTimer {
public:
    /// An open pass: end() it (or let time() do so).
    struct Mark {
        std::chrono::steady_clock::time_point start;
        int slot = -1;  ///< the timestamp pair in use, -1: none
    };

    explicit PassTimer(RenderStats& stats) : m_stats(stats) {}

    Mark begin(PassTiming timing);
    void end(std::string_view pass, const Mark& mark, PassTiming timing);

    template <typename Work>
    void time(std::string_view pass, PassTiming timing, Work&& work) {
        const Mark mark = begin(timing);
        work();
        end(pass, mark, timing);
    }

private:
    struct Slot {
        gl::Query before, after;
        std::string pass;
        bool pending = false;  ///< written, not yet collected
    };
    /// Records every pending pair the GPU has passed; never waits.
    void collect();

    RenderStats& m_stats;
    std::vector<Slot> m_slots;  // grows to kMaxSlots; a pass finding none free goes untimed
};

}  // namespace sss::detail
