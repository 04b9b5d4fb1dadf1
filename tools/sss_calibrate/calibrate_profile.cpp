// sss-calibrate: generates src/mesh/profile_calibration_table.inc, the table behind
// sss::profileCalibrationScale() (the calibrated scattering profile, see sss/bssrdf.h).
//
// For every (eta, reduced albedo, incidence) node it divides the exact multiple-scattering
// diffuse reflectance of an isotropic half-space below a smooth dielectric
// (sss::isotropicHalfSpaceReflectance: Chandrasekhar's H-function and the adding equation, the
// result the random walk sss::simulateSlab is validated against in test_random_walk.cpp) by the
// directional dipole's at the same incidence:
//   T(eta, mu_i) * dipolePlaneIntegral(mu_i) * fresnelHemisphereIntegral(eta).
// Lengths do not matter (both scale with 1 / sigma_t'), so sigma_t' = 1. Exact means no noise:
// the table is as good as its interpolation (checked against fresh walks in test_profile.cpp).
// Usage: sss-calibrate OUT.inc (about two minutes on one core).
//
// sss-calibrate --transmission OUT.inc generates src/mesh/profile_transmission_table.inc, the
// table behind sss::profileTransmissionScale(): for every (eta, s, reduced optical thickness
// tau) node, the diffuse transmittance of a slab by the random walk (sss::simulateSlab with a
// finite thickness; light leaving the far face after scattering; there is no exact solution for
// finite slabs) over the dipole's (sss::profileSlabTransmittance). The walk's relative standard
// error is at most 2 % where the transmittance is above 1e-4 (more paths are run until it is);
// below that the light that gets through is invisible next to the rest and the factor of the
// next thinner node is kept.
#include "sss/bssrdf.h"
#include "sss/random_walk.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

namespace {

// s = sqrt(1 - alpha') spaces the albedos the way the diffusion kernel changes (sigma_tr /
// sigma_t' = sqrt(3) s), dense towards alpha' = 1 where most presets live (cream R: s = 0.005).
const std::vector<double> kS{0,    0.002, 0.005, 0.01, 0.02, 0.03, 0.04, 0.05, 0.065, 0.08, 0.1,  0.12, 0.14,
                             0.16, 0.18,  0.2,   0.23, 0.26, 0.3,  0.34, 0.38, 0.42,  0.46, 0.5,  0.55, 0.6,
                             0.65, 0.7,   0.75,  0.8,  0.85, 0.9,  0.93, 0.96, 0.98,  0.99, 0.995};
// eta covers [1, 2.5]; the entry cosines are the shader's nodes mu = 1 - 0.19 i (dirpole.glsl).
const std::vector<double> kEta{1.0, 1.1, 1.2, 1.3, 1.4, 1.5, 1.6, 1.7, 1.8, 1.9, 2.0, 2.25, 2.5};
constexpr int kMuNodes = sss::kProfileIncidenceNodes;


std::string list(const std::vector<double>& v) {
    std::string line;
    char buf[32];
    for (size_t i = 0; i < v.size(); ++i) {
        std::snprintf(buf, sizeof buf, "%s%.7g", i ? ", " : "", v[i]);
        line += buf;
    }
    return line;
}

// The medium of one table node: reduced albedo 1 - s^2 in every channel, sigma_t' = 1 / mm, g = 0.
sss::ScatteringMaterial calibrationMedium(double s, double eta) {
    const double albedo = 1.0 - s * s;
    sss::ScatteringMaterial m;
    m.sigmaS = glm::dvec3(albedo);
    m.sigmaA = glm::dvec3(1.0 - albedo);
    m.eta = eta;
    m.name = "calibration";
    return m;
}

using Table = std::vector<std::vector<std::vector<double>>>;  // [eta][s][node]

// Writes a generated table file: the comment (each line starting "// "), then namespace `name`
// with kEta, kS and kScale. Returns the exit status.
int writeTable(const std::string& out, const std::string& comment, const std::string& name, const std::vector<double>& s,
               const Table& scale) {
    std::ofstream f(out);
    if (!f) {
        std::cerr << "sss-calibrate: cannot write " << out << "\n";
        return 1;
    }
    f << comment << "namespace " << name << " {\n";
    f << "inline constexpr double kEta[] = {" << list(kEta) << "};\n";
    f << "inline constexpr double kS[] = {" << list(s) << "};\n";
    f << "inline constexpr double kScale[" << scale.size() << "][" << s.size() << "][" << scale[0][0].size() << "] = {\n";
    for (const auto& byS : scale) {
        f << "    {\n";
        for (const auto& byNode : byS) f << "        {" << list(byNode) << "},\n";
        f << "    },\n";
    }
    f << "};\n}  // namespace " << name << "\n";
    std::cerr << "wrote " << out << "\n";
    return 0;
}

// The transmission table's albedo grid: coarser than the reflection's (each node costs walks).
const std::vector<double> kTransmissionS{0, 0.02, 0.05, 0.1, 0.15, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.97};

int calibrateTransmission(const std::string& out) {
    const auto start = std::chrono::steady_clock::now();
    constexpr int kTau = sss::kProfileThicknessNodes;
    Table scale(kEta.size(), std::vector<std::vector<double>>(kTransmissionS.size(), std::vector<double>(kTau, 1.0)));
    for (size_t e = 0; e < kEta.size(); ++e) {
        for (size_t i = 0; i < kTransmissionS.size(); ++i) {
            const sss::ScatteringMaterial m = calibrationMedium(kTransmissionS[i], kEta[e]);
            const sss::DipoleConstants k = sss::deriveDipoleConstants(m, 1.0, sss::ScatteringProfile::Dipole);
            for (int t = 0; t < kTau; ++t) {
                const double tau = sss::profileThicknessNode(t);  // mm, as sigma_t' = 1 / mm
                sss::SlabRandomWalkOptions w;
                w.thickness = tau;
                w.paths = 1 << 14;
                w.seed = 1000003u * e + 1009u * i + t + 1;
                sss::Estimate walk;
                for (;;) {
                    // One channel is enough (all three are the same medium); simulateSlab runs all three,
                    // so pool them: three independent estimates of the same number.
                    const sss::SlabRandomWalkResult r = sss::simulateSlab(m, 0.0, w);
                    double v = 0.0, var = 0.0;
                    for (const auto& c : r.channels) {
                        v += c.transmitted.value / 3.0;
                        var += c.transmitted.standardError * c.transmitted.standardError / 9.0;
                    }
                    walk = {v, std::sqrt(var)};
                    if (walk.value < 1e-4 || walk.standardError <= 0.02 * walk.value || w.paths >= (1 << 20)) break;
                    w.paths *= 4;
                }
                const double dipole = sss::profileSlabTransmittance(k, tau).x;
                if (walk.value >= 1e-4 && walk.standardError <= 0.05 * walk.value && dipole > 0.0)
                    scale[e][i][t] = walk.value / dipole;
                else if (t > 0)
                    scale[e][i][t] = scale[e][i][t - 1];
            }
        }
        std::fprintf(stderr, "eta %.2f done (%.0f s)\n", kEta[e],
                     std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    return writeTable(out,
                      "// Generated by sss-calibrate --transmission (tools/sss_calibrate/calibrate_profile.cpp); do not edit by\n"
                      "// hand. The calibrated profile's transmission factor (sss::profileTransmissionScale): the random\n"
                      "// walk's diffuse transmittance through a slab over the directional dipole's, per relative index\n"
                      "// eta, s = sqrt(1 - alpha') and reduced optical thickness tau = profileThicknessNode(t) = 0.25 * 2^t.\n",
                      "sss::transmission_calibration", kTransmissionS, scale);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc == 3 && std::string(argv[1]) == "--transmission") return calibrateTransmission(argv[2]);
    if (argc != 2) {
        std::cerr << "usage: sss-calibrate OUT.inc | sss-calibrate --transmission OUT.inc\n";
        return 2;
    }
    const std::string out = argv[1];
    const auto start = std::chrono::steady_clock::now();
    // scale[e][s][m]
    Table scale(kEta.size(), std::vector<std::vector<double>>(kS.size(), std::vector<double>(kMuNodes)));
    for (size_t e = 0; e < kEta.size(); ++e) {
        const double hemisphere = sss::fresnelHemisphereIntegral(kEta[e]);
        for (size_t i = 0; i < kS.size(); ++i) {
            const sss::ScatteringMaterial m = calibrationMedium(kS[i], kEta[e]);
            const double albedo = m.sigmaS.x;
            const sss::DipoleConstants k = sss::deriveDipoleConstants(m, 1.0, sss::ScatteringProfile::Dipole);
            for (int j = 0; j < kMuNodes; ++j) {
                const double mu = sss::profileIncidenceNode(j);
                const double theta = std::acos(mu) * 180.0 / std::numbers::pi;
                const double exact = sss::isotropicHalfSpaceReflectance(albedo, kEta[e], theta).multiple;
                const double dipole = sss::fresnelTransmittance(kEta[e], mu) * sss::dipolePlaneIntegral(k, mu).x * hemisphere;
                scale[e][i][j] = dipole > 0.0 ? exact / dipole : 0.0;
            }
        }
        std::fprintf(stderr, "eta %.2f done (%.0f s)\n", kEta[e],
                     std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    return writeTable(out,
                      "// Generated by sss-calibrate (tools/sss_calibrate/calibrate_profile.cpp); do not edit by hand.\n"
                      "// The calibrated profile's factor (sss::profileCalibrationScale): the exact multiple-scattering\n"
                      "// diffuse reflectance of an isotropic half-space (H-function + adding equation) over the\n"
                      "// directional dipole's, per relative index eta, s = sqrt(1 - alpha') and entry cosine\n"
                      "// mu = profileIncidenceNode(m) = 1 - 0.19 m.\n",
                      "sss::calibration", kS, scale);
}
