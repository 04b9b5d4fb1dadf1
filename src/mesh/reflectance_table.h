#pragma once
// How a textured material's reflectance becomes coefficients (sss::materialFromReflectance): the
// profile's total diffuse reflectance at normal incidence against the reduced albedo, for one eta,
// tabulated once and inverted by interpolation. The same rows give what the radiosity estimate
// gathers per unit irradiance, by which the textured passes normalise (docs/textured-materials.md).
#include "sss/api.h"
#include "sss/bssrdf.h"
#include "sss/image.h"
#include "sss/mesh.h"

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace sss::detail {

/// Reduced albedos the inversion spans: beyond them the reflectance is clamped.
inline constexpr double kMinReducedAlbedo = 1e-4;
inline constexpr double kMaxReducedAlbedo = 0.99995;

struct ReflectanceTable {
    std::vector<double> s;            ///< sqrt(1 - alpha'), ascending
    std::vector<double> reflectance;  ///< total diffuse reflectance at normal incidence, descending
    /// T(eta, 1) times the plane integral of S_d: the radiosity a flat surface lit head-on by unit
    /// irradiance sends out (before the exit Fresnel factor), without single scattering.
    std::vector<double> gathered;
};

/// The table for `eta` and `profile`, built on first use (about a second) and kept.
SSS_API const ReflectanceTable& reflectanceTable(double eta, ScatteringProfile profile);

struct ReflectanceInversion {
    double reducedAlbedo = 0.0;
    double gathered = 0.0;  ///< ReflectanceTable::gathered at that albedo
};

/// The reduced albedo whose reflectance is `reflectance` (clamped to the table's range).
SSS_API ReflectanceInversion invertReflectance(const ReflectanceTable& table, double reflectance);

/// The rule for points of different texels (docs/textured-materials.md): the light leaving x_o
/// follows x_o's profile normalised to what it gathers under even light, times an effective
/// `gathered` for the medium the light crossed: the geometric mean of
///  - the entry points' `gathered`, each weighted by the light it brings to x_o, and
///  - the texture's around x_o (LogGatheredMips at surroundingLevel()),
/// half each (kSurroundingShare), so that light through a part of another colour leaves in the
/// exit point's. Measured against the random walk on two-material slabs. Logarithms are taken of
/// `gathered` floored at kMinGathered.
inline constexpr double kSurroundingShare = 0.5;
inline constexpr double kMinGathered = 1e-6;

/// The linear value of an sRGB-encoded 8-bit value.
SSS_API double srgbToLinear(std::uint8_t value);

/// An 8-bit texture sampled as the GPU samples its mip level 0: bilinear, repeating, texture
/// coordinate (0, 0) at the bottom-left (Mesh::texcoords()).
class TextureSampler {
public:
    /// `srgb`: decode the colour channels from sRGB (a base colour); otherwise value / 255.
    SSS_API TextureSampler(const Image8& image, bool srgb);
    SSS_API glm::dvec3 operator()(glm::dvec2 uv) const;

private:
    int m_width = 0, m_height = 0;
    std::vector<glm::dvec3> m_texels;  // rows bottom to top
};

/// ln gathered of each texel of a base-colour texture (sRGB decoded, floored at kMinGathered), with
/// the mip chain glGenerateTextureMipmap builds from it (2 x 2 means; odd sizes drop their last
/// row or column): level L holds the geometric mean of `gathered` over squares 2^L texels wide.
class LogGatheredMips {
public:
    SSS_API LogGatheredMips(const Image8& reflectance, const ReflectanceTable& table);
    /// Channel `c` sampled as the GPU samples the chain: bilinear and repeating within the two
    /// levels around `level` (clamped to the chain), linear between them.
    SSS_API double operator()(glm::dvec2 uv, double level, int c) const;
    int width() const { return m_levels.front().width; }
    int height() const { return m_levels.front().height; }
    /// Level 0 as RGBA floats, rows bottom to top (for upload).
    SSS_API std::vector<float> baseLevelRgba() const;

private:
    struct Level {
        int width = 0, height = 0;
        std::vector<glm::dvec3> texels;  // rows bottom to top
    };
    double bilinear(const Level& level, glm::dvec2 uv, int c) const;
    std::vector<Level> m_levels;
};

/// The surroundings of x_o in the textured rule: the mean of LogGatheredMips over two squares,
/// kSurroundingWidths[k] / sigma_tr wide (sigma_tr of x_o's own material). Two widths stand for
/// the profile's steep centre and long tail (one square sqrt(12) / sigma_tr wide, matching its
/// second moment, measured 16.5 % on the two-texel slab; these two 6.4 %).
inline constexpr double kSurroundingWidths[2] = {0.25, 2.0};

/// The mip level at which LogGatheredMips averages over a square `width` world units wide at
/// `texelsPerUnit` texels per world unit; 0 at the finest.
SSS_API double surroundingLevel(double width, double texelsPerUnit);

/// Texels of a `width` x `height` texture per world unit of `mesh` placed by `model`: the square
/// root of the texture's area over the surface's, summed over the triangles (a mesh-wide mean).
/// 0 for a mesh without texture coordinates or area.
SSS_API double meanTexelDensity(const Mesh& mesh, const glm::mat4& model, int width, int height);

}  // namespace sss::detail
