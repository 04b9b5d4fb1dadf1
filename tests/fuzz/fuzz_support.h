#pragma once
// Shared by the libFuzzer targets in tests/fuzz: a per-process scratch directory for the
// loaders (which take paths), and the oracle's failure report.
//
// Oracle policy: a loader call either returns a value that keeps its documented invariants or
// throws sss::Error. Any other exception escapes LLVMFuzzerTestOneInput (std::terminate, which
// libFuzzer reports as a crash); a broken invariant is reported by SSS_FUZZ_CHECK, which prints
// the failed condition and traps.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>

#define SSS_FUZZ_CHECK(cond, ...)                                                          \
    do {                                                                                   \
        if (!(cond)) {                                                                     \
            std::fprintf(stderr, "\n==== sss fuzz oracle violation (%s:%d): %s\n", __FILE__, \
                         __LINE__, #cond);                                                 \
            std::fprintf(stderr, "     " __VA_ARGS__);                                     \
            std::fprintf(stderr, "\n");                                                    \
            std::fflush(stderr);                                                           \
            __builtin_trap();                                                              \
        }                                                                                  \
    } while (0)

namespace sss::fuzz {

/// A directory of its own for this process, made on first use under $TMPDIR (else /tmp) and
/// removed at normal exit (a crashing run leaves it behind: under ctest, TMPDIR points into the
/// build tree).
const std::filesystem::path& scratchDir();

/// Writes data to scratchDir()/name (replacing it) and returns the path. Traps if it cannot:
/// a fuzz run without a writable scratch directory would silently test nothing.
std::filesystem::path writeScratchFile(const std::string& name, const uint8_t* data, std::size_t size);

}  // namespace sss::fuzz
