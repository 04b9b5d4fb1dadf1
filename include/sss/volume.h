#pragma once
/// @file
/// Scalar volumes (8- or 16-bit unsigned voxels) on the CPU and the headerless .raw loader.

#include "sss/bounds.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

namespace sss {

/// Storage type of one voxel. UInt16 is little-endian in files and in Volume::bytes().
enum class VoxelType { UInt8, UInt16 };

/// Bytes per voxel of a type: 1 or 2.
constexpr std::size_t bytesPerVoxel(VoxelType type) { return type == VoxelType::UInt16 ? 2 : 1; }

/// What a .raw file name says about its contents.
struct RawVolumeInfo {
    glm::ivec3 dims{0};                ///< voxels along x, y, z
    VoxelType type = VoxelType::UInt8;  ///< UInt8 unless the name says uint16
    glm::vec3 spacing{1.0f};           ///< always (1,1,1): names do not carry spacing
};

/// Options of Volume::loadRaw; every set field overrides what the file name says.
struct RawLoadOptions {
    std::optional<glm::ivec3> dims;    ///< voxels along x, y, z; required if the name has none
    std::optional<VoxelType> type;     ///< default: from the name, else UInt8
    std::optional<glm::vec3> spacing;  ///< voxel size (any unit, only ratios matter); default 1
};

/// Parses names like "bonsai_256x256x256_uint8.raw" or "cthead_256x256x108_uint16.raw": the
/// first '_'/'.'-separated token of the form <int>x<int>x<int> gives dims, a token "uint8" or
/// "uint16" (case-insensitive) gives the type (UInt8 if absent). Directories in the argument
/// are ignored. Returns nullopt if there is no dims token. Dims are not validated here (a
/// "0x4x4" token is returned as is; Volume::loadRaw rejects it).
std::optional<RawVolumeInfo> parseRawVolumeName(std::string_view filename);

/// A dense 3D grid of unsigned scalars. Layout: x fastest, then y, then z, no padding.
/// Invariants: every dim in [1, 8192], total size <= 4 GiB, spacing finite and > 0, and the
/// sides dims * spacing within a factor of 1e6 of each other (worldBounds() stays non-degenerate).
class Volume {
public:
    /// Loads a headerless .raw file. dims/type come from options, else from the file name
    /// (see parseRawVolumeName); spacing from options, else (1,1,1).
    /// @throws Error Io if the file is missing or unreadable; InvalidArgument if dims are unknown
    ///         or invalid, or spacing is invalid; Parse if the file size does not match.
    ///         Messages start with "Volume::loadRaw: <path>: ".
    static Volume loadRaw(const std::filesystem::path& path, const RawLoadOptions& options = {});

    /// Wraps voxel bytes (little-endian for UInt16) in a volume.
    /// @throws Error InvalidArgument if dims are not positive, too large (a side > 8192 or more
    ///         than 4 GiB), bytes.size() != voxelCount * bytesPerVoxel, or spacing is not finite
    ///         and > 0.
    static Volume fromData(glm::ivec3 dims, VoxelType type, std::vector<uint8_t> bytes,
                           glm::vec3 spacing = glm::vec3(1.0f));

    /// Same as the free function sss::parseRawVolumeName.
    static std::optional<RawVolumeInfo> parseRawVolumeName(std::string_view filename) {
        return sss::parseRawVolumeName(filename);
    }

    glm::ivec3 dims() const { return m_dims; }        ///< voxels along x, y, z
    glm::vec3 spacing() const { return m_spacing; }   ///< voxel size along x, y, z
    VoxelType type() const { return m_type; }         ///< storage type
    const std::vector<uint8_t>& bytes() const { return m_bytes; }  ///< raw little-endian voxels
    /// Number of voxels, dims.x * dims.y * dims.z.
    std::size_t voxelCount() const {
        return static_cast<std::size_t>(m_dims.x) * static_cast<std::size_t>(m_dims.y) *
               static_cast<std::size_t>(m_dims.z);
    }

    /// Raw value of voxel (x, y, z). @throws Error InvalidArgument if outside dims.
    uint16_t valueAt(int x, int y, int z) const;
    /// Voxel value scaled to [0,1]: value/255 (UInt8) or value/65535 (UInt16).
    /// @throws Error InvalidArgument if outside dims.
    float normalizedAt(int x, int y, int z) const;
    /// Smallest and largest raw value (computed once, at construction).
    std::pair<uint16_t, uint16_t> valueRange() const { return m_range; }
    /// The box centred at the origin whose largest side is 1, other sides proportional to
    /// dims * spacing. This is where renderers place the volume in world space.
    Bounds worldBounds() const;
    /// The raw values that a transfer function's domain [0,1] spans: a voxel of raw value v has
    /// the TF coordinate x = clamp((v - lo) / (hi - lo), 0, 1). (0, 255) for UInt8 (the whole
    /// type range, the thesis's convention); valueRange() for UInt16, since 16-bit data usually
    /// fills only part of its range (12-bit CT), with hi raised to lo + 1 if all voxels are equal.
    /// The renderers classify with it, and a transfer-function editor's x axis shows it.
    std::pair<double, double> transferFunctionRange() const;
    /// Counts of raw values in `bins` equal-width bins over the whole type range (0..255 or
    /// 0..65535, not valueRange()); bin = value * bins / (typeMax + 1). Default 256 bins.
    /// Counts saturate at UINT32_MAX.
    /// @throws Error InvalidArgument if bins < 1 or bins > 65536.
    std::vector<uint32_t> histogram(int bins = 256) const;
    /// Counts of raw values in `bins` equal-width bins over range = (lo, hi):
    /// bin = floor((value - lo) / (hi - lo) * bins), with hi itself in the last bin; values
    /// outside [lo, hi] are not counted. With transferFunctionRange(), bin i holds the voxels
    /// whose TF coordinate is in [i / bins, (i + 1) / bins), what a TF editor draws under x.
    /// Counts saturate at UINT32_MAX.
    /// @throws Error InvalidArgument if bins < 1 or bins > 65536, or unless lo < hi, both finite.
    std::vector<uint32_t> histogram(int bins, std::pair<double, double> range) const;

private:
    Volume() = default;

    glm::ivec3 m_dims{0};
    VoxelType m_type = VoxelType::UInt8;
    glm::vec3 m_spacing{1.0f};
    std::vector<uint8_t> m_bytes;
    std::pair<uint16_t, uint16_t> m_range{0, 0};
};

}  // namespace sss
