#include "support/gl_test.h"

#include <catch2/catch.hpp>
#include <sss/error.h>

#include <memory>

namespace sss::test {
namespace {
std::unique_ptr<EglContext> g_context;
}

GlContext& glContext() {
    if (!g_context) {
        try {
            g_context = EglContext::create({.debug = true});
        } catch (const Error& e) {
            FAIL("cannot create the headless GL test context: " << e.what());
        }
        INFO("GL renderer: " << g_context->info().renderer);
    }
    g_context->makeCurrent();
    return *g_context;
}

bool anyGlErrorSeen() { return g_context && g_context->debugMessages().errors > 0; }

void destroyGlContext() { g_context.reset(); }

GlTestScope::GlTestScope() : m_context(glContext()) {
    REQUIRE(m_context.info().debug);
    m_context.resetDebugMessages();
}

void GlTestScope::requireNoErrors() const {
    const DebugMessageCounts counts = m_context.debugMessages();
    INFO("last GL error: " << m_context.lastDebugError());
    REQUIRE(counts.errors == 0);
}

}  // namespace sss::test
