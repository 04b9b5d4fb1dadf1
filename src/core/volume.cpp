#include "sss/volume.h"

#include "util/format.h"

#include "sss/error.h"

#include "core/voxel_storage.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

namespace sss {
namespace {

constexpr int kMaxSide = 8192;
constexpr double kMaxExtentRatio = 1e6;
constexpr uint64_t kMaxBytes = uint64_t(4) << 30;  // 4 GiB

std::string dimsStr(glm::ivec3 d) {
    return std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z);
}

const char* typeStr(VoxelType t) { return voxelTypeName(t); }

std::string vecStr(glm::vec3 v) { return detail::formatVec(v); }

// Throws InvalidArgument (prefixed) unless dims/spacing describe a volume we accept.
// Returns the byte size.
uint64_t checkLayout(const std::string& prefix, glm::ivec3 dims, VoxelType type, glm::vec3 spacing) {
    if (dims.x <= 0 || dims.y <= 0 || dims.z <= 0)
        throw Error(ErrorKind::InvalidArgument, prefix + "dims must be positive, got " + dimsStr(dims));
    if (dims.x > kMaxSide || dims.y > kMaxSide || dims.z > kMaxSide)
        throw Error(ErrorKind::InvalidArgument, prefix + "dims " + dimsStr(dims) +
                                                    " are too large: each side must be <= " +
                                                    std::to_string(kMaxSide));
    const uint64_t bytes = uint64_t(dims.x) * uint64_t(dims.y) * uint64_t(dims.z) * bytesPerVoxel(type);
    if (bytes > kMaxBytes) {
        std::ostringstream s;
        s << prefix << "dims " << dimsStr(dims) << ' ' << typeStr(type) << " would need "
          << double(bytes) / double(uint64_t(1) << 30) << " GiB, more than the 4 GiB limit";
        throw Error(ErrorKind::InvalidArgument, s.str());
    }
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(spacing[i]) || spacing[i] <= 0.0f)
            throw Error(ErrorKind::InvalidArgument,
                        prefix + "spacing must be finite and > 0, got " + vecStr(spacing));
    // The renderers place the volume in a box whose largest side is 1 (worldBounds); a side
    // more than kMaxExtentRatio times shorter would be degenerate in float.
    const glm::dvec3 extent = glm::dvec3(dims) * glm::dvec3(spacing);
    const double ratio = std::max({extent.x, extent.y, extent.z}) / std::min({extent.x, extent.y, extent.z});
    if (!(ratio <= kMaxExtentRatio)) {
        char factor[32];
        std::snprintf(factor, sizeof factor, "%.3g", ratio);
        throw Error(ErrorKind::InvalidArgument,
                    prefix + "dims " + dimsStr(dims) + " times spacing " + vecStr(spacing) +
                        " give sides whose lengths differ by a factor of " + factor +
                        "; at most 1e6 is supported");
    }
    return bytes;
}

bool parseInt(std::string_view s, int& out) {
    if (s.empty()) return false;
    auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    return ec == std::errc() && end == s.data() + s.size();
}

bool parseDimsToken(std::string_view token, glm::ivec3& dims) {
    std::size_t a = token.find('x');
    if (a == std::string_view::npos) return false;
    std::size_t b = token.find('x', a + 1);
    if (b == std::string_view::npos) return false;
    // Digits only: from_chars would accept a leading '-', which is not a dims token.
    if (!std::all_of(token.begin(), token.end(), [](char c) { return c == 'x' || (c >= '0' && c <= '9'); }))
        return false;
    return parseInt(token.substr(0, a), dims.x) && parseInt(token.substr(a + 1, b - a - 1), dims.y) &&
           parseInt(token.substr(b + 1), dims.z);
}

// Histogram counts are counted in 64 bits and returned saturated at UINT32_MAX.
std::vector<uint32_t> saturated(const std::vector<uint64_t>& counts) {
    std::vector<uint32_t> result(counts.size());
    std::transform(counts.begin(), counts.end(), result.begin(),
                   [](uint64_t c) { return static_cast<uint32_t>(std::min<uint64_t>(c, UINT32_MAX)); });
    return result;
}

bool equalsIgnoreCase(std::string_view a, std::string_view b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
               return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
           });
}

}  // namespace

std::optional<RawVolumeInfo> parseRawVolumeName(std::string_view filename) {
    if (std::size_t slash = filename.find_last_of("/\\"); slash != std::string_view::npos)
        filename.remove_prefix(slash + 1);
    RawVolumeInfo info;
    bool haveDims = false, haveType = false;
    std::size_t start = 0;
    while (start <= filename.size()) {
        std::size_t end = filename.find_first_of("_.", start);
        if (end == std::string_view::npos) end = filename.size();
        std::string_view token = filename.substr(start, end - start);
        glm::ivec3 dims;
        if (!haveDims && parseDimsToken(token, dims)) {
            info.dims = dims;
            haveDims = true;
        } else if (!haveType && equalsIgnoreCase(token, "uint8")) {
            info.type = VoxelType::UInt8;
            haveType = true;
        } else if (!haveType && equalsIgnoreCase(token, "uint16")) {
            info.type = VoxelType::UInt16;
            haveType = true;
        }
        start = end + 1;
    }
    if (!haveDims) return std::nullopt;
    return info;
}

Volume Volume::fromData(glm::ivec3 dims, VoxelType type, std::vector<uint8_t> bytes, glm::vec3 spacing) {
    const std::string prefix = "Volume::fromData: ";
    const uint64_t expected = checkLayout(prefix, dims, type, spacing);
    if (bytes.size() != expected)
        throw Error(ErrorKind::InvalidArgument, prefix + "bytes has " + std::to_string(bytes.size()) +
                                                    " bytes, expected " + std::to_string(expected) +
                                                    " for " + dimsStr(dims) + " " + typeStr(type));
    Volume v;
    v.m_dims = dims;
    v.m_type = type;
    v.m_spacing = spacing;
    v.m_bytes = std::move(bytes);
    // Computed once here so valueRange() is a cheap, thread-safe getter.
    double lo = 0.0, hi = 0.0;
    if (type == VoxelType::UInt8) {
        auto [mn, mx] = std::minmax_element(v.m_bytes.begin(), v.m_bytes.end());
        lo = *mn;
        hi = *mx;
    } else {
        lo = std::numeric_limits<double>::infinity();
        hi = -lo;
        const std::size_t n = v.voxelCount();
        for (std::size_t i = 0; i < n; ++i) {
            const double value = detail::rawValue(v.m_bytes.data(), type, i);
            if (!std::isfinite(value))
                throw Error(ErrorKind::InvalidArgument, prefix + "voxel " + std::to_string(i) + " is " +
                                                            detail::formatNumber(value) +
                                                            "; float32 voxels must be finite");
            lo = std::min(lo, value);
            hi = std::max(hi, value);
        }
    }
    v.m_range = {lo, hi};
    return v;
}

Volume Volume::loadRaw(const std::filesystem::path& path, const RawLoadOptions& options) {
    const std::string file = path.string();
    const std::string prefix = "Volume::loadRaw: " + file + ": ";
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw Error(ErrorKind::Io, prefix + "file does not exist");
    if (std::filesystem::is_directory(path, ec)) throw Error(ErrorKind::Io, prefix + "is a directory");

    const std::optional<RawVolumeInfo> info = parseRawVolumeName(path.filename().string());
    if (!options.dims && !info)
        throw Error(ErrorKind::InvalidArgument,
                    prefix + "dimensions unknown: the file name has no WxHxD token (as in "
                             "name_256x256x256_uint8.raw) and RawLoadOptions::dims is not set");
    const glm::ivec3 dims = options.dims ? *options.dims : info->dims;
    const VoxelType type = options.type ? *options.type : (info ? info->type : VoxelType::UInt8);
    const glm::vec3 spacing = options.spacing ? *options.spacing : glm::vec3(1.0f);
    const uint64_t expected = checkLayout(prefix, dims, type, spacing);

    const uint64_t actual = std::filesystem::file_size(path, ec);
    if (ec) throw Error(ErrorKind::Io, prefix + "cannot read the file size: " + ec.message());
    if (actual != expected)
        throw Error(ErrorKind::Parse, prefix + "file has " + std::to_string(actual) + " bytes, expected " +
                                          std::to_string(expected) + " for " + dimsStr(dims) + " " +
                                          typeStr(type));

    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(ErrorKind::Io, prefix + "cannot be opened for reading");
    std::vector<uint8_t> bytes(static_cast<std::size_t>(expected));
    in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(expected));
    if (in.gcount() != static_cast<std::streamsize>(expected))
        throw Error(ErrorKind::Io, prefix + "read " + std::to_string(in.gcount()) + " of " +
                                       std::to_string(expected) + " bytes");
    return fromData(dims, type, std::move(bytes), spacing);
}

const char* voxelTypeName(VoxelType type) {
    switch (type) {
    case VoxelType::UInt8: return "uint8";
    case VoxelType::UInt16: return "uint16";
    case VoxelType::Int16: return "int16";
    case VoxelType::Float32: return "float32";
    }
    return "unknown";
}

void Volume::setValueWindow(std::optional<std::pair<double, double>> window) {
    if (window && !(std::isfinite(window->first) && std::isfinite(window->second) && window->first < window->second))
        throw Error(ErrorKind::InvalidArgument, "Volume::setValueWindow: the window must be finite with lo < hi, got (" +
                                                    detail::formatNumber(window->first) + ", " +
                                                    detail::formatNumber(window->second) + ")");
    m_window = window;
}

double Volume::valueAt(int x, int y, int z) const {
    if (x < 0 || y < 0 || z < 0 || x >= m_dims.x || y >= m_dims.y || z >= m_dims.z)
        throw Error(ErrorKind::InvalidArgument, "Volume::valueAt: voxel (" + std::to_string(x) + ", " +
                                                    std::to_string(y) + ", " + std::to_string(z) +
                                                    ") is outside dims " + dimsStr(m_dims));
    const std::size_t i = (static_cast<std::size_t>(z) * static_cast<std::size_t>(m_dims.y) +
                           static_cast<std::size_t>(y)) * static_cast<std::size_t>(m_dims.x) +
                          static_cast<std::size_t>(x);
    return detail::rawValue(m_bytes.data(), m_type, i);
}

float Volume::normalizedAt(int x, int y, int z) const {
    const double value = valueAt(x, y, z);
    switch (m_type) {
    case VoxelType::UInt8: return float(value) * (1.0f / 255.0f);
    case VoxelType::UInt16: return float(value) * (1.0f / 65535.0f);
    case VoxelType::Int16: return float(value + 32768.0) * (1.0f / 65535.0f);
    case VoxelType::Float32: break;
    }
    const double span = m_range.second - m_range.first;
    return span > 0.0 ? float((value - m_range.first) / span) : 0.0f;
}

Bounds Volume::worldBounds() const {
    // In double: dims * spacing can pass FLT_MAX (spacing 3e38, say) although the ratio is fine.
    const glm::dvec3 extent = glm::dvec3(m_dims) * glm::dvec3(m_spacing);
    const double largest = std::max({extent.x, extent.y, extent.z});
    const glm::vec3 half = glm::vec3(0.5 * extent / largest);
    Bounds b;
    b.extend(-half);
    b.extend(half);
    return b;
}

std::vector<uint32_t> Volume::histogram(int bins) const {
    if (bins < 1 || bins > 65536)
        throw Error(ErrorKind::InvalidArgument,
                    "Volume::histogram: bins must be in [1, 65536], got " + std::to_string(bins));
    // 64-bit while counting: a 2048x2048x1024 uint8 volume of one value holds 2^32 voxels.
    std::vector<uint64_t> counts(static_cast<std::size_t>(bins), 0);
    if (m_type == VoxelType::UInt8) {
        for (uint8_t value : m_bytes) ++counts[static_cast<std::size_t>(uint64_t(value) * uint64_t(bins) / 256)];
    } else if (m_type != VoxelType::Float32) {
        // Integer storage codes 0..65535 (Int16 biased by 32768) over the whole type range.
        const std::size_t n = voxelCount();
        for (std::size_t i = 0; i < n; ++i) {
            const uint64_t code = detail::storageCode(m_bytes.data(), m_type, i);
            ++counts[static_cast<std::size_t>(code * uint64_t(bins) / 65536)];
        }
    } else {
        const auto [lo, hi] = transferFunctionDataRange();
        return histogram(bins, {lo, hi});
    }
    return saturated(counts);
}

std::pair<double, double> Volume::transferFunctionRange() const {
    if (m_window) return *m_window;
    return transferFunctionDataRange();
}

std::pair<double, double> Volume::transferFunctionDataRange() const {
    if (m_type == VoxelType::UInt8) return {0.0, 255.0};
    // A flat volume: widen by 1, or for huge floats by a step that is not lost to rounding.
    const double lo = m_range.first;
    const double step = std::max(1.0, std::abs(lo) * std::ldexp(1.0, -20));
    return {lo, std::max(lo + step, m_range.second)};
}

std::vector<uint32_t> Volume::histogram(int bins, std::pair<double, double> range) const {
    const double lo = range.first, hi = range.second;  // (clang 14: lambdas cannot capture bindings)
    if (bins < 1 || bins > 65536)
        throw Error(ErrorKind::InvalidArgument,
                    "Volume::histogram: bins must be in [1, 65536], got " + std::to_string(bins));
    if (!(std::isfinite(lo) && std::isfinite(hi) && lo < hi))
        throw Error(ErrorKind::InvalidArgument, "Volume::histogram: range must be finite with lo < hi, got (" +
                                                    detail::formatNumber(lo) + ", " + detail::formatNumber(hi) + ")");
    std::vector<uint64_t> counts(static_cast<std::size_t>(bins), 0);
    auto binOfValue = [&](double value) -> int32_t {
        if (value < lo || value > hi) return -1;
        const double bin = std::floor((value - lo) / (hi - lo) * bins);
        return static_cast<int32_t>(std::min(bin, static_cast<double>(bins - 1)));
    };
    if (m_type == VoxelType::Float32) {
        const std::size_t n = voxelCount();
        for (std::size_t i = 0; i < n; ++i)
            if (const int32_t bin = binOfValue(detail::rawValue(m_bytes.data(), m_type, i)); bin >= 0)
                ++counts[static_cast<std::size_t>(bin)];
        return saturated(counts);
    }
    // One bin index per possible storage code (-1: outside the range), then one lookup per voxel.
    const std::size_t codes = m_type == VoxelType::UInt8 ? 256 : 65536;
    const double codeToValue = m_type == VoxelType::Int16 ? -32768.0 : 0.0;
    std::vector<int32_t> binOf(codes, -1);
    for (std::size_t c = 0; c < codes; ++c) binOf[c] = binOfValue(static_cast<double>(c) + codeToValue);
    auto count = [&](std::size_t code) {
        if (const int32_t bin = binOf[code]; bin >= 0) ++counts[static_cast<std::size_t>(bin)];
    };
    if (m_type == VoxelType::UInt8) {
        for (uint8_t value : m_bytes) count(value);
    } else {
        const std::size_t n = voxelCount();
        for (std::size_t i = 0; i < n; ++i) count(detail::storageCode(m_bytes.data(), m_type, i));
    }
    return saturated(counts);
}

}  // namespace sss
