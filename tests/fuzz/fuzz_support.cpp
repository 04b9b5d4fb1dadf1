#include "fuzz_support.h"

#include "sss/log.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <system_error>
#include <vector>

namespace sss::fuzz {

const std::filesystem::path& scratchDir() {
    static const std::filesystem::path dir = [] {
        const char* tmp = std::getenv("TMPDIR");
        std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/sss-fuzz-XXXXXX";
        std::vector<char> buf(pattern.begin(), pattern.end());
        buf.push_back('\0');
        if (!::mkdtemp(buf.data())) {
            std::fprintf(stderr, "sss fuzz: cannot create a scratch directory %s: %s\n", pattern.c_str(),
                         std::strerror(errno));
            std::abort();
        }
        std::filesystem::path made(buf.data());
        static std::filesystem::path forCleanup;
        forCleanup = made;
        std::atexit([] {
            std::error_code ec;
            std::filesystem::remove_all(forCleanup, ec);
        });
        return made;
    }();
    return dir;
}

std::filesystem::path writeScratchFile(const std::string& name, const uint8_t* data, std::size_t size) {
    std::filesystem::path path = scratchDir() / name;
    std::FILE* f = std::fopen(path.c_str(), "wb");
    bool ok = f != nullptr;
    if (ok && size > 0) ok = std::fwrite(data, 1, size, f) == size;
    if (f) ok = std::fclose(f) == 0 && ok;
    if (!ok) {
        std::fprintf(stderr, "sss fuzz: cannot write %s: %s\n", path.c_str(), std::strerror(errno));
        std::abort();
    }
    return path;
}

}  // namespace sss::fuzz

// Called once by libFuzzer before the first input. The loaders' warnings (skipped faces, ...)
// would flood the output at thousands of inputs a second: they are dropped unless
// SSS_FUZZ_LOG=1 is set.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
    const char* keep = std::getenv("SSS_FUZZ_LOG");
    if (!(keep && std::string_view(keep) == "1")) sss::setLogHandler([](sss::LogLevel, std::string_view) {});
    return 0;
}

// Assimp 5.2 (Debian's, not instrumented) leaks a few KB on some error paths, e.g. an ASCII
// STL cut inside a facet. That is its bug, outside libsss, and bounded per failed load; leaks
// whose stack runs through it are not reported. teem 1.11 keeps its error-message array (biff)
// in a global it drops: 4184 bytes once per process, the same after 1 or 50 failed NRRD loads.
// VTK's MetaIO leaks what it allocated when std::length_error leaves MetaImage::Read on a damaged
// header (libsss turns the exception into sss::Error): a few hundred bytes per such file.
// VTK's XML reader drops a data array it made when a damaged .vti fails (about 1 KB); libsss
// holds every VTK object in a vtkNew, so leaks whose stack runs through VTK are VTK's.
// Leaks in libsss itself still are reported.
extern "C" const char* __lsan_default_suppressions() {
    return "leak:libassimp.so\nleak:libteem.so\nleak:libvtkmetaio\nleak:libvtkCommonCore\nleak:libvtkIOXML\n";
}
