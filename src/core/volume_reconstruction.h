#pragma once
// The field between voxel centres on the CPU (VolumeReconstruction), as the shaders reconstruct
// it (shaders/volume/reconstruction.glsl): what the references sample and what the empty-space
// and majorant bounds must cover.
#include "sss/volume.h"

#include <array>

namespace sss::detail {

/// Voxels a sample reads beyond the one at or below it, on each side along each axis: trilinear
/// reads voxels floor(x) and floor(x) + 1, the cubic B-spline floor(x) - 1 to floor(x) + 2
/// (x = tc n - 0.5). Bounds over a region widen by this many voxels.
constexpr int reconstructionReach(VolumeReconstruction r) { return r == VolumeReconstruction::CubicBSpline ? 2 : 1; }

/// The uniform cubic B-spline's weights of voxels floor(x) - 1 .. floor(x) + 2 at fraction
/// f = x - floor(x): non-negative, summing to 1.
inline std::array<double, 4> cubicBSplineWeights(double f) {
    const double f2 = f * f, f3 = f2 * f;
    const double w0 = (1.0 - f) * (1.0 - f) * (1.0 - f) / 6.0;
    const double w1 = (4.0 - 6.0 * f2 + 3.0 * f3) / 6.0;
    const double w3 = f3 / 6.0;
    return {w0, w1, 1.0 - w0 - w1 - w3, w3};
}

}  // namespace sss::detail
