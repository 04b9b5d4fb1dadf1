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

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <string_view>
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

/// The opacities (alpha) of the first size.x x size.y texels of a classification table as a
/// one-channel texture (R32F or R16F), linearly filtered, clamped at the edges: for readers of
/// the opacity alone, a quarter of the channels to filter.
gl::Texture uploadOpacities(const std::vector<glm::vec4>& table, glm::ivec2 size, GLenum internalFormat,
                            std::string_view label);

}  // namespace sss::detail
