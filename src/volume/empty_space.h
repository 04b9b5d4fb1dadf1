#pragma once
// Empty-space skipping: a coarse grid of bricks (kBrickVoxels^3 voxels each) that records, per
// brick, the range of values a sample inside it can take (trilinear or cubic). When the transfer
// function changes, each brick is marked occupied if the TF gives any opacity over its range; the ray
// caster jumps over unoccupied bricks in whole steps, so its samples (and image) are exactly
// those of a caster without skipping.
#include "gl/texture.h"
#include "sss/volume.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <vector>

namespace sss::detail {

inline constexpr int kBrickVoxels = 8;
static_assert((kBrickVoxels & (kBrickVoxels - 1)) == 0, "kBrickVoxels must be a power of two");

/// The shaders' `textureToBrick`: a sample's brick is ivec3(tc * this), exactly the integer
/// division of its voxel by kBrickVoxels, as that is a power of two.
inline glm::vec3 textureToBrick(const glm::ivec3& dims) { return glm::vec3(dims) / static_cast<float>(kBrickVoxels); }

class OccupancyGrid {
public:
    /// Computes the per-brick value ranges (normalised to [0, 1] like texture samples), for
    /// each reconstruction.
    explicit OccupancyGrid(const Volume& volume);
    glm::ivec3 brickCount() const { return m_bricks; }
    /// Re-derives occupancy for a TF table (entry i at TF coordinate i/(N-1)) and the samples
    /// `reconstruction` takes, and uploads it.
    void update(const std::vector<glm::vec4>& transferFunctionTable, glm::vec2 valueScaleOffset,
                VolumeReconstruction reconstruction);
    /// The reconstruction of the last update().
    VolumeReconstruction reconstruction() const { return m_reconstruction; }
    const gl::Texture& texture() const { return m_texture; }
    /// R8 per brick, 1 where the brick or one of its 26 neighbours is occupied: a point within
    /// kBrickVoxels voxels (per axis) of a brick marked 0 samples no opacity. The light-volume
    /// sweep skips its medium samples there (shaders/volume/light_propagation.comp).
    const gl::Texture& occupiedNeighbourhoods() const { return m_neighbourhoods; }
    /// Fraction of bricks marked occupied by the last update().
    double occupiedFraction() const { return m_occupiedFraction; }
    /// Per brick (x fastest), the largest TF opacity a sample inside it can be
    /// classified to under the last update()'s table: a bound, as the path tracer's majorants
    /// need (volume/path_trace_pass.h).
    const std::vector<float>& maxOpacity() const { return m_maxOpacity; }

private:
    glm::ivec3 m_bricks{0};
    struct Ranges {
        std::vector<float> min, max;  // per brick
    };
    Ranges m_ranges[2];  // indexed by VolumeReconstruction: trilinear, cubic
    VolumeReconstruction m_reconstruction = VolumeReconstruction::Trilinear;
    std::vector<float> m_maxOpacity;  // per brick, from the last update()
    gl::Texture m_texture;            // R8, 1 = occupied
    gl::Texture m_neighbourhoods;     // R8, 1 = occupied within one brick
    double m_occupiedFraction = 1.0;
};

}  // namespace sss::detail
