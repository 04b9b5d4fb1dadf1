#include "volume/preintegration.h"

#include "util/parallel.h"

#include <algorithm>
#include <cmath>

namespace sss::detail {

int preintegrationSize(int entries) { return std::clamp(entries, 2, kPreintegrationMaxSize); }

std::vector<glm::vec4> preintegrate(const std::vector<glm::vec4>& transferFunction, int size, float segmentVoxels) {
    const int entries = static_cast<int>(transferFunction.size());
    // Alpha is interpolated between entries, as by the GPU's lookup (interpolating the extinction
    // instead differs by 2 % on the ramps of a thin band). Opaque entries are clamped so that a
    // voxel of them lets 1e-7 through (exactly 0 would give inf and NaN in the sums).
    std::vector<glm::vec4> tf(transferFunction);
    for (glm::vec4& e : tf) e.a = std::min(e.a, 1.0f - 1e-7f);
    std::vector<glm::vec4> table(2 * static_cast<size_t>(size) * size);
    const size_t layer = static_cast<size_t>(size) * size;
    parallelFor(
        0, size,
        [] { return 0; },
        [&](int, std::int64_t back) {
            const double xBack = double(back) / (size - 1);
            for (int front = 0; front < size; ++front) {
                const double xFront = double(front) / (size - 1);
                // Two sub-steps per transfer-function entry crossed (the TF is linear between
                // entries, its transmittance is not): within 5e-3 of a fine sum on a thin band.
                const int steps =
                    std::clamp(static_cast<int>(std::ceil(2.0 * std::abs(xBack - xFront) * (entries - 1))), 1, 256);
                const float subVoxels = segmentVoxels / static_cast<float>(steps);
                const float du = static_cast<float>((xBack - xFront) * (entries - 1) / steps);
                float u = static_cast<float>(xFront * (entries - 1)) + 0.5f * du;
                float r = 0.0f, g = 0.0f, b = 0.0f, depth = 0.0f, transmittance = 1.0f;
                for (int k = 0; k < steps; ++k, u += du) {
                    const float clamped = std::clamp(u, 0.0f, static_cast<float>(entries - 1));
                    const int i = std::min(static_cast<int>(clamped), entries - 2);
                    const float f = clamped - static_cast<float>(i);
                    const glm::vec4 e = tf[i] * (1.0f - f) + tf[i + 1] * f;
                    const float tau = -std::log1p(-e.a) * subVoxels;
                    const float w = transmittance * -std::expm1(-tau);
                    r += w * e.r;
                    g += w * e.g;
                    b += w * e.b;
                    depth += w * (static_cast<float>(k) + static_cast<float>(meanContributionDepth(tau))) / steps;
                    transmittance -= w;
                }
                const size_t texel = static_cast<size_t>(back) * size + front;
                table[texel] = glm::vec4(r, g, b, 1.0f - transmittance);
                table[layer + texel] = glm::vec4(depth, 0.0f, 0.0f, 0.0f);
            }
        },
        [](int) {});
    return table;
}

double meanContributionDepth(double tau) {
    // The mean of x under the density tau e^(-tau x) on [0, 1]; its series where it cancels
    // (the next term, tau^3 / 720, is below 2e-6 there).
    if (tau < 0.1) return 0.5 - tau / 12.0;
    return 1.0 / tau - 1.0 / std::expm1(tau);
}

gl::Texture uploadPreintegration(const std::vector<glm::vec4>& table, int size) {
    gl::Texture texture = gl::Texture::create2DArray(GL_RGBA16F, size, size, 2, "pre-integrated transfer function");
    texture.upload(GL_RGBA, GL_FLOAT, table.data());
    texture.setFilter(GL_LINEAR, GL_LINEAR);
    return texture;
}

}  // namespace sss::detail
