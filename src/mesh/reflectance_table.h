#pragma once
// How a textured material's reflectance becomes coefficients (sss::materialFromReflectance): the
// profile's total diffuse reflectance at normal incidence against the reduced albedo, for one eta,
// tabulated once and inverted by interpolation. The same rows give what the radiosity estimate
// gathers per unit irradiance, by which the textured passes normalise (docs/textured-materials.md).
#include "sss/api.h"
#include "sss/bssrdf.h"
#include "sss/image.h"

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

/// The rule for a pair of points of different texels: the light entering at x_i and leaving at
/// x_o follows x_o's profile, times (R(x_i) / R(x_o))^kEntryReflectanceExponent per channel
/// (R floored at kMinEntryReflectance). Measured against the random walk on a two-material slab
/// (docs/textured-materials.md). ENTRY_REFLECTANCE_EXPONENT in the shaders.
inline constexpr double kEntryReflectanceExponent = 0.5;
inline constexpr double kMinEntryReflectance = 1e-3;

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

}  // namespace sss::detail
