#pragma once
/// @file
/// Measured scattering materials and the scale that relates them to scene units.

#include "sss/api.h"
#include "sss/bssrdf.h"

#include <glm/vec3.hpp>

#include <memory>
#include <string>
#include <string_view>
#include <vector>

SSS_BEGIN_API

namespace sss {

/// How long one scene unit is, for converting the mm^-1 coefficients of ScatteringMaterial
/// (sigma_scene = sigma_mm * millimetresPerUnit; pass it to deriveDipoleConstants()).
/// The scale changes the look enormously: it decides how many transport lengths fit into the
/// object. Potato's red 1/sigma_tr is 14 mm, little on a 15 cm object and a lot on a 1.5 cm one.
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

class Image8;

/// A translucent material whose colour varies over a mesh's surface, in the parametrisation of
/// production renderers (Christensen and Burley 2015): the reflectance per texel, i.e. the colour
/// the surface shows under even light, and a mean free path per channel. Each texel's
/// coefficients are those of materialFromReflectance() for its reflectance, so a flat, evenly lit
/// textured slab shows the texture's colour. The mesh needs texture coordinates.
/// How points with different coefficients combine (docs/textured-materials.md): the light leaving
/// x_o follows x_o's profile, scaled to an effective medium, the geometric mean of the light's
/// entry points' materials and of the texture around x_o. The renderers cache the entries' part
/// (maps or vertices) and take the surroundings' part per pixel, so the texture keeps its detail
/// down to a quarter of a diffusion length wherever the radiosity is cached.
struct TexturedScattering {
    /// Reduced mean free path 1 / sigma_t' per channel, in mm, each finite and > 0 (default:
    /// potato's, as ScatteringMaterial's default).
    glm::dvec3 meanFreePath{1.0 / 0.6824, 1.0 / 0.709, 1.0 / 0.67};
    /// Relative index of refraction, in [0.4, 2.5] (default: 1.3).
    double eta = 1.3;
    /// Reflectance per texel: an sRGB-encoded base colour (decoded to linear before use; alpha is
    /// ignored). Null: the mesh's Mesh::baseColour().
    std::shared_ptr<const Image8> reflectance;
    /// Optional factor on the mean free path per texel: the red channel, linear, value / 255,
    /// floored at 1 / 255 (so meanFreePath is the longest path and the texture thins it). Null: 1.
    /// Its texture coordinates are the reflectance's.
    std::shared_ptr<const Image8> meanFreePathScale;
    std::string name = "textured";  ///< label for messages and UIs

    /// Checks meanFreePath and eta. @throws Error InvalidArgument naming the field.
    void validate() const;
};

/// A preset's look with its colour left to a texture: its reduced mean free path
/// 1 / (sigma_s' + sigma_a) per channel, its eta and its name.
TexturedScattering texturedScattering(const ScatteringMaterial& material);

/// The homogeneous material (g = 0, reduced coefficients) whose profile reflects `reflectance`
/// per channel (the total diffuse reflectance under a collimated beam at normal incidence,
/// profileDiffuseReflectance(), which for the calibrated profile is the random walk's) with the
/// reduced mean free path `meanFreePath` (mm). Reflectances beyond what the profile reaches
/// (reduced albedo 0.99995) or below its floor (reduced albedo 1e-4) are clamped there.
/// @throws Error InvalidArgument for a reflectance that is not finite, a mean free path that is
///         not finite and > 0, or an eta outside [0.4, 2.5].
ScatteringMaterial materialFromReflectance(const glm::dvec3& reflectance, const glm::dvec3& meanFreePath, double eta,
                                           ScatteringProfile profile = ScatteringProfile::Calibrated);

}  // namespace sss

SSS_END_API
