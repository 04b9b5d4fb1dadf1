// libFuzzer target: sss::parseRawVolumeName and sss::Volume::loadRaw (headerless .raw volumes
// whose dims and type come from the file name, or from RawLoadOptions).
//
// Input layout (every input is used; missing bytes read as 0):
//   byte 0          option flags: 0x01 dims set, 0x02 type set (0x08: UInt16, else UInt8),
//                   0x04 spacing set, 0x10 dims are int32 instead of int16
//   [dims]          3 x int16 (or int32), little-endian, if 0x01
//   [spacing]       3 x float (IEEE bits), little-endian, if 0x04
//   name '\n'       the first line: the file name ('/' and NUL become '_', at most 200 bytes)
//   contents        the rest: the file's bytes
// So "@bonsai_4x4x4_uint8.raw\n" followed by 64 bytes is a valid volume without options ('@'
// is 0x40: no flag set). Seeds are in corpus/raw.
//
// Oracle (see fuzz_support.h): both functions return or throw sss::Error. parseRawVolumeName
// ignores directories and never returns negative dims. A loaded volume has the dims, type and
// spacing the options or the name imply, dims in [1, 8192], exactly the file's bytes, a
// correct valueRange(), finite worldBounds() whose largest side is 1, and a histogram that
// counts every voxel.
//
// Allocation bound: the loader allocates only for a file of exactly the implied size, and the
// file is never larger than the input; still, inputs whose implied volume the library would
// accept but which exceed 64 MiB are skipped (they only ever reach the size-mismatch error), so
// a loader that allocated before checking the size could not exhaust memory here.
#include "fuzz_support.h"

#include "sss/error.h"
#include "sss/volume.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <optional>
#include <string>
#include <system_error>

namespace {

constexpr uint64_t kMaxImpliedBytes = uint64_t(64) << 20;
constexpr uint64_t kLibraryMaxBytes = uint64_t(4) << 30;

class Reader {
public:
    Reader(const uint8_t* data, std::size_t size) : m_data(data), m_size(size) {}
    uint8_t byte() { return m_pos < m_size ? m_data[m_pos++] : 0; }
    template <typename T>
    T little() {
        uint8_t bytes[sizeof(T)];
        for (auto& b : bytes) b = byte();  // little-endian host assumed (x86-64, aarch64)
        T value;
        std::memcpy(&value, bytes, sizeof(T));
        return value;
    }
    // Three values in order (function arguments have no evaluation order).
    template <typename T, typename Vec>
    Vec little3() {
        const T x = little<T>();
        const T y = little<T>();
        const T z = little<T>();
        return Vec(x, y, z);
    }
    std::string_view rest() const {
        return {reinterpret_cast<const char*>(m_data) + std::min(m_pos, m_size), m_size - std::min(m_pos, m_size)};
    }

private:
    const uint8_t* m_data;
    std::size_t m_size;
    std::size_t m_pos = 0;
};

std::string sanitizedName(std::string_view line) {
    std::string name(line.substr(0, 200));
    std::replace(name.begin(), name.end(), '/', '_');
    std::replace(name.begin(), name.end(), '\0', '_');
    if (name.empty() || name == "." || name == "..") name = "_" + name;
    return name;
}

bool sameInfo(const std::optional<sss::RawVolumeInfo>& a, const std::optional<sss::RawVolumeInfo>& b) {
    if (a.has_value() != b.has_value()) return false;
    return !a || (a->dims == b->dims && a->type == b->type && a->spacing == b->spacing);
}

void checkParsed(std::string_view name) {
    const std::optional<sss::RawVolumeInfo> info = sss::parseRawVolumeName(name);
    if (info) {
        SSS_FUZZ_CHECK(info->dims.x >= 0 && info->dims.y >= 0 && info->dims.z >= 0, "dims %d x %d x %d",
                       info->dims.x, info->dims.y, info->dims.z);
        SSS_FUZZ_CHECK(info->spacing == glm::vec3(1.0f), "spacing from a name");
    }
    SSS_FUZZ_CHECK(sameInfo(info, sss::Volume::parseRawVolumeName(name)), "Volume::parseRawVolumeName differs");
    // Directories are ignored: the last component alone parses the same, and so does the name
    // under another directory.
    std::string_view last = name;
    if (const std::size_t slash = last.find_last_of("/\\"); slash != std::string_view::npos)
        last.remove_prefix(slash + 1);
    SSS_FUZZ_CHECK(sameInfo(info, sss::parseRawVolumeName(last)), "a directory changed the result");
    SSS_FUZZ_CHECK(sameInfo(info, sss::parseRawVolumeName("dir_8x8x8_uint16.raw/" + std::string(last))),
                   "a parent directory's name changed the result");
}

void checkVolume(const sss::Volume& v, glm::ivec3 dims, sss::VoxelType type, glm::vec3 spacing,
                 std::string_view contents) {
    SSS_FUZZ_CHECK(v.dims() == dims, "dims %d x %d x %d, expected %d x %d x %d", v.dims().x, v.dims().y,
                   v.dims().z, dims.x, dims.y, dims.z);
    SSS_FUZZ_CHECK(v.type() == type, "voxel type");
    SSS_FUZZ_CHECK(v.spacing() == spacing, "spacing (%g, %g, %g)", v.spacing().x, v.spacing().y, v.spacing().z);
    for (int i = 0; i < 3; ++i) SSS_FUZZ_CHECK(dims[i] >= 1 && dims[i] <= 8192, "dims[%d] = %d", i, dims[i]);
    SSS_FUZZ_CHECK(v.voxelCount() * sss::bytesPerVoxel(type) == v.bytes().size(), "%zu voxels in %zu bytes",
                   v.voxelCount(), v.bytes().size());
    SSS_FUZZ_CHECK(v.bytes().size() == contents.size() &&
                       std::equal(v.bytes().begin(), v.bytes().end(), contents.begin(),
                                  [](uint8_t a, char b) { return a == static_cast<uint8_t>(b); }),
                   "bytes differ from the file's (%zu vs %zu bytes)", v.bytes().size(), contents.size());

    uint16_t lo = 0xffff, hi = 0;
    for (std::size_t i = 0; i < v.voxelCount(); ++i) {
        const uint16_t value = type == sss::VoxelType::UInt8
                                   ? v.bytes()[i]
                                   : static_cast<uint16_t>(v.bytes()[2 * i] | (v.bytes()[2 * i + 1] << 8));
        lo = std::min(lo, value);
        hi = std::max(hi, value);
    }
    SSS_FUZZ_CHECK(v.valueRange() == std::make_pair(double(lo), double(hi)), "valueRange (%g, %g), voxels span (%u, %u)",
                   v.valueRange().first, v.valueRange().second, lo, hi);

    const sss::Bounds b = v.worldBounds();
    const glm::vec3 size = b.size();
    SSS_FUZZ_CHECK(!b.empty() && std::isfinite(b.min.x) && std::isfinite(b.min.y) && std::isfinite(b.min.z) &&
                       std::isfinite(b.max.x) && std::isfinite(b.max.y) && std::isfinite(b.max.z),
                   "worldBounds (%g, %g, %g)..(%g, %g, %g) for dims %d x %d x %d, spacing (%g, %g, %g)", b.min.x,
                   b.min.y, b.min.z, b.max.x, b.max.y, b.max.z, dims.x, dims.y, dims.z, spacing.x, spacing.y,
                   spacing.z);
    SSS_FUZZ_CHECK(std::fabs(std::max({size.x, size.y, size.z}) - 1.0f) < 1e-5f,
                   "worldBounds' largest side is %g, not 1", std::max({size.x, size.y, size.z}));

    const std::vector<uint32_t> histogram = v.histogram();
    SSS_FUZZ_CHECK(histogram.size() == 256, "histogram has %zu bins", histogram.size());
    SSS_FUZZ_CHECK(std::accumulate(histogram.begin(), histogram.end(), uint64_t(0)) == v.voxelCount(),
                   "histogram does not count every voxel");
}

void load(const std::filesystem::path& path, const sss::RawLoadOptions& options, std::string_view contents) {
    const std::optional<sss::RawVolumeInfo> info = sss::parseRawVolumeName(path.filename().string());
    if (!options.dims && !info) {
        try {
            (void)sss::Volume::loadRaw(path, options);
        } catch (const sss::Error&) {
            return;
        }
        SSS_FUZZ_CHECK(false, "loaded a volume without dims in the name or the options");
    }
    const glm::ivec3 dims = options.dims ? *options.dims : info->dims;
    const sss::VoxelType type = options.type ? *options.type : (info ? info->type : sss::VoxelType::UInt8);
    const glm::vec3 spacing = options.spacing ? *options.spacing : glm::vec3(1.0f);
    if (dims.x > 0 && dims.y > 0 && dims.z > 0) {
        const uint64_t implied =
            uint64_t(dims.x) * uint64_t(dims.y) * uint64_t(dims.z) * sss::bytesPerVoxel(type);
        if (implied > kMaxImpliedBytes && implied <= kLibraryMaxBytes) return;
    }
    std::optional<sss::Volume> volume;
    try {
        volume = sss::Volume::loadRaw(path, options);
    } catch (const sss::Error&) {
        return;  // any other exception escapes: a bug
    }
    checkVolume(*volume, dims, type, spacing, contents);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
    Reader in(data, size);
    const uint8_t flags = in.byte();
    sss::RawLoadOptions options;
    if (flags & 0x01)
        options.dims = (flags & 0x10) ? in.little3<int32_t, glm::ivec3>() : in.little3<int16_t, glm::ivec3>();
    if (flags & 0x02) options.type = (flags & 0x08) ? sss::VoxelType::UInt16 : sss::VoxelType::UInt8;
    if (flags & 0x04) options.spacing = in.little3<float, glm::vec3>();

    const std::string_view rest = in.rest();
    const std::size_t newline = rest.find('\n');
    const std::string_view line = rest.substr(0, newline);
    const std::string_view contents = newline == std::string_view::npos ? std::string_view() : rest.substr(newline + 1);

    checkParsed(line);
    const std::string name = sanitizedName(line);
    checkParsed(name);

    const std::filesystem::path path =
        sss::fuzz::writeScratchFile(name, reinterpret_cast<const uint8_t*>(contents.data()), contents.size());
    load(path, options, contents);
    if (options.dims || options.type || options.spacing) load(path, {}, contents);
    std::error_code ec;
    std::filesystem::remove(path, ec);
    return 0;
}
