// Measured material presets. Values are facts from the published tables: Jensen et al. 2001
// (as in pbrt-v3's SubsurfaceParameterTable) and Narasimhan et al. 2006 (pbrt-v3's
// full-concentration extrapolation). Both give reduced scattering sigma_s', so g = 0.
#include "sss/materials.h"

#include "mesh/reflectance_table.h"
#include "util/format.h"

#include "sss/error.h"

#include <array>
#include <cctype>
#include <cmath>

namespace sss {
namespace {

struct Preset {
    const char* name;
    glm::dvec3 sigmaSPrime;  // mm^-1
    glm::dvec3 sigmaA;       // mm^-1
    double eta = 1.3;
};

const std::array kPresets = {
    // Jensen, Marschner, Levoy, Hanrahan, "A Practical Model for Subsurface Light Transport", 2001.
    Preset{"apple", {2.29, 2.39, 1.97}, {0.0030, 0.0034, 0.046}},
    Preset{"chicken1", {0.15, 0.21, 0.38}, {0.015, 0.077, 0.19}},
    Preset{"chicken2", {0.19, 0.25, 0.32}, {0.018, 0.088, 0.20}},
    Preset{"cream", {7.38, 5.47, 3.15}, {0.0002, 0.0028, 0.0163}},
    Preset{"ketchup", {0.18, 0.07, 0.03}, {0.061, 0.97, 1.45}},
    Preset{"marble", {2.19, 2.62, 3.00}, {0.0021, 0.0041, 0.0071}, 1.5},
    Preset{"potato", {0.68, 0.70, 0.55}, {0.0024, 0.0090, 0.12}},
    Preset{"skimmilk", {0.70, 1.22, 1.90}, {0.0014, 0.0025, 0.0142}},
    Preset{"skin1", {0.74, 0.88, 1.01}, {0.032, 0.17, 0.48}},
    Preset{"skin2", {1.09, 1.59, 1.79}, {0.013, 0.070, 0.145}},
    Preset{"spectralon", {11.6, 20.4, 14.9}, {0.0, 0.0, 0.0}},
    Preset{"wholemilk", {2.55, 3.21, 3.77}, {0.0011, 0.0024, 0.014}},
    // Narasimhan, Gupta, Donner, Ramamoorthi, Nayar, Jensen, "Acquiring Scattering Properties of
    // Participating Media by Dilution", 2006.
    Preset{"lowfatmilk", {0.89187, 1.5136, 2.532}, {0.002875, 0.00575, 0.0115}},
    Preset{"reducedmilk", {2.4858, 3.1669, 4.5214}, {0.0025556, 0.0051111, 0.012778}},
    Preset{"regularmilk", {4.5513, 5.8294, 7.136}, {0.0015333, 0.0046, 0.019933}},
    Preset{"espresso", {0.72378, 0.84557, 1.0247}, {4.7984, 6.5751, 8.8493}},
    Preset{"mintmochacoffee", {0.31602, 0.38538, 0.48131}, {3.772, 5.8228, 7.82}},
    Preset{"lowfatsoymilk", {0.30576, 0.34233, 0.61664}, {0.0014375, 0.0071875, 0.035937}},
    Preset{"regularsoymilk", {0.59223, 0.73866, 1.4693}, {0.0019167, 0.0095833, 0.065167}},
    Preset{"lowfatchocolatemilk", {0.64925, 0.83916, 1.1057}, {0.0115, 0.0368, 0.1564}},
    Preset{"regularchocolatemilk", {1.4585, 2.1289, 2.9527}, {0.010063, 0.043125, 0.14375}},
    Preset{"coke", {8.9053e-05, 8.372e-05, 0.0}, {0.10014, 0.16503, 0.2468}},
    Preset{"pepsi", {6.1697e-05, 4.2564e-05, 0.0}, {0.091641, 0.14158, 0.20729}},
    Preset{"sprite", {6.0306e-06, 6.4139e-06, 6.5504e-06}, {0.001886, 0.0018308, 0.0020025}},
    Preset{"gatorade", {0.0024574, 0.003007, 0.0037325}, {0.024794, 0.019289, 0.008878}},
    Preset{"chardonnay", {1.7982e-05, 1.3758e-05, 1.2023e-05}, {0.010782, 0.011855, 0.023997}},
    Preset{"whitezinfandel", {1.7501e-05, 1.9069e-05, 1.288e-05}, {0.012072, 0.016184, 0.019843}},
    Preset{"merlot", {2.1129e-05, 0.0, 0.0}, {0.11632, 0.25191, 0.29434}},
    Preset{"budweiserbeer", {2.4356e-05, 2.4079e-05, 1.0564e-05}, {0.011492, 0.024911, 0.057786}},
    Preset{"coorslightbeer", {5.0922e-05, 4.301e-05, 0.0}, {0.006164, 0.013984, 0.034983}},
    Preset{"clorox", {0.0024035, 0.0031373, 0.003991}, {0.0033542, 0.014892, 0.026297}},
    Preset{"applejuice", {0.00013612, 0.00015836, 0.000227}, {0.012957, 0.023741, 0.052184}},
    Preset{"cranberryjuice", {0.00010402, 0.00011646, 7.8139e-05}, {0.039437, 0.094223, 0.12426}},
    Preset{"grapejuice", {5.382e-05, 0.0, 0.0}, {0.10404, 0.23958, 0.29325}},
    Preset{"rubygrapefruitjuice", {0.011002, 0.010927, 0.011036}, {0.085867, 0.18314, 0.25262}},
    Preset{"whitegrapefruitjuice", {0.22826, 0.23998, 0.32748}, {0.0138, 0.018831, 0.056781}},
    Preset{"shampoo", {0.0007176, 0.0008303, 0.0009016}, {0.014107, 0.045693, 0.061717}},
    Preset{"strawberryshampoo", {0.00015671, 0.00015947, 1.518e-05}, {0.01449, 0.05796, 0.075823}},
    Preset{"headshouldersshampoo", {0.023805, 0.028804, 0.034306}, {0.084621, 0.15688, 0.20365}},
    Preset{"lemonteapowder", {0.040224, 0.045264, 0.051081}, {2.4288, 4.5757, 7.2127}},
    Preset{"orangepowder", {0.00015617, 0.00017482, 0.0001762}, {0.001449, 0.003441, 0.007863}},
    Preset{"pinklemonadepowder", {0.00012103, 0.00013073, 0.00012528}, {0.001165, 0.002366, 0.003195}},
    Preset{"cappuccinopowder", {1.8436, 2.5851, 2.1662}, {35.844, 49.547, 61.084}},
    Preset{"saltpowder", {0.027333, 0.032451, 0.031979}, {0.28415, 0.3257, 0.34148}},
    Preset{"sugarpowder", {0.00022272, 0.00025513, 0.000271}, {0.012638, 0.031051, 0.050124}},
    Preset{"suissemochapowder", {2.7979, 3.5452, 4.3365}, {17.502, 27.004, 35.433}},
    Preset{"pacificoceansurfacewater", {0.0001764, 0.00032095, 0.00019617}, {0.031845, 0.031324, 0.030147}},
};

// Lower case, letters and digits only.
std::string canonical(std::string_view name) {
    std::string out;
    for (const char ch : name) {
        const auto c = static_cast<unsigned char>(ch);
        if (std::isalnum(c)) out += static_cast<char>(std::tolower(c));
    }
    return out;
}

}  // namespace

ScatteringMaterial materialPreset(std::string_view name) {
    const std::string key = canonical(name);
    for (const Preset& p : kPresets) {
        if (key != p.name) continue;
        ScatteringMaterial m;
        m.sigmaA = p.sigmaA;
        m.sigmaS = p.sigmaSPrime;
        m.g = 0.0;
        m.eta = p.eta;
        m.name = p.name;
        return m;
    }
    std::string known;
    for (const Preset& p : kPresets) known += (known.empty() ? "" : ", ") + std::string(p.name);
    throw Error(ErrorKind::InvalidArgument,
                "materialPreset: unknown material \"" + std::string(name) + "\"; known: " + known);
}

std::vector<std::string> materialPresetNames() {
    std::vector<std::string> names;
    for (const Preset& p : kPresets) names.emplace_back(p.name);
    return names;
}

namespace {

bool positiveFinite(const glm::dvec3& v) {
    return std::isfinite(v.x + v.y + v.z) && v.x > 0.0 && v.y > 0.0 && v.z > 0.0;
}

void checkEta(const char* where, double eta) {
    if (!(eta >= 0.4 && eta <= 2.5))
        throw Error(ErrorKind::InvalidArgument, where, "eta", "must be in [0.4, 2.5], got " + detail::formatNumber(eta));
}

}  // namespace

void TexturedScattering::validate() const {
    if (!positiveFinite(meanFreePath))
        throw Error(ErrorKind::InvalidArgument, "TexturedScattering", "meanFreePath",
                    "must be finite and > 0 in every channel, got " + detail::formatVec(glm::vec3(meanFreePath)));
    checkEta("TexturedScattering", eta);
}

TexturedScattering texturedScattering(const ScatteringMaterial& material) {
    material.validate();
    TexturedScattering t;
    t.meanFreePath = 1.0 / (material.sigmaS * (1.0 - material.g) + material.sigmaA);
    t.eta = material.eta;
    t.name = material.name;
    return t;
}

ScatteringMaterial materialFromReflectance(const glm::dvec3& reflectance, const glm::dvec3& meanFreePath, double eta,
                                           ScatteringProfile profile) {
    if (!std::isfinite(reflectance.x + reflectance.y + reflectance.z))
        throw Error(ErrorKind::InvalidArgument, "materialFromReflectance", "reflectance",
                    "must be finite, got " + detail::formatVec(glm::vec3(reflectance)));
    if (!positiveFinite(meanFreePath))
        throw Error(ErrorKind::InvalidArgument, "materialFromReflectance", "meanFreePath",
                    "must be finite and > 0 in every channel, got " + detail::formatVec(glm::vec3(meanFreePath)));
    checkEta("materialFromReflectance", eta);
    const detail::ReflectanceTable& table = detail::reflectanceTable(eta, profile);
    ScatteringMaterial m;
    for (int c = 0; c < 3; ++c) {
        const double albedo = detail::invertReflectance(table, reflectance[c]).reducedAlbedo;
        m.sigmaS[c] = albedo / meanFreePath[c];
        m.sigmaA[c] = (1.0 - albedo) / meanFreePath[c];
    }
    m.g = 0.0;
    m.eta = eta;
    m.name = "reflectance";
    return m;
}

}  // namespace sss
