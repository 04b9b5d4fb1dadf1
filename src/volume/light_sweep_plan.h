#pragma once
// How the light volume (light_volume_pass.h) sweeps the light through a volume and gathers its
// chromaticity over a cone: plain CPU geometry, shared by the GPU pass and by the CPU reference
// that evaluates the same model (sss/volume_reference.h, chromaticityConeScale).
#include "sss/api.h"  // SSS_API: sss::io, sss::reference and sss::scene call these in a shared build
#include "sss/bounds.h"
#include "sss/light.h"

#include <glm/vec3.hpp>

#include <vector>

namespace sss::detail {

/// One sweep of the propagation, as planned on the CPU.
struct LightSweep {
    int axis = 2;           ///< data axis the sweep runs along
    bool reversed = false;  ///< the light travels towards -axis
    float weight = 1.0f;
    int firstSlice = 0;     ///< sweep-frame slice the sweep starts at
    bool pyramid = false;   ///< owns only the voxels whose dominant light axis is its own
};

/// A directional light is swept along the axis it travels most along, in voxels. Near the
/// diagonal where that axis changes, a second sweep along the next axis is blended in, so the light
/// volume stays continuous as the light turns. `share` is the second axis's excess over the third
/// relative to both, (a2 - a3) / (a1 + a2 - 2 a3), 0.5 on the diagonal; the second sweep's weight
/// rises from 0 at kSweepBlendStart to 0.5 there. Below it one sweep is 0.1-0.4 points further
/// from the reference on real data and takes half the time (docs/light-volume-sweep.md, "One
/// sweep away from a diagonal").
inline constexpr float kSweepBlendStart = 0.42f;
SSS_API float secondSweepWeight(float share);

/// The sweeps for `light` (already in the volume's model space) over a volume of `box` whose
/// light volume has `dims` voxels. A point or spot light outside the box takes the same band,
/// with the axes ranked by how far beyond each face it is; one inside takes six sweeps.
SSS_API std::vector<LightSweep> planLightSweeps(const Light& modelSpaceLight, const Bounds& box, glm::ivec3 dims);

/// The light volume's size for a volume of `volumeDims` at `scale` (each side at least 1).
SSS_API glm::ivec3 lightVolumeDims(glm::ivec3 volumeDims, float scale);

/// Cone half-angle (radians) holding half the scattered energy of HG(g), clamped to 60 degrees.
SSS_API float chromaticityConeAngle(float g);

/// The cone gather at every slice: the previous slice's chromaticity is read at the light ray's
/// crossing (centre) and at 8 points on a ring of radius tangent x (the path between slices),
/// weighted by HG(g) at the centre and at the cone's edge; centre + 8 x ring = 1.
struct ChromaticityCone {
    float tangent = 0.0f;
    float centreWeight = 1.0f;
    float ringWeight = 0.0f;  ///< each of the 8 ring points
};
SSS_API ChromaticityCone chromaticityCone(float g);

}  // namespace sss::detail
