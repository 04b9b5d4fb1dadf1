#pragma once
// How a textured material's reflectance becomes coefficients (sss::materialFromReflectance): the
// profile's total diffuse reflectance at normal incidence against the reduced albedo, for one eta,
// tabulated once and inverted by interpolation. The same rows give what the radiosity estimate
// gathers per unit irradiance, by which the textured passes normalise (docs/textured-materials.md).
#include "sss/api.h"
#include "sss/bssrdf.h"

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

}  // namespace sss::detail
