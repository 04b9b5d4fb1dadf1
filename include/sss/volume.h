#pragma once
/// @file
/// Scalar volumes (8/16-bit integer or 32-bit float voxels) on the CPU, the headerless .raw
/// loader and Volume::load for NRRD, MetaImage, NIfTI, VTK XML image data and DICOM series.

#include "sss/api.h"
#include "sss/bounds.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

SSS_BEGIN_API

namespace sss {

/// Storage type of one voxel. Multi-byte types are little-endian in Volume::bytes() (and in
/// .raw files); Int16 is two's complement (CT Hounsfield units), Float32 is IEEE 754.
enum class VoxelType { UInt8, UInt16, Int16, Float32 };

/// How a volume's field is reconstructed between voxel centres. Every renderer of a volume (the
/// ray caster, the light volume, both path tracers, the CPU references) takes the same one, so
/// a reference measures the field that is drawn.
enum class VolumeReconstruction {
    /// Trilinear interpolation, as the texture unit's GL_LINEAR (default): one fetch per sample.
    Trilinear,
    /// The cubic B-spline of the voxels, from eight trilinear fetches (docs/reconstruction.md).
    /// Smooth where trilinear interpolation shows the voxel staircase as terraces (rings on a
    /// coarse sphere under a steep transfer function, slice lines on CT with thick slices); it
    /// does not pass through the voxel values, and blurs the data by about a voxel.
    CubicBSpline,
};

/// Bytes per voxel of a type: 1, 2 or 4.
constexpr std::size_t bytesPerVoxel(VoxelType type) {
    return type == VoxelType::UInt8 ? 1 : type == VoxelType::Float32 ? 4 : 2;
}

/// "uint8", "uint16", "int16" or "float32".
const char* voxelTypeName(VoxelType type);

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

/// Options of Volume::load.
struct VolumeLoadOptions {
    /// Passed to Volume::loadRaw for .raw files; ignored for the other formats, whose header
    /// says dims, type and spacing.
    RawLoadOptions raw;
    /// Oblique direction matrices (not a signed permutation) are rejected unless this is set;
    /// then the voxels are kept in file order and the rotation is ignored (with a warning on
    /// the log).
    bool allowOblique = false;
};

/// Parses names like "bonsai_256x256x256_uint8.raw" or "cthead_256x256x108_uint16.raw": the
/// first '_'/'.'-separated token of the form <int>x<int>x<int> gives dims, a token "uint8" or
/// "uint16" (case-insensitive) gives the type (UInt8 if absent). Directories in the argument
/// are ignored. Returns nullopt if there is no dims token. Dims are not validated here (a
/// "0x4x4" token is returned as is; Volume::loadRaw rejects it).
std::optional<RawVolumeInfo> parseRawVolumeName(std::string_view filename);

/// A dense 3D grid of scalars. Layout: x fastest, then y, then z, no padding.
/// Invariants: every dim in [1, 8192], total size <= 4 GiB, spacing finite and > 0, the sides
/// dims * spacing within a factor of 1e6 of each other (worldBounds() stays non-degenerate), and
/// Float32 voxels finite.
class Volume {
public:
    /// Loads a volume, picking the reader by what the path is: a directory is a DICOM series
    /// (every file in it that parses as DICOM; slices ordered by position); ".raw" goes to
    /// loadRaw unchanged; ".nrrd"/".nhdr" NRRD, ".mhd"/".mha" MetaImage, ".nii"/".nii.gz"
    /// NIfTI-1 or -2, ".vti" VTK XML image data (extensions case-insensitive). Readers: teem
    /// (NRRD), MetaIO as VTK bundles it (MetaImage), VTK (NIfTI, .vti, DICOM).
    /// Dims, type and spacing come from the header. Voxels are reordered so that x, y, z run
    /// along the file's world/patient axes in increasing order: a direction matrix that is a
    /// signed permutation is undone (axes swapped, flipped axes reversed); NIfTI uses its qform
    /// (else sform) matrix; a DICOM series its ImageOrientationPatient. Voxel types: uint8,
    /// int16, uint16, float32; int8 is widened to int16, and uint32/int32/float64 are rejected,
    /// as is more than one component. DICOM rescale slope/intercept are applied by VTK's
    /// reader (Hounsfield units; float32 when they are fractional); NIfTI scl_slope/scl_inter
    /// other than 1/0 give float32. Not thread-safe with other code using VTK's output window or std::cout
    /// while a load runs (their messages are captured for the exception).
    /// @throws Error Io if the path is missing or unreadable; Parse if the reader fails or the
    ///         file is truncated or inconsistent, or for a voxel type, component count or (without
    ///         allowOblique) orientation that is not supported; InvalidArgument for an unknown
    ///         extension, or as fromData. Messages start with "Volume::load: <path>: " (loadRaw's
    ///         with its own).
    static Volume load(const std::filesystem::path& path, const VolumeLoadOptions& options = {});

    /// Loads a headerless .raw file. dims/type come from options, else from the file name
    /// (see parseRawVolumeName); spacing from options, else (1,1,1).
    /// @throws Error Io if the file is missing or unreadable; InvalidArgument if dims are unknown
    ///         or invalid, or spacing is invalid; Parse if the file size does not match.
    ///         Messages start with "Volume::loadRaw: <path>: ".
    static Volume loadRaw(const std::filesystem::path& path, const RawLoadOptions& options = {});

    /// Wraps voxel bytes (little-endian for multi-byte types) in a volume.
    /// @throws Error InvalidArgument if dims are not positive, too large (a side > 8192 or more
    ///         than 4 GiB), bytes.size() != voxelCount * bytesPerVoxel, spacing is not finite
    ///         and > 0, or a Float32 voxel is NaN or infinite.
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

    /// Raw value of voxel (x, y, z) in data units (exact for every type: a Hounsfield unit for
    /// Int16 CT). @throws Error InvalidArgument if outside dims.
    double valueAt(int x, int y, int z) const;
    /// Voxel value scaled to [0,1] over the type's range: value/255 (UInt8), value/65535
    /// (UInt16), (value + 32768)/65535 (Int16); Float32 has no type range, so over valueRange()
    /// (0 if all voxels are equal). @throws Error InvalidArgument if outside dims.
    float normalizedAt(int x, int y, int z) const;
    /// Smallest and largest raw value (computed once, at construction).
    std::pair<double, double> valueRange() const { return m_range; }
    /// The box centred at the origin whose largest side is 1, other sides proportional to
    /// dims * spacing. This is where renderers place the volume in world space.
    Bounds worldBounds() const;
    /// The raw values that a transfer function's domain [0,1] spans: a voxel of raw value v has
    /// the TF coordinate x = clamp((v - lo) / (hi - lo), 0, 1). The value window if one is set
    /// (setValueWindow); else (0, 255) for UInt8 (the whole type range, the thesis's convention)
    /// and valueRange() for the other types, since 16-bit and float data usually fill only part
    /// of their range (12-bit CT), with hi raised to lo + max(1, |lo| * 2^-20) if all voxels are
    /// equal.
    /// Every renderer (GPU, VolumeReference, VolumePathTracer) classifies with it, and a
    /// transfer-function editor's x axis shows it.
    std::pair<double, double> transferFunctionRange() const;
    /// Sets the value window (in raw data units, e.g. Hounsfield units) that
    /// transferFunctionRange() returns instead of the data range: a CT window such as
    /// (-1000, 2000). Values outside it clamp to the TF's ends. nullopt restores the default.
    /// Renderers read it when the volume is given to them (setVolume, construction).
    /// @throws Error InvalidArgument unless lo < hi, both finite.
    void setValueWindow(std::optional<std::pair<double, double>> window);
    /// The window set by setValueWindow, if any.
    std::optional<std::pair<double, double>> valueWindow() const { return m_window; }
    /// Counts of raw values in `bins` equal-width bins over the whole type range (0..255,
    /// 0..65535 or -32768..32767; Float32: valueRange(), widened as transferFunctionRange()
    /// does); bin = (value - typeMin) * bins / (typeMax - typeMin + 1). Default 256 bins.
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
    std::pair<double, double> transferFunctionDataRange() const;  // the default, without the window

    glm::ivec3 m_dims{0};
    VoxelType m_type = VoxelType::UInt8;
    glm::vec3 m_spacing{1.0f};
    std::vector<uint8_t> m_bytes;
    std::pair<double, double> m_range{0, 0};
    std::optional<std::pair<double, double>> m_window;
};

}  // namespace sss

SSS_END_API
