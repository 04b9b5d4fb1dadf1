#include "frame/pass_timer.h"

#include "gl/gl.h"
#include "sss/timing.h"

namespace sss::detail {

namespace {

// Pairs in flight at once: a few frames of every pass of a renderer. When all are still on the
// GPU, a pass goes without a GPU time rather than wait.
constexpr std::size_t kMaxSlots = 64;

}  // namespace

PassTimer::Mark PassTimer::begin(PassTiming timing) {
    Mark mark{std::chrono::steady_clock::now(), -1};
    if (!timing.gpuTimes) return mark;
    collect();
    for (std::size_t i = 0; i < m_slots.size() && mark.slot < 0; ++i)
        if (!m_slots[i].pending) mark.slot = static_cast<int>(i);
    if (mark.slot < 0 && m_slots.size() < kMaxSlots) {
        m_slots.push_back({gl::Query::create(GL_TIMESTAMP), gl::Query::create(GL_TIMESTAMP), {}, false});
        mark.slot = static_cast<int>(m_slots.size() - 1);
    }
    if (mark.slot >= 0) glQueryCounter(m_slots[static_cast<std::size_t>(mark.slot)].before.id(), GL_TIMESTAMP);
    return mark;
}

void PassTimer::end(std::string_view pass, const Mark& mark, PassTiming timing) {
    if (mark.slot >= 0) {
        Slot& slot = m_slots[static_cast<std::size_t>(mark.slot)];
        glQueryCounter(slot.after.id(), GL_TIMESTAMP);
        slot.pass = pass;
        slot.pending = true;
    }
    if (timing.finishEachPass) finishGpuWork();
    m_stats.record(pass, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - mark.start).count());
}

void PassTimer::collect() {
    for (Slot& slot : m_slots) {
        if (!slot.pending) continue;
        GLint available = 0;
        glGetQueryObjectiv(slot.after.id(), GL_QUERY_RESULT_AVAILABLE, &available);
        if (!available) continue;
        // Both results are there (the earlier timestamp passed first), so these do not wait.
        GLuint64 before = 0, after = 0;
        glGetQueryObjectui64v(slot.before.id(), GL_QUERY_RESULT, &before);
        glGetQueryObjectui64v(slot.after.id(), GL_QUERY_RESULT, &after);
        m_stats.recordGpu(slot.pass, static_cast<double>(after - before) * 1e-6);
        slot.pending = false;
    }
}

}  // namespace sss::detail
