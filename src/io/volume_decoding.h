#pragma once
// What the volume readers of the io component share: the decoded voxels before orientation, and
// one function per reader. A reader whose library was not built throws ErrorKind::Unsupported,
// naming the format and the build option.
#include "sss/error.h"
#include "sss/volume.h"

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace sss::detail {


// What a reader hands over before orientation and validation.
struct Decoded {
    glm::ivec3 dims{0};
    VoxelType type = VoxelType::UInt8;
    std::vector<uint8_t> bytes;  // little-endian, x fastest
    glm::dvec3 spacing{1.0};
    glm::dmat3 direction{1.0};   // column j: world direction of index axis j
};

[[noreturn]] inline void fail(ErrorKind kind, const std::string& prefix, const std::string& what) {
    throw Error(kind, prefix + what);
}

inline std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

// The file's axes are accepted up to 8192 voxels each, the rest is checked by Volume::fromData;
// a header claiming more is rejected before anything allocates.
inline void checkDims(const std::string& prefix, const std::array<long long, 3>& dims) {
    for (long long d : dims)
        if (d < 1 || d > 8192)
            fail(ErrorKind::Parse, prefix,
                 "dims " + std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + "x" + std::to_string(dims[2]) +
                     " are out of range: each side must be in [1, 8192]");
}

// Copies `count` voxels of a library's scalar type into our storage; int8 widens to int16.
template <class T>
std::vector<uint8_t> toBytes(const void* data, std::size_t count) {
    std::vector<uint8_t> out(count * sizeof(T));
    std::memcpy(out.data(), data, out.size());
    return out;
}

inline std::vector<uint8_t> widenInt8(const void* data, std::size_t count) {
    std::vector<uint8_t> out(count * 2);
    const auto* in = static_cast<const int8_t*>(data);
    for (std::size_t i = 0; i < count; ++i) {
        const auto v = static_cast<uint16_t>(static_cast<int16_t>(in[i]));
        out[2 * i] = static_cast<uint8_t>(v & 0xff);
        out[2 * i + 1] = static_cast<uint8_t>(v >> 8);
    }
    return out;
}

inline std::string unsupportedType(const std::string& name) {
    return "voxel type " + name + " is not supported (uint8, int8, int16, uint16 and float32 are)";
}


/// The readers: `file` as given, `prefix` starts every message ("Volume::load: <file>: ").
Decoded readNifti(const std::string& file, const std::string& prefix);
Decoded readVti(const std::string& file, const std::string& prefix);
Decoded readDicomSeries(const std::string& dir, const std::string& prefix);
Decoded readMetaImage(const std::string& file, const std::string& prefix);
Decoded readNrrd(const std::string& file, const std::string& prefix);

}  // namespace sss::detail
