// libFuzzer target: sss::Volume::load for the headered formats read through VTK and teem
// (NRRD, MetaImage, NIfTI-1/2, VTK XML image data) and the choice of reader by extension.
//
// Input: the first byte picks the file name's extension (byte % 6: .nrrd .mha .nii .nii.gz .vti
// .mhd); the rest is the file. Oracle (see fuzz_support.h): load() returns or throws sss::Error,
// and a returned volume keeps the invariants of include/sss/volume.h: every side in [1, 8192],
// as many bytes as voxels times the voxel size, finite positive spacing, finite float voxels and
// a finite value range with lo <= hi.
//
// VTK and teem are linked as Debian builds them (not instrumented): coverage guidance stops at
// their boundary, and only what reaches libsss's code or crashes outright is seen.
#include "fuzz_support.h"

#include "sss/error.h"
#include "sss/volume.h"

#include <cmath>
#include <cstring>
#include <optional>

namespace {

void checkVolume(const sss::Volume& volume) {
    const glm::ivec3 d = volume.dims();
    for (int i = 0; i < 3; ++i) SSS_FUZZ_CHECK(d[i] >= 1 && d[i] <= 8192, "dims %d x %d x %d", d.x, d.y, d.z);
    SSS_FUZZ_CHECK(volume.bytes().size() == volume.voxelCount() * sss::bytesPerVoxel(volume.type()),
                   "%zu bytes for %zu voxels", volume.bytes().size(), volume.voxelCount());
    const glm::vec3 s = volume.spacing();
    for (int i = 0; i < 3; ++i)
        SSS_FUZZ_CHECK(std::isfinite(s[i]) && s[i] > 0.0f, "spacing %g, %g, %g", s.x, s.y, s.z);
    if (volume.type() == sss::VoxelType::Float32) {
        const std::vector<uint8_t>& bytes = volume.bytes();
        for (std::size_t i = 0; i < bytes.size(); i += 4) {
            float v = 0.0f;
            std::memcpy(&v, bytes.data() + i, 4);
            SSS_FUZZ_CHECK(std::isfinite(v), "voxel %zu is %g", i / 4, v);
        }
    }
    const auto [lo, hi] = volume.valueRange();
    SSS_FUZZ_CHECK(std::isfinite(lo) && std::isfinite(hi) && lo <= hi, "value range %g..%g", lo, hi);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    static const char* const kNames[] = {"input.nrrd", "input.mha", "input.nii", "input.nii.gz", "input.vti",
                                         "input.mhd"};
    const std::filesystem::path path = sss::fuzz::writeScratchFile(kNames[data[0] % 6], data + 1, size - 1);
    std::optional<sss::Volume> volume;
    try {
        volume = sss::Volume::load(path);
    } catch (const sss::Error&) {
        return 0;  // any other exception escapes: a bug
    }
    checkVolume(*volume);
    return 0;
}
