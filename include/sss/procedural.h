#pragma once
/// @file
/// Procedural test meshes and volumes, deterministic on every platform we build for.

#include "sss/api.h"
#include "sss/bounds.h"
#include "sss/mesh.h"
#include "sss/volume.h"

#include <glm/vec3.hpp>

SSS_BEGIN_API

namespace sss {

/// UV sphere centred at the origin with exact (analytic) normals: 2 pole vertices plus
/// rings-1 latitude circles of `segments` vertices; each of the `rings` bands has `segments`
/// quads of 2 triangles, and the quads touching a pole are kept as one real and one degenerate
/// triangle. 20x20 gives 382 vertices and 800 triangles (the reference study's sphere).
/// @throws Error InvalidArgument unless segments in [3, 4096], rings in [2, 4096], radius
///         finite and > 0.
Mesh makeUvSphere(int segments = 20, int rings = 20, float radius = 1.0f);

/// Torus around the y axis, centred at the origin, with exact normals:
/// majorSegments * minorSegments vertices and twice as many triangles (no seam duplicates).
/// @throws Error InvalidArgument unless 0 < minorRadius < majorRadius (finite) and both
///         segment counts are in [3, 4096].
Mesh makeTorus(float majorRadius = 0.7f, float minorRadius = 0.3f, int majorSegments = 48,
               int minorSegments = 24);

/// A unit sphere carved by deep folds: a concave test model with overhangs, standing in for the
/// Happy Buddha's robe. Three narrow grooves run around it (slots deeper than they are wide:
/// their lips shadow their floors, depth edges seen from most light directions) and seven folds
/// run from pole to pole. On the UV sphere's grid (theta from the +y pole, phi around y) the
/// radius is 1 - 0.3 sin(theta)^2 max(0, cos(8 theta))^4 - 0.2 sin(theta)^2 (0.5 + 0.5 cos(7 phi))^6,
/// with smooth area-weighted normals. 160 x 128 gives 20 322 vertices and 40 960 triangles.
/// @throws Error InvalidArgument unless segments in [3, 4096] and rings in [2, 4096].
Mesh makeFolds(int segments = 160, int rings = 128);

/// Axis-aligned box of the given size centred at the origin: 24 vertices (4 per face, flat
/// normals), 12 triangles. Default 1.6 x 1.0 x 0.2, a slab for translucency tests. Texture
/// coordinates project the box along z: (0, 0) at its -x, -y edge and (1, 1) at +x, +y, so the top
/// face (+z) shows a texture once, upright, seen from above.
/// @throws Error InvalidArgument unless every size component is finite and > 0.
Mesh makeSlab(glm::vec3 size = glm::vec3(1.6f, 1.0f, 0.2f));

/// The walls of a Cornell box (open towards +z) around `content`: a cube of side
/// 1.6 x the content's largest extent, centred on it, with normals facing inwards. White floor,
/// ceiling and back wall; red left (-x) and green right (+x) walls.
struct CornellBox {
    Mesh white, red, green;
    glm::vec3 whiteColor{0.73f, 0.71f, 0.68f};
    glm::vec3 redColor{0.63f, 0.065f, 0.05f};
    glm::vec3 greenColor{0.14f, 0.45f, 0.09f};
    Bounds bounds{};  ///< the box itself
};
/// @throws Error InvalidArgument if `content` is empty.
CornellBox makeCornellBox(const Bounds& content);

/// n^3 uint8 volume with four soft Gaussian blobs of different sizes and peak values.
/// @throws Error InvalidArgument unless n in [2, 1024].
Volume makeBlobsVolume(int n = 64);

/// n^3 uint8 hollow spherical shell centred in the volume, 255 inside the shell, 0 elsewhere,
/// with edges softened over about a voxel. outerRadius and thickness are fractions of the side.
/// @throws Error InvalidArgument unless n in [2, 1024], 0 < outerRadius <= 0.5 and
///         0 < thickness <= outerRadius.
Volume makeShellVolume(int n = 64, float outerRadius = 0.42f, float thickness = 0.08f);

/// n^3 uint8 look-alike of the C60 "bucky" data set: 60 Gaussian blobs at the vertices of a
/// truncated icosahedron (radius 0.35 of the side) on a faint spherical halo.
/// @throws Error InvalidArgument unless n in [2, 1024].
Volume makeBuckyLikeVolume(int n = 32);

}  // namespace sss

SSS_END_API
