#pragma once
// Pre-integrated classification (Engel, Kraus & Ertl 2001): the colour and opacity of a whole ray
// segment between two samples, assuming the data value changes linearly between them, looked up
// from a 2D table indexed by the values at the segment's ends. A point-sampled transfer function
// with steep opacity misses a thin structure whenever both samples fall beside it (wood grain
// and moire at step 1, noise once jittered); the segment integral sees every value the data
// passes through between the samples.
#include "gl/texture.h"

#include <glm/vec4.hpp>

#include <vector>

namespace sss::detail {

/// The table's side: at most this many values (or the transfer function's entries, if fewer).
/// Two layers of 256 x 256 RGBA16F are 512 kiB; finer transfer functions keep their detail in segments that
/// cross it, and lose it only within one table cell.
inline constexpr int kPreintegrationMaxSize = 256;

/// The table for `transferFunction` (entries as TransferFunction::table: entry n belongs to
/// value n / (N - 1), linearly interpolated between entries as the GPU's lookup is) and segments
/// `segmentVoxels` long (opacities are defined per voxel): two layers of size x size texels,
/// row-major with the front value along x and the back value along y. Layer 0 holds the
/// segment's premultiplied colour C = integral of colour x opacity x transmittance before it,
/// and its opacity alpha; layer 1 (in .r) the opacity-weighted mean position of what the segment
/// adds, as a fraction of the segment from its front, times alpha (premultiplied, so that it
/// interpolates). Shading belongs there: in dense material, the segment's end lies in the shadow
/// of the very surface the segment holds. Integrated in sub-steps of half a
/// transfer-function entry (at most 256 per segment). On the diagonal it equals the point
/// classification: C = colour x alpha, alpha = 1 - (1 - a)^segmentVoxels.
std::vector<glm::vec4> preintegrate(const std::vector<glm::vec4>& transferFunction, int size, float segmentVoxels);

/// The table side used for a transfer function of `entries` entries.
int preintegrationSize(int entries);

/// Where, as a fraction from its front, a homogeneous stretch of optical depth `tau` adds its
/// light on average (weighted by opacity x transmittance): 1/2 when thin, towards 0 when dense.
double meanContributionDepth(double tau);

/// The table as a two-layer RGBA16F array texture (half floats keep 3 digits at every magnitude), linearly filtered, clamped at the edges.
gl::Texture uploadPreintegration(const std::vector<glm::vec4>& table, int size);

}  // namespace sss::detail
