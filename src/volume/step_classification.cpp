#include "volume/step_classification.h"

#include <algorithm>
#include <cmath>

namespace sss::detail {

namespace {
constexpr int kLeastMaxTextureSize = 16384;  // GL 4.5, GL_MAX_TEXTURE_SIZE

int refinement(int entries) {
    return std::clamp((kLeastMaxTextureSize - 1) / std::max(entries - 1, 1), 1, kStepClassificationRefinement);
}
}  // namespace

int stepClassificationEntries(int entries) { return (entries - 1) * refinement(entries) + 1; }

std::vector<glm::vec4> stepClassification(const std::vector<glm::vec4>& transferFunction, float stepVoxels) {
    const int entries = static_cast<int>(transferFunction.size());
    const int r = refinement(entries);
    std::vector<glm::vec4> table(static_cast<size_t>(stepClassificationEntries(entries)));
    for (size_t j = 0; j < table.size(); ++j) {
        const int i = std::min(static_cast<int>(j) / r, entries - 2);
        const float f = static_cast<float>(static_cast<int>(j) - i * r) / static_cast<float>(r);
        glm::vec4 e = transferFunction[i] * (1.0f - f) + transferFunction[i + 1] * f;
        // As the shader's correctOpacity (shaders/volume/transfer_function.glsl).
        e.a = 1.0f - std::pow(1.0f - std::min(e.a, 1.0f), stepVoxels);
        table[j] = e;
    }
    return table;
}

gl::Texture uploadStepClassification(const std::vector<glm::vec4>& table) {
    gl::Texture texture =
        gl::Texture::create2D(GL_RGBA32F, static_cast<int>(table.size()), 1, "transfer function for the ray step");
    texture.upload(GL_RGBA, GL_FLOAT, table.data());
    texture.setFilter(GL_LINEAR, GL_LINEAR);
    return texture;
}

gl::Texture uploadOpacities(const std::vector<glm::vec4>& table, glm::ivec2 size, GLenum internalFormat,
                            std::string_view label) {
    std::vector<float> opacities(static_cast<size_t>(size.x) * static_cast<size_t>(size.y));
    std::transform(table.begin(), table.begin() + static_cast<std::ptrdiff_t>(opacities.size()), opacities.begin(),
                   [](const glm::vec4& texel) { return texel.a; });
    gl::Texture texture = gl::Texture::create2D(internalFormat, size.x, size.y, label);
    texture.upload(GL_RED, GL_FLOAT, opacities.data());
    texture.setFilter(GL_LINEAR, GL_LINEAR);
    return texture;
}

}  // namespace sss::detail
