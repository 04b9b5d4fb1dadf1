#include "sss/timing.h"

#include "gl/gl.h"
#include "gl/query.h"

namespace sss {

void finishGpuWork() { glFinish(); }

struct GpuTimer::Query {
    gl::Query query;
};

GpuTimer::GpuTimer(const GlContext& context, bool forceCpuClock)
    : m_method(forceCpuClock || context.info().software ? TimingMethod::CpuClockAroundFinish
                                                        : TimingMethod::GlTimerQuery) {
    if (m_method == TimingMethod::GlTimerQuery) m_query = std::make_unique<Query>(Query{gl::Query::create(GL_TIME_ELAPSED)});
}

GpuTimer::~GpuTimer() = default;

void GpuTimer::begin() {
    if (m_method == TimingMethod::GlTimerQuery) {
        glBeginQuery(GL_TIME_ELAPSED, m_query->query.id());
    } else {
        glFinish();  // start from an idle GPU so earlier work is not billed to this section
        m_start = std::chrono::steady_clock::now();
    }
}

double GpuTimer::endMilliseconds() {
    if (m_method == TimingMethod::GlTimerQuery) {
        glEndQuery(GL_TIME_ELAPSED);
        GLuint64 ns = 0;
        glGetQueryObjectui64v(m_query->query.id(), GL_QUERY_RESULT, &ns);
        return static_cast<double>(ns) * 1e-6;
    }
    glFinish();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - m_start).count();
}

}  // namespace sss
