#pragma once
// GL test support. Every [gl] test case starts with `sss::test::GlTestScope gl;` which makes the
// process's debug context current and resets its KHR_debug counters, and ends with
// `gl.requireNoErrors();`. As a backstop, test_main.cpp fails the whole run if any GL error
// message arrived at all, so a test that forgets the check still cannot pass with errors.
#include <sss/context.h>

namespace sss::test {

/// The process-wide headless debug context (created on first use; a failure fails the test).
GlContext& glContext();

class GlTestScope {
public:
    GlTestScope();
    GlContext& context() { return m_context; }
    /// REQUIREs that no GL error message arrived since the scope began.
    void requireNoErrors() const;

private:
    GlContext& m_context;
};

/// True once any GL error was reported in this process.
bool anyGlErrorSeen();

/// Destroys the process-wide context; main() calls it before returning, because tearing EGL
/// down from a static destructor races the driver's own exit handlers.
void destroyGlContext();

}  // namespace sss::test
