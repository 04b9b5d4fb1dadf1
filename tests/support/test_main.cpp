// Catch2 runner for every libsss test binary. Beyond Catch's own result, a run fails if any GL
// error was reported through KHR_debug during it (see support/gl_test.h).
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include "support/gl_test.h"

#include <cstdio>

int main(int argc, char* argv[]) {
    int result = Catch::Session().run(argc, argv);
    if (sss::test::anyGlErrorSeen()) {
        std::fprintf(stderr, "FAILED: GL errors were reported through KHR_debug during this run\n");
        if (result == 0) result = 1;
    }
    sss::test::destroyGlContext();
    return result;
}
