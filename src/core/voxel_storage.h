#pragma once
// How each VoxelType is decoded from Volume::bytes() and what its GPU texture holds. One place,
// so the GPU passes, the CPU reference, the path tracer and the empty-space grid agree on the
// transfer-function coordinate bit for bit.
//
// Texture formats and the "sample" s a texture fetch returns for a voxel of raw value v:
//   UInt8   R8 (unorm)   s = v / 255
//   UInt16  R16 (unorm)  s = v / 65535
//   Int16   R16 (unorm) of the biased code v + 32768: s = (v + 32768) / 65535. Exact and linear
//           (R16_SNORM would merge -32768 with -32767), and the same path as UInt16.
//   Float32 R32F of s = float((v - lo) / (hi - lo)) with (lo, hi) = valueRange() (hi - lo = 1
//           if flat): in [0, 1] like the others, so the RGBA16_SNORM gradient volume and the
//           gradient scale work unchanged; computed once, in float, for GPU and CPU alike.
// so raw = s * scale + offset with (scale, offset) = storageToRaw(volume).
#include "sss/volume.h"

#include <glm/vec2.hpp>

#include <cstdint>
#include <cstring>

namespace sss::detail {

struct StorageToRaw {
    double scale, offset;
};

inline StorageToRaw storageToRaw(const Volume& volume) {
    switch (volume.type()) {
    case VoxelType::UInt8: return {255.0, 0.0};
    case VoxelType::UInt16: return {65535.0, 0.0};
    case VoxelType::Int16: return {65535.0, -32768.0};
    case VoxelType::Float32: break;
    }
    const auto [lo, hi] = volume.valueRange();
    return {hi > lo ? hi - lo : 1.0, lo};
}

// 16-bit storage code of voxel i of an integer type: the value for UInt8/UInt16, value + 32768
// for Int16 (what the R16 texture holds).
inline unsigned storageCode(const uint8_t* bytes, VoxelType type, std::size_t i) {
    if (type == VoxelType::UInt8) return bytes[i];
    const unsigned u = static_cast<unsigned>(bytes[2 * i] | (bytes[2 * i + 1] << 8));
    return type == VoxelType::Int16 ? u ^ 0x8000u : u;  // flipping the sign bit adds 32768
}

// Raw value of voxel i in data units.
inline double rawValue(const uint8_t* bytes, VoxelType type, std::size_t i) {
    if (type != VoxelType::Float32) {
        const double code = static_cast<double>(storageCode(bytes, type, i));
        return type == VoxelType::Int16 ? code - 32768.0 : code;
    }
    float f;
    std::memcpy(&f, bytes + 4 * i, 4);  // little-endian host (x86-64, aarch64)
    return static_cast<double>(f);
}

// Float32 only: the normalised float the R32F texture holds for voxel i.
inline float floatSample(const uint8_t* bytes, std::size_t i, StorageToRaw m) {
    return static_cast<float>((rawValue(bytes, VoxelType::Float32, i) - m.offset) / m.scale);
}

// The value the texture holds for voxel i before the unorm normalisation: the storage code for
// integer types, floatSample for Float32. Sample s = storedValue / storedPerSample.
inline double storedValue(const uint8_t* bytes, VoxelType type, std::size_t i, StorageToRaw m) {
    if (type != VoxelType::Float32) return static_cast<double>(storageCode(bytes, type, i));
    return static_cast<double>(floatSample(bytes, i, m));
}

// The unorm divisor: 255, 65535, or 1 for Float32 (R32F holds the sample itself).
constexpr double storedPerSample(VoxelType type) {
    return type == VoxelType::UInt8 ? 255.0 : type == VoxelType::Float32 ? 1.0 : 65535.0;
}

// (a, b) with TF coordinate x = clamp(s * a + b, 0, 1) for a texture sample s, from
// Volume::transferFunctionRange() (lo, hi): raw = s * scale + offset, x = (raw - lo) / (hi - lo).
inline glm::dvec2 sampleToTfCoordinate(const Volume& volume) {
    const auto [lo, hi] = volume.transferFunctionRange();
    const StorageToRaw m = storageToRaw(volume);
    return {m.scale / (hi - lo), (m.offset - lo) / (hi - lo)};
}

}  // namespace sss::detail
