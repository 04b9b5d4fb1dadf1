#include "mesh/textured_material.h"

#include "lighting/texture_units.h"
#include "mesh/reflectance_table.h"
#include "sss/error.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <string>
#include <vector>

namespace sss::detail {
namespace {

constexpr int kTableColumns = 4;  // texels per row: see textured_material.glsl's materialRow
constexpr int kMinSurfaceSize = 256;  // texels along the longer side of prepareSurface's textures

TexturedMaterialSummary summarise(const Image8& reflectance, const Image8* pathScale) {
    TexturedMaterialSummary s;
    std::array<double, 256> linear{};
    for (int v = 0; v < 256; ++v) linear[static_cast<size_t>(v)] = srgbToLinear(static_cast<std::uint8_t>(v));
    const auto& texels = reflectance.data();
    for (std::size_t i = 0; i < texels.size(); i += 4)
        for (int c = 0; c < 3; ++c) {
            const double r = linear[texels[i + static_cast<size_t>(c)]];
            s.meanReflectance[c] += r;
            s.maxReflectance[c] = std::max(s.maxReflectance[c], r);
        }
    s.meanReflectance /= static_cast<double>(texels.size() / 4);
    if (pathScale) {
        int smallest = 255;
        for (std::size_t i = 0; i < pathScale->data().size(); i += 4) smallest = std::min<int>(smallest, pathScale->data()[i]);
        s.minPathScale = std::max(smallest, 1) / 255.0;
    }
    return s;
}

// Row i: the profile's factors at reflectance (i / (rows - 1))^2, the same for every channel.
std::vector<float> tabulate(double eta, ScatteringProfile profile) {
    const ReflectanceTable& table = reflectanceTable(eta, profile);
    std::vector<float> rows;
    rows.reserve(static_cast<size_t>(kTexturedTableRows * kTableColumns * 4));
    for (int i = 0; i < kTexturedTableRows; ++i) {
        const double root = i / double(kTexturedTableRows - 1);
        const ReflectanceInversion at = invertReflectance(table, root * root);
        const bool calibrated = profile == ScatteringProfile::Calibrated;
        std::array<float, 16> row{};
        for (int m = 0; m < kProfileIncidenceNodes; ++m)
            row[static_cast<size_t>(m)] =
                calibrated ? static_cast<float>(profileCalibrationScale(at.reducedAlbedo, eta, profileIncidenceNode(m))) : 1.0f;
        for (int d = 0; d < kProfileThicknessNodes; ++d)
            row[static_cast<size_t>(kProfileIncidenceNodes + d)] =
                calibrated ? static_cast<float>(profileTransmissionScale(at.reducedAlbedo, eta, profileThicknessNode(d))) : 1.0f;
        row[13] = static_cast<float>(at.reducedAlbedo);
        row[14] = static_cast<float>(at.gathered);
        rows.insert(rows.end(), row.begin(), row.end());
    }
    return rows;
}

// Decoded here rather than by an sRGB texture format: llvmpipe's decode is 2 % low at the darkest
// values (sRGB 30), where the reflectance decides the whole colour.
gl::Texture uploadReflectance(const Image8& image, const char* label) {
    std::array<float, 256> linear{};
    for (int v = 0; v < 256; ++v) linear[static_cast<size_t>(v)] = static_cast<float>(srgbToLinear(static_cast<std::uint8_t>(v)));
    // GL's rows start at the bottom: flipped, texture coordinate v = 0 is the image's last row.
    const Image8 flipped = image.flippedVertically();
    std::vector<float> texels;
    texels.reserve(flipped.data().size());
    for (std::size_t i = 0; i < flipped.data().size(); i += 4)
        texels.insert(texels.end(), {linear[flipped.data()[i]], linear[flipped.data()[i + 1]], linear[flipped.data()[i + 2]], 1.0f});
    const int levels = std::bit_width(static_cast<unsigned>(std::max(image.width(), image.height())));
    gl::Texture t = gl::Texture::create2D(GL_RGBA16F, image.width(), image.height(), label, levels);
    t.upload(GL_RGBA, GL_FLOAT, texels.data());
    glGenerateTextureMipmap(t.id());
    t.setFilter(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR);
    t.setWrap(GL_REPEAT);
    return t;
}

// LogGatheredMips's level 0; the GPU builds the same chain.
gl::Texture uploadLogGathered(const Image8& reflectance, const ReflectanceTable& table) {
    const LogGatheredMips mips(reflectance, table);
    const int levels = std::bit_width(static_cast<unsigned>(std::max(mips.width(), mips.height())));
    gl::Texture t = gl::Texture::create2D(GL_RGBA16F, mips.width(), mips.height(), "material ln gathered", levels);
    t.upload(GL_RGBA, GL_FLOAT, mips.baseLevelRgba().data());
    glGenerateTextureMipmap(t.id());
    t.setFilter(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR);
    t.setWrap(GL_REPEAT);
    return t;
}

gl::Texture uploadPathScale(const Image8* image) {
    if (!image) {
        gl::Texture t = gl::Texture::create2D(GL_R8, 1, 1, "material path scale (none)");
        const std::uint8_t one = 255;
        t.upload(GL_RED, GL_UNSIGNED_BYTE, &one);
        return t;
    }
    const Image8 flipped = image->flippedVertically();
    std::vector<std::uint8_t> red;
    red.reserve(flipped.data().size() / 4);
    for (std::size_t i = 0; i < flipped.data().size(); i += 4) red.push_back(flipped.data()[i]);
    const int levels = std::bit_width(static_cast<unsigned>(std::max(image->width(), image->height())));
    gl::Texture t = gl::Texture::create2D(GL_R8, image->width(), image->height(), "material path scale", levels);
    t.upload(GL_RED, GL_UNSIGNED_BYTE, red.data());
    glGenerateTextureMipmap(t.id());
    t.setFilter(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR);
    t.setWrap(GL_REPEAT);
    return t;
}

}  // namespace

ShaderDefines texturedMaterialDefines(bool textured) {
    return {{"TEXTURED_MATERIAL", textured ? "1" : "0"},
            {"TEXTURED_TABLE_ROWS", std::to_string(kTexturedTableRows)},
            {"MIN_GATHERED", std::to_string(kMinGathered)},
            {"SURROUNDING_SHARE", std::to_string(kSurroundingShare)},
            {"SURROUNDING_NARROW", std::to_string(kSurroundingWidths[0])},
            {"SURROUNDING_WIDE", std::to_string(kSurroundingWidths[1])}};
}

TexturedMaterialGpu::TexturedMaterialGpu(const TexturedScattering& material, const Image8& reflectance,
                                         ScatteringProfile profile)
    : m_material(material), m_profile(profile) {
    material.validate();
    m_summary = summarise(reflectance, material.meanFreePathScale.get());
    const ReflectanceTable& table = reflectanceTable(material.eta, profile);
    for (int c = 0; c < 3; ++c) m_referenceGathered[c] = invertReflectance(table, m_summary.maxReflectance[c]).gathered;
    m_widest = materialFromReflectance(m_summary.maxReflectance, material.meanFreePath, material.eta, profile);
    m_widest.name = material.name;
    m_reflectance = uploadReflectance(reflectance, "material reflectance");
    m_pathScale = uploadPathScale(material.meanFreePathScale.get());
    m_logGathered = uploadLogGathered(reflectance, table);
    m_width = reflectance.width();
    m_height = reflectance.height();
    // A small texture is magnified: its per-texel results are computed on a finer grid, so that
    // they interpolate like the reflectance they come from.
    const int refine = std::max(1, (kMinSurfaceSize + std::max(m_width, m_height) - 1) / std::max(m_width, m_height));
    const int width = m_width * refine, height = m_height * refine;
    const int levels = std::bit_width(static_cast<unsigned>(std::max(width, height)));
    for (auto [texture, label] : {std::pair{&m_surfaceAlbedo, "material surface albedo"},
                                  std::pair{&m_surroundings, "material surroundings"}}) {
        *texture = gl::Texture::create2D(GL_RGBA16F, width, height, label, levels);
        texture->setFilter(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR);
        texture->setWrap(GL_REPEAT);
    }
    const std::vector<float> rows = tabulate(material.eta, profile);
    m_table = gl::Texture::create2D(GL_RGBA32F, kTableColumns, kTexturedTableRows, "material table");
    m_table.upload(GL_RGBA, GL_FLOAT, rows.data());
    m_table.setFilter(GL_LINEAR, GL_LINEAR);
}

void TexturedMaterialGpu::prepareSurface(double millimetresPerUnit) {
    const std::pair key{millimetresPerUnit, m_texelsPerUnit};
    if (m_surfaceKey == key) return;
    if (!m_surfaceProgram)
        m_surfaceProgram = gl::Program::link({{GL_COMPUTE_SHADER, "mesh/textured_surface.comp"}}, texturedMaterialDefines(true));
    bind(*m_surfaceProgram, millimetresPerUnit);
    m_surfaceAlbedo.bindImage(0, GL_WRITE_ONLY);
    m_surroundings.bindImage(1, GL_WRITE_ONLY);
    m_surfaceProgram->use();
    const glm::ivec3 size = m_surfaceAlbedo.size();
    glDispatchCompute(static_cast<GLuint>((size.x + 7) / 8), static_cast<GLuint>((size.y + 7) / 8), 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    glUseProgram(0);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(1, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glGenerateTextureMipmap(m_surfaceAlbedo.id());
    glGenerateTextureMipmap(m_surroundings.id());
    m_surfaceKey = key;
}

void TexturedMaterialGpu::bind(const gl::Program& p, double millimetresPerUnit) const {
    p.set("materialReflectance", units::kMaterialReflectance);
    p.set("materialPathScale", units::kMaterialPathScale);
    p.set("materialTable", units::kMaterialTable);
    p.set("materialSigmaT", glm::vec3(millimetresPerUnit / m_material.meanFreePath));
    p.set("referenceGathered", glm::vec3(m_referenceGathered));
    p.set("materialLogGathered", units::kMaterialLogGathered);
    p.set("materialTexelsPerUnit", static_cast<float>(m_texelsPerUnit));
    m_reflectance.bind(units::kMaterialReflectance);
    m_pathScale.bind(units::kMaterialPathScale);
    m_table.bind(units::kMaterialTable);
    m_logGathered.bind(units::kMaterialLogGathered);
    p.set("materialSurfaceAlbedo", units::kMaterialSurfaceAlbedo);
    p.set("materialSurroundings", units::kMaterialSurroundings);
    p.set("materialSurfaceRefine", std::log2(static_cast<float>(m_surfaceAlbedo.size().x) / static_cast<float>(m_width)));
    m_surfaceAlbedo.bind(units::kMaterialSurfaceAlbedo);
    m_surroundings.bind(units::kMaterialSurroundings);
}

}  // namespace sss::detail
