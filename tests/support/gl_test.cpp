#include "support/gl_test.h"

#include <catch2/catch.hpp>
#include <sss/error.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>

namespace sss::test {
namespace {
std::unique_ptr<EglContext> g_context;
}

bool glRequired() {
    for (const char* name : {"CI", "SSS_REQUIRE_GL"}) {
        const char* v = std::getenv(name);
        if (v && (std::strcmp(v, "1") == 0 || std::strcmp(v, "true") == 0 || std::strcmp(v, "TRUE") == 0)) return true;
    }
    return false;
}

void skipTest(const std::string& why) {
    std::fprintf(stderr, "SKIPPED: %s\n", why.c_str());
    std::fflush(stderr);
    g_context.reset();
    std::_Exit(kSkipExitCode);
}

GlContext& glContext() {
    if (!g_context) {
        try {
            g_context = EglContext::create({.debug = true});
        } catch (const Error& e) {
            if (!glRequired())
                skipTest(std::string("no headless GL 4.5 context (set CI=true or SSS_REQUIRE_GL=1 to fail instead): ") +
                         e.what());
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
