#pragma once
// Post-classification's table for one ray step. A transfer function's opacity is defined per
// voxel; a sample `stepVoxels` long has opacity 1 - (1 - alpha)^stepVoxels. Correcting each
// entry once, on the CPU, leaves the ray caster a table lookup per sample where it raised to a
// power (a tenth of an emission-absorption frame on llvmpipe). Interpolating corrected entries
// is not correcting the interpolated opacity; the two differ only where the opacity changes
// steeply between two TF entries, and the table is finer than the transfer function
// (kStepClassificationRefinement entries per TF interval, on the TF's own entries too): a ray
// through an edge from 0 to 0.8 within one entry ends within 1.2e-3 of per-sample correction,
// 1.7e-2 without the finer grid (tests/gl/test_volume_renderer.cpp).
#include "gl/texture.h"

#include <glm/vec4.hpp>

#include <vector>

namespace sss::detail {

inline constexpr int kStepClassificationRefinement = 4;

/// The table's entries for a transfer function of `entries` entries: (entries - 1) x the
/// refinement + 1, fewer refinements where that would pass 16384 (GL 4.5's least texture side).
int stepClassificationEntries(int entries);

/// `transferFunction` (entries as TransferFunction::table) resampled to stepClassificationEntries
/// entries, linearly between its own, with each opacity corrected for a sample `stepVoxels` long.
/// Colours are unchanged (not premultiplied).
std::vector<glm::vec4> stepClassification(const std::vector<glm::vec4>& transferFunction, float stepVoxels);

/// The table as a one-row RGBA32F texture, linearly filtered, clamped at the edges.
gl::Texture uploadStepClassification(const std::vector<glm::vec4>& table);

}  // namespace sss::detail
