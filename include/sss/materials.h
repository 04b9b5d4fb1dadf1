#pragma once
/// @file
/// Measured scattering materials and the scale that relates them to scene units.

#include "sss/api.h"
#include "sss/bssrdf.h"

#include <string>
#include <string_view>
#include <vector>

SSS_BEGIN_API

namespace sss {

/// How long one scene unit is, for converting the mm^-1 coefficients of ScatteringMaterial
/// (sigma_scene = sigma_mm * millimetresPerUnit; pass it to deriveDipoleConstants()).
/// The scale changes the look enormously: it decides how many transport lengths fit into the
/// object. Potato's red 1/sigma_tr is 7.6 mm, nothing on a 15 cm object and a lot on a 1.5 cm one.
struct ScatteringScale {
    /// Millimetres per scene unit, finite and > 0 (default: 1000, i.e. scene units are metres).
    /// Why 1000: the Stanford scans are in metres (the bunny in data/meshes is 0.155 units tall,
    /// a real 15.5 cm bunny), and the thesis renders it in cream with a sampling ("scattering")
    /// radius of 0.025 units. At 1 unit = 1 m that radius is 25 mm, about 1.7 transport lengths of
    /// cream's widest channel (1/sigma_tr,R = 15 mm, exp(-1.66) = 0.19 at the rim): the kernel
    /// the thesis sampled. (Dal Corso's ray_engine default of 100 would make it a 1.5 cm bunny.)
    double millimetresPerUnit = 1000.0;
};

/// A named measured material. Names are matched ignoring case and any character that is not a
/// letter or digit ("Regular Milk", "regular_milk" and "regularmilk" are the same preset).
///  - Jensen, Marschner, Levoy, Hanrahan 2001 (sigma_s', sigma_a in mm^-1, g = 0): apple,
///    chicken1, chicken2, cream, ketchup, marble, potato, skimmilk, skin1, skin2, spectralon,
///    wholemilk.
///  - Narasimhan, Gupta, Donner, Ramamoorthi, Nayar, Jensen 2006, as extrapolated to full
///    concentration by pbrt-v3 (sigma_s', sigma_a in mm^-1, g = 0): the milks, coffees, soy and
///    chocolate milks, sodas, wines, beers, juices, shampoos, powders and ocean water of
///    materialPresetNames(). Several barely scatter (merlot has sigma_s' = 0 in G and B), where a
///    diffusion model is a poor fit but still finite.
/// eta is 1.3 for all (the conventional value; the Dal Corso thesis table) except marble, 1.5.
/// @throws Error InvalidArgument for an unknown name; the message lists the known names.
ScatteringMaterial materialPreset(std::string_view name);

/// The canonical names of all presets (lower case, letters and digits only), in table order.
std::vector<std::string> materialPresetNames();

}  // namespace sss

SSS_END_API
