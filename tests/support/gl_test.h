#pragma once
// GL test support. Every [gl] test case starts with `sss::test::GlTestScope gl;` which makes the
// process's debug context current and resets its KHR_debug counters, and ends with
// `gl.requireNoErrors();`. As a backstop, test_main.cpp fails the whole run if any GL error
// message arrived at all, so a test that forgets the check still cannot pass with errors.
#include <sss/context.h>

#include <string>

namespace sss::test {

/// Exit code of a test process that skipped its test; ctest reads it through SKIP_RETURN_CODE.
constexpr int kSkipExitCode = 77;

/// True when a GL test must fail, not skip, without a usable context: under CI (CI=true or 1)
/// or when asked (SSS_REQUIRE_GL=1; scripts/test.sh sets it, as it installs llvmpipe).
bool glRequired();

/// Ends the test process as skipped (exit kSkipExitCode), saying why on stderr.
[[noreturn]] void skipTest(const std::string& why);

/// The process-wide headless debug context, created on first use. Without one the test is
/// skipped, or fails where glRequired(): it never passes silently.
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
