#pragma once
/// @file
/// Isosurfaces of a volume as triangle meshes (component io, through VTK's flying edges): a CT
/// scan's skin or bone as a translucent mesh beside, or inside, the volume rendering of the same
/// data. The mesh keeps the voxel spacing: its coordinates are the volume's physical units
/// (millimetres for medical data), centred on the volume's centre, so it renders at its real
/// size with MeshRenderOptions::millimetresPerUnit = 1, and scaling it by 1 / (the largest side
/// of dims * spacing) lays it over the volume's Volume::worldBounds().

#include "sss/api.h"
#include "sss/mesh.h"
#include "sss/volume.h"

SSS_BEGIN_API

namespace sss {

struct IsosurfaceOptions {
    /// The iso value in the volume's raw data units (Volume::valueAt; Hounsfield units for Int16
    /// CT), finite and strictly inside Volume::valueRange().
    double value = 0.0;
    /// Passes of windowed-sinc smoothing, which removes the voxel staircase without shrinking
    /// the surface, >= 0 (default: 15; 0 keeps the raw marching-cubes vertices).
    int smoothingIterations = 15;
    /// Decimate to about this many triangles (quadric decimation), >= 0 (default: 0, keep all).
    int maxTriangles = 0;
};

/// The surface where the volume's values cross `options.value`, with smooth vertex normals
/// pointing towards lower values (out of a CT head's skin into the air). Coordinates: see the
/// file comment.
/// @throws Error InvalidArgument for options out of range (naming the field) or when no voxel
///         pair crosses the value (an empty surface); Unsupported when libsss was built without
///         VTK (SSS_WITH_VTK=OFF).
Mesh extractIsosurface(const Volume& volume, const IsosurfaceOptions& options);

/// An isosurface where the renderers place its volume, and the scale that keeps it life-size.
struct WorldIsosurface {
    Mesh mesh;  ///< extractIsosurface's mesh laid over the volume's Volume::worldBounds()
    /// MeshRenderOptions::millimetresPerUnit for `mesh`: one world unit is the volume's largest
    /// side, dims * spacing, in millimetres.
    double millimetresPerUnit = 1.0;
};

/// extractIsosurface() in the volume's world box, for a volume whose spacing unit is
/// `millimetresPerVolumeUnit` millimetres (1 for medical data), > 0 and finite. Throws as
/// extractIsosurface(), and InvalidArgument naming millimetresPerVolumeUnit.
WorldIsosurface extractIsosurfaceInWorldBox(const Volume& volume, const IsosurfaceOptions& options,
                                            double millimetresPerVolumeUnit = 1.0);

}  // namespace sss

SSS_END_API
