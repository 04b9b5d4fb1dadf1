#pragma once
// Light-volume test scenes and the light-volume pass run alone, shared by the sweep's and ray
// doubling's tests.
#include "volume/light_volume_pass.h"

#include <sss/light.h>
#include <sss/transfer_function.h>
#include <sss/volume.h>
#include <sss/volume_clip.h>

#include <glm/vec4.hpp>

#include <cstdint>
#include <functional>
#include <vector>

namespace sss::test::light_volumes {

/// A uint8 volume of n^3 voxels whose voxel (x, y, z) is value(x, y, z).
Volume makeVolume(int n, const std::function<uint8_t(int, int, int)>& value);

/// Binary TF: values >= 0.5 get `opacity`, below are transparent.
TransferFunction stepTf(float opacity, glm::vec3 color = glm::vec3(1.0f));

/// A light volume read back: (c, l) per voxel, x fastest.
struct LightVolumeReadback {
    glm::ivec3 dims;
    std::vector<glm::vec4> texels;
    const glm::vec4& at(int x, int y, int z) const { return texels[static_cast<size_t>((z * dims.y + y) * dims.x + x)]; }
};

/// Empty-space skipping in the propagation: off, or with the occupancy grid derived from `skipTf`
/// (the propagated TF itself when it is null).
struct Skipping {
    bool on = false;
    const TransferFunction* skipTf = nullptr;
};

/// Two small dense blobs in a 48^3 box under a two-colour TF: most bricks (8^3) and their
/// neighbourhoods are empty and some are not, and the light comes out of the blobs tinted.
Volume twoBlobsVolume();
TransferFunction twoBlobsTf();

/// Lights that exercise every kind of sweep: a directional light near a diagonal (two blended
/// sweeps, long slabs), a nearly axial one (one sweep), a point light inside (six sweeps) and, at a
/// reduced resolution, a slanted light (one sweep) whose light-volume voxels span several data
/// voxels.
struct SweepCase {
    Light light;
    float scale;
};
extern const SweepCase kSweepCases[4];

/// Runs the light-volume pass alone on `volume` under `tf` and reads the light volume back;
/// `layout`, if given, receives how the pass laid out its dispatches.
LightVolumeReadback propagate(const Volume& volume, const TransferFunction& tf, const Light& light,
                              detail::LightVolumeSettings settings = {}, Skipping skipping = {},
                              detail::LightVolumePass::SweepLayout* layout = nullptr, const VolumeClip* clip = nullptr);

}  // namespace sss::test::light_volumes
