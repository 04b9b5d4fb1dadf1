#pragma once
/// @file
/// Clip planes and a crop box for volumes: what is cut away is neither seen nor, unless asked,
/// casts shadows, so a cut face is lit like the inside it exposes. Applies to the ray casters,
/// the light volume and its eye pass, the GPU path tracer and the CPU references; meshes of a
/// hybrid scene are not clipped.
#include "sss/api.h"
#include <glm/vec3.hpp>

#include <string>
#include <vector>

SSS_BEGIN_API

namespace sss {

/// Where a VolumeClip's crop box or planes are given.
enum class CropSpace {
    Data,   ///< the volume's normalised data coordinates, [0, 1] per axis
    World,  ///< world coordinates: a box aligned with the world's axes, whatever the volume's placement
};

/// A plane through `point`; the half-space its normal points into is kept. In world space, or
/// in the volume's normalised data coordinates (VolumeClip::planeSpace).
struct ClipPlane {
    glm::vec3 point{0.0f};
    glm::vec3 normal{0.0f, 0.0f, 1.0f};  ///< non-zero; need not be unit length
    bool operator==(const ClipPlane&) const = default;
};

struct VolumeClip {
    static constexpr int kMaxPlanes = 6;
    /// Up to kMaxPlanes planes: a sample is kept where it is on the kept side of every plane.
    std::vector<ClipPlane> planes;
    /// Where the planes are given: World (the default), or Data, where a plane keeps the points
    /// p of [0, 1]^3 with dot(normal, p - point) >= 0 (n . p + d >= 0 with d = -n . point).
    CropSpace planeSpace = CropSpace::World;
    /// The box kept. In CropSpace::Data (the default) the volume's normalised data coordinates:
    /// (0,0,0) is the first voxel's corner, (1,1,1) the last one's far corner, as a VTK cropping
    /// region; the default is the whole volume. In CropSpace::World, world coordinates.
    glm::vec3 cropMin{0.0f};
    glm::vec3 cropMax{1.0f};
    CropSpace cropSpace = CropSpace::Data;
    /// Clipped matter still shadows (and scatters light onto) what is kept (default: off).
    bool clippedMatterCastsShadows = false;

    /// Nothing is cut: no planes and the whole crop box.
    bool clipsNothing() const;
    bool operator==(const VolumeClip&) const = default;
};

/// Throws ErrorKind::InvalidArgument naming `context` and the field: more than kMaxPlanes
/// planes, a zero or non-finite normal or point, a crop box that is empty (or, in data space,
/// leaves [0, 1]).
void validate(const VolumeClip& clip, const std::string& context = {});

}  // namespace sss

SSS_END_API
