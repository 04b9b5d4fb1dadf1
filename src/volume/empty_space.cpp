#include "volume/empty_space.h"

#include "core/voxel_storage.h"
#include "core/volume_reconstruction.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace sss::detail {

OccupancyGrid::OccupancyGrid(const Volume& volume) {
    const glm::ivec3 dims = volume.dims();
    m_bricks = (dims + kBrickVoxels - 1) / kBrickVoxels;
    const size_t count = static_cast<size_t>(m_bricks.x) * m_bricks.y * m_bricks.z;
    for (Ranges& r : m_ranges) {
        r.min.assign(count, 1.0f);
        r.max.assign(count, 0.0f);
    }
    // The texture's samples (voxel_storage.h), as the shader's classify() sees them.
    const float scale = 1.0f / static_cast<float>(storedPerSample(volume.type()));
    const StorageToRaw storage = storageToRaw(volume);
    // A sample inside brick b mixes voxels up to `reach` beyond the brick on each side (one
    // trilinear, two cubic: volume_reconstruction.h), so each voxel widens the range of every
    // brick whose extended footprint contains it.
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x) {
                const std::size_t index = (static_cast<std::size_t>(z) * dims.y + y) * dims.x + x;
                const float value =
                    static_cast<float>(storedValue(volume.bytes().data(), volume.type(), index, storage)) * scale;
                const glm::ivec3 v(x, y, z);
                for (const VolumeReconstruction r : {VolumeReconstruction::Trilinear, VolumeReconstruction::CubicBSpline}) {
                    const int reach = reconstructionReach(r);
                    Ranges& ranges = m_ranges[static_cast<int>(r)];
                    const glm::ivec3 lo = glm::max(glm::ivec3(0), (v - reach) / kBrickVoxels);
                    const glm::ivec3 hi = glm::min(m_bricks - 1, (v + reach) / kBrickVoxels);
                    for (int bz = lo.z; bz <= hi.z; ++bz)
                        for (int by = lo.y; by <= hi.y; ++by)
                            for (int bx = lo.x; bx <= hi.x; ++bx) {
                                const size_t i = (static_cast<size_t>(bz) * m_bricks.y + by) * m_bricks.x + bx;
                                ranges.min[i] = std::min(ranges.min[i], value);
                                ranges.max[i] = std::max(ranges.max[i], value);
                            }
                }
            }
    m_texture = gl::Texture::create3D(GL_R8, m_bricks, "empty-space occupancy");
    m_texture.setFilter(GL_NEAREST, GL_NEAREST);
    m_neighbourhoods = gl::Texture::create3D(GL_R8, m_bricks, "empty-space occupied neighbourhoods");
    m_neighbourhoods.setFilter(GL_NEAREST, GL_NEAREST);
}

namespace {

// Marks every brick next to a marked one (26-neighbourhood): one pass per axis, each spreading
// the marks one brick along it.
std::vector<std::uint8_t> dilateByOneBrick(std::vector<std::uint8_t> marks, glm::ivec3 bricks) {
    const auto index = [&](glm::ivec3 b) { return (static_cast<size_t>(b.z) * bricks.y + b.y) * bricks.x + b.x; };
    for (int axis = 0; axis < 3; ++axis) {
        std::vector<std::uint8_t> spread(marks.size(), 0);
        glm::ivec3 b;
        for (b.z = 0; b.z < bricks.z; ++b.z)
            for (b.y = 0; b.y < bricks.y; ++b.y)
                for (b.x = 0; b.x < bricks.x; ++b.x) {
                    std::uint8_t m = marks[index(b)];
                    for (int step : {-1, 1}) {
                        glm::ivec3 n = b;
                        n[axis] += step;
                        if (n[axis] >= 0 && n[axis] < bricks[axis]) m = std::max(m, marks[index(n)]);
                    }
                    spread[index(b)] = m;
                }
        marks = std::move(spread);
    }
    return marks;
}

}  // namespace

void OccupancyGrid::update(const std::vector<glm::vec4>& table, glm::vec2 valueScaleOffset,
                           VolumeReconstruction reconstruction) {
    m_reconstruction = reconstruction;
    const Ranges& ranges = m_ranges[static_cast<int>(reconstruction)];
    const std::vector<float>& rangeMin = ranges.min;
    const std::vector<float>& rangeMax = ranges.max;
    const int entries = static_cast<int>(table.size());
    // Largest opacity over table entries [a, b]: a prefix structure is overkill for 256 entries.
    auto maxOpacity = [&](int a, int b) {
        float m = 0.0f;
        for (int i = a; i <= b; ++i) m = std::max(m, table[static_cast<size_t>(i)].a);
        return m;
    };
    std::vector<std::uint8_t> occupied(rangeMin.size());
    m_maxOpacity.assign(rangeMin.size(), 0.0f);
    size_t count = 0;
    for (size_t i = 0; i < rangeMin.size(); ++i) {
        // TF coordinates of the range (clamped as classify() does), then the table entries the
        // linear lookup can blend: the ones around each end.
        const float lo = std::clamp(rangeMin[i] * valueScaleOffset.x + valueScaleOffset.y, 0.0f, 1.0f);
        const float hi = std::clamp(rangeMax[i] * valueScaleOffset.x + valueScaleOffset.y, 0.0f, 1.0f);
        const int a = std::max(0, static_cast<int>(std::floor(lo * static_cast<float>(entries - 1))));
        const int b = std::min(entries - 1, static_cast<int>(std::ceil(hi * static_cast<float>(entries - 1))));
        m_maxOpacity[i] = rangeMin[i] <= rangeMax[i] ? maxOpacity(a, b) : 0.0f;
        occupied[i] = m_maxOpacity[i] > 0.0f ? 255 : 0;
        count += occupied[i] ? 1 : 0;
    }
    m_texture.upload(GL_RED, GL_UNSIGNED_BYTE, occupied.data());
    m_neighbourhoods.upload(GL_RED, GL_UNSIGNED_BYTE, dilateByOneBrick(occupied, m_bricks).data());
    m_occupiedFraction = rangeMin.empty() ? 0.0 : static_cast<double>(count) / static_cast<double>(rangeMin.size());
}

}  // namespace sss::detail
