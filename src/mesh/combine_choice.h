#pragma once
// What MeshCombine::Automatic resolves to. The evaluate-once vertex estimate interpolates the
// radiosity linearly between vertices, which holds wherever the radiosity varies little across a
// triangle. Subsurface transport blurs the incident light over about one diffusion length
// 1 / sigma_tr, so without the near field the test compares the mesh's edges with that length
// and takes the paper's per-pixel maps on coarser meshes. With the near field
// (MeshRenderOptions::nearField, src/mesh/near_field.h) the pixel keeps the detail the vertices
// cannot, and the estimate was nearer the reference than the maps at every scale measured on
// meshes that follow their shape (docs/near-field.md). A mesh too coarse to follow its own shape
// (a box of two-triangle faces) leaves the vertices nothing to interpolate between: the maps.
#include "sss/materials.h"
#include "sss/mesh.h"
#include "sss/mesh_scattering_renderer.h"

#include <glm/mat4x4.hpp>

namespace sss::detail {

/// The longest edge of the triangles that hold 90 % of the surface area, in the mesh's units: the
/// area-weighted 90th percentile of each triangle's longest edge. A few long slivers do not
/// count; large faces (a box's 2-triangle sides) do.
float surfaceEdgeLength(const Mesh& mesh);

/// How far `model` stretches the mesh at most (the largest singular value of its 3x3 part).
float largestScale(const glm::mat4& model);

/// Edge length over diffusion length: `edgeLength` (scene units) times sigma_tr of the
/// narrowest-profile channel among those that reflect at least a tenth of the brightest channel's
/// diffuse reflectance (ketchup's absorbed green and blue set no scale). 0 when no channel
/// absorbs (sigma_tr = 0: the profile is wider than any mesh).
double edgeToDiffusionLength(float edgeLength, const ScatteringMaterial& material, double millimetresPerUnit);

/// The largest edgeToDiffusionLength() at which MeshCombine::Automatic takes the vertex estimate
/// (measured: tests/gl/test_mesh_accuracy.cpp, "the automatic combine ...").
inline constexpr double kVertexEstimateMaxEdgeRatio = 2.0;

/// The largest surfaceEdgeLength() over the mesh's bounding radius at which the vertex estimate
/// with the near field is taken on triangles wider than kVertexEstimateMaxEdgeRatio (measured:
/// the automatic-combine test; a 24-segment sphere, 0.26, and a two-triangle-faced slab, 2.0).
inline constexpr double kVertexEstimateMaxEdgeOverRadius = 0.5;

/// `requested` unless it is Automatic; then VertexEstimate up to kVertexEstimateMaxEdgeRatio,
/// and above it where the near field is on (`nearField` > 0) and the mesh follows its shape
/// (`edgeOverRadius` up to kVertexEstimateMaxEdgeOverRadius); PerPixel otherwise.
MeshCombine resolveCombine(MeshCombine requested, double edgeRatio, float nearField, double edgeOverRadius);

}  // namespace sss::detail
