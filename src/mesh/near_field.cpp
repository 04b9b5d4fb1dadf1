#include "mesh/near_field.h"

#include "sss/materials.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

namespace sss::detail {

namespace {

// The disk integral out to each of `radial` log-spaced radii ending at `radius`: (outer edge of
// bin i, integral up to it). The quadrature of dipoleDiskIntegral().
std::vector<std::pair<double, glm::dvec3>> cumulativeDiskIntegral(const DipoleConstants& c, double cosIncidence,
                                                                  double radius, int radial) {
    std::vector<std::pair<double, glm::dvec3>> cumulative;
    // Log-spaced midpoints in r from far below the shortest mean free path (the profile's peak
    // is about a mean free path wide) to the radius; the azimuth over [0, pi], twice (the kernel
    // is mirror-symmetric about the plane of incidence).
    double shortest = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 3; ++i) shortest = std::min(shortest, 1.0 / c.sigmaTPrime[i]);
    const double r0 = 1e-6 * shortest;
    if (!(radius > r0)) return cumulative;
    const double sinI = std::sqrt(std::max(0.0, 1.0 - cosIncidence * cosIncidence));
    const glm::dvec3 wi{sinI, 0.0, cosIncidence}, n{0.0, 0.0, 1.0};
    const bool symmetric = sinI < 1e-12;
    const int azimuthal = symmetric ? 1 : 32;
    const double l0 = std::log(r0), dl = (std::log(radius) - l0) / radial;
    glm::dvec3 sum(0.0);
    for (int i = 0; i < radial; ++i) {
        const double r = std::exp(l0 + (i + 0.5) * dl);
        for (int j = 0; j < azimuthal; ++j) {
            const double phi = std::numbers::pi * (j + 0.5) / azimuthal;
            // Entry at the origin, exit at the disk point's surface point: S_d depends on their
            // offset only, so this is the integral over entry points around a fixed exit.
            const glm::dvec3 xo{r * std::cos(phi) / cosIncidence, r * std::sin(phi), 0.0};
            sum += evaluateSd(c, glm::dvec3(0.0), n, wi, xo, n) * (r * r * dl * 2.0 * std::numbers::pi / azimuthal);
        }
        cumulative.emplace_back(std::exp(l0 + (i + 1) * dl), sum);
    }
    return cumulative;
}

constexpr int kRadialBins = 320;

// Tap k's ring table (NearFieldRingTable) from the disk integral's bins [first, end): each bin a
// ring at its mid radius weighted by its integral, per channel.
void tabulateRing(const std::vector<std::pair<double, glm::dvec3>>& cumulative, std::size_t first, std::size_t end,
                  NearFieldRingTable& ring) {
    if (first >= end) return;
    ring.outer = static_cast<float>(cumulative[end - 1].first);
    glm::dvec3 weight(0.0), meanSquare(0.0);
    std::array<glm::dvec3, kNearFieldRingNodes> h{}, q{};
    for (std::size_t b = first; b < end; ++b) {
        const double inner = b == 0 ? 0.0 : cumulative[b - 1].first, outer = cumulative[b].first;
        const double r = b == 0 ? outer : std::sqrt(inner * outer);
        const glm::dvec3 w = cumulative[b].second - (b == 0 ? glm::dvec3(0.0) : cumulative[b - 1].second);
        weight += w;
        meanSquare += w * r * r;
        for (int i = 0; i < kNearFieldRingNodes; ++i) {
            const double t = ring.outer * (2.0 * i / (kNearFieldRingNodes - 1) - 1.0);
            const glm::dvec2 m = nearFieldRingMoments(r, t);
            h[i] += w * m.x;
            q[i] += w * m.y;
        }
    }
    for (int ch = 0; ch < 3; ++ch) {
        if (!(weight[ch] > 0.0)) continue;
        ring.meanSquareRadius[ch] = static_cast<float>(meanSquare[ch] / weight[ch]);
        for (int i = 0; i < kNearFieldRingNodes; ++i) {
            ring.h[i][ch] = static_cast<float>(h[i][ch] / weight[ch]);
            ring.q[i][ch] = static_cast<float>(q[i][ch] / weight[ch]);
        }
    }
}

// The share of the disk integral within tap k's ring's outer radius: eighths up to 7/8, then
// halving what is left (15/16, 31/32, ...), the last ring out to the disk's edge. The tail's rings
// find a cast shadow's edge or a terminator several diffusion lengths away, whose light is a
// small share of the profile's but all a point in the dark gets.
static_assert(kNearFieldTaps >= 8);
double tapUpperQuantile(int k) {
    if (k + 1 >= kNearFieldTaps) return 1.0;
    if (k < 7) return (k + 1) / 8.0;
    return 1.0 - std::ldexp(1.0, -(k - 3));
}

// Visibility taps for the near field lit head-on: tap k stands for the ring between the
// quantiles tapUpperQuantile(k - 1) and tapUpperQuantile(k) of the channels' mean share of the
// disk integral, at the ring's median radius; each channel weighs it by its own share of the
// disk integral in that ring.
void placeVisibilityTaps(const DipoleConstants& c, double radius, NearFieldTable& table) {
    const auto cumulative = cumulativeDiskIntegral(c, 1.0, radius, kRadialBins);
    if (cumulative.empty()) return;
    const glm::dvec3 total = cumulative.back().second;
    auto share = [&](const glm::dvec3& v) {
        glm::dvec3 s(0.0);
        for (int ch = 0; ch < 3; ++ch) s[ch] = total[ch] > 0.0 ? v[ch] / total[ch] : 0.0;
        return s;
    };
    auto meanShare = [&](const glm::dvec3& v) { const glm::dvec3 s = share(v); return (s.x + s.y + s.z) / 3.0; };
    // The first radius at which the mean share reaches q, and the integral there.
    auto at = [&](double q) {
        for (const auto& [r, integral] : cumulative)
            if (meanShare(integral) >= q) return std::pair{r, integral};
        return cumulative.back();
    };
    glm::dvec3 previous(0.0);
    std::size_t bin = 0;  // the first bin of tap k's annulus
    double lower = 0.0;
    for (int k = 0; k < kNearFieldTaps; ++k) {
        const double upper = tapUpperQuantile(k);
        std::size_t end = bin;  // one past the annulus's last bin: the first to reach `upper`
        while (end < cumulative.size() && (end == bin || meanShare(cumulative[end - 1].second) < upper)) ++end;
        if (k + 1 == kNearFieldTaps) end = cumulative.size();
        const glm::dvec3 ringEnd = cumulative[end - 1].second;
        table.tapRadius[k] = static_cast<float>(at(0.5 * (lower + upper)).first);
        table.tapWeight[k] = glm::vec3(share(ringEnd - previous));
        tabulateRing(cumulative, bin, end, table.rings[k]);
        lower = upper;
        bin = end;
        previous = ringEnd;
    }
}

}  // namespace

glm::dvec2 nearFieldRingMoments(double r, double t) {
    if (t >= r) return glm::dvec2(0.0);
    if (t <= -r) return {-t, t * t + 0.5 * r * r};
    const double a = std::acos(t / r), sinA = std::sin(a);  // the lit arc is |phi| < a
    const double h = r * sinA - t * a;
    const double q = r * r * (0.5 * a + 0.5 * sinA * std::cos(a)) - 2.0 * r * t * sinA + t * t * a;
    return glm::dvec2(h, q) / std::numbers::pi;
}

glm::dvec3 dipoleDiskIntegral(const DipoleConstants& c, double cosIncidence, double radius) {
    if (!(radius > 0.0) || !(cosIncidence > 0.0)) return glm::dvec3(0.0);
    const auto cumulative = cumulativeDiskIntegral(c, std::min(cosIncidence, 1.0), radius, kRadialBins);
    return cumulative.empty() ? glm::dvec3(0.0) : cumulative.back().second;
}

glm::dvec3 dipoleDiskIntegralBehind(const DipoleConstants& c, double depth, double radius) {
    double shortest = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 3; ++i) shortest = std::min(shortest, 1.0 / c.sigmaTPrime[i]);
    const double r0 = 1e-6 * shortest;
    if (!(radius > r0)) return glm::dvec3(0.0);
    // Head-on light makes the integrand symmetric about the axis: log-spaced rings in r.
    const glm::dvec3 up{0.0, 0.0, 1.0}, xo{0.0, 0.0, -std::max(depth, 0.0)};
    const double l0 = std::log(r0), dl = (std::log(radius) - l0) / kRadialBins;
    glm::dvec3 sum(0.0);
    for (int i = 0; i < kRadialBins; ++i) {
        const double r = std::exp(l0 + (i + 0.5) * dl);
        sum += evaluateSd(c, glm::dvec3(r, 0.0, 0.0), up, up, xo, -up) * (r * r * dl * 2.0 * std::numbers::pi);
    }
    return sum;
}

float nearFieldRadius(float nearFieldEdges, double edgeLength, double edgeRatio, float diskRadius) {
    if (edgeRatio < kNearFieldMinEdgeRatio) return 0.0f;
    return std::min(diskRadius, static_cast<float>(nearFieldEdges * edgeLength));
}

float nearFieldCorrection(double edgeFreePaths) {
    const double k = kNearFieldCorrectionFreePaths;
    return edgeFreePaths > k ? static_cast<float>((k / edgeFreePaths) * (k / edgeFreePaths)) : 1.0f;
}

NearFieldTable tabulateNearField(const DipoleConstants& c, double radius, double edgeLength) {
    NearFieldTable table;
    table.radius = static_cast<float>(std::max(radius, 0.0));
    table.texturedShare.fill(glm::vec3(1.0f));
    for (int ch = 0; ch < 3; ++ch) table.correction[ch] = nearFieldCorrection(edgeLength * c.sigmaTPrime[ch]);
    if (!(radius > 0.0)) return table;
    placeVisibilityTaps(c, radius, table);
    for (int i = 0; i < kNearFieldNodes; ++i) {
        // Grazing light (node 0) enters nothing: T(eta, 0) = 0.
        const double mu = std::max(static_cast<double>(i) / (kNearFieldNodes - 1), 1e-3);
        const glm::dvec3 perIrradiance = fresnelTransmittance(c.eta, mu) * dipoleDiskIntegral(c, mu, radius) / mu;
        table.reflectance[i] = glm::vec3(perIrradiance);
    }
    // Six diffusion lengths of the farthest-reaching channel: e^-6 of the light is left there.
    double longest = 0.0;
    for (int ch = 0; ch < 3; ++ch) longest = std::max(longest, 1.0 / std::max(c.sigmaTr[ch], 1e-12));
    table.behindDepth = static_cast<float>(std::min(6.0 * longest, 16.0 * radius));
    for (int i = 0; i < kNearFieldNodes; ++i) {
        const double t = static_cast<double>(i) / (kNearFieldNodes - 1);
        table.behind[i] = glm::vec3(dipoleDiskIntegralBehind(c, table.behindDepth * t * t, radius));
    }
    return table;
}

void tabulateTexturedNearFieldShare(NearFieldTable& table, const ScatteringMaterial& widest, double millimetresPerUnit,
                                    ScatteringProfile profile) {
    table.texturedShare.fill(glm::vec3(1.0f));
    if (!(table.radius > 0.0f)) return;
    const glm::dvec3 sigmaT = widest.sigmaS + widest.sigmaA;  // 1 / the texture's mean free path
    // The share of a flat surface's light (head-on) entering within rho, per channel, for the
    // material of reduced albedo `albedo` (per channel, in (0, 1)).
    auto nearShare = [&](const glm::dvec3& albedo) {
        ScatteringMaterial m = widest;
        m.sigmaS = albedo * sigmaT;
        m.sigmaA = (1.0 - albedo) * sigmaT;
        const DipoleConstants c = deriveDipoleConstants(m, millimetresPerUnit, profile);
        const glm::dvec3 near = dipoleDiskIntegral(c, 1.0, table.radius), whole = dipolePlaneIntegral(c, 1.0);
        glm::dvec3 share(1.0);
        for (int ch = 0; ch < 3; ++ch)
            if (whole[ch] > 0.0) share[ch] = near[ch] / whole[ch];
        return share;
    };
    const glm::dvec3 reference = nearShare(widest.sigmaS / sigmaT);
    for (int i = 0; i < kNearFieldNodes; ++i) {
        const double t = 1.0 - static_cast<double>(i) / (kNearFieldNodes - 1);
        const glm::dvec3 share = nearShare(glm::dvec3(std::clamp(1.0 - t * t, 1e-4, 1.0 - 1e-6)));
        for (int ch = 0; ch < 3; ++ch)
            table.texturedShare[i][ch] = reference[ch] > 0.0 ? static_cast<float>(share[ch] / reference[ch]) : 1.0f;
    }
}

std::vector<glm::vec4> packNearFieldRings(const NearFieldTable& table) {
    std::vector<glm::vec4> packed;
    packed.reserve(kNearFieldTaps * (2 + 2 * kNearFieldRingNodes));
    for (const NearFieldRingTable& ring : table.rings) {
        packed.emplace_back(ring.outer, 0.0f, 0.0f, 0.0f);
        packed.emplace_back(ring.meanSquareRadius, 0.0f);
        for (int i = 0; i < kNearFieldRingNodes; ++i) {
            packed.emplace_back(ring.h[i], 0.0f);
            packed.emplace_back(ring.q[i], 0.0f);
        }
    }
    return packed;
}

void setNearFieldUniforms(const gl::Program& p, const NearFieldTable& table) {
    p.set("nearFieldOn", table.radius > 0.0f ? 1 : 0);
    glProgramUniform3fv(p.id(), p.uniformLocation("nearField[0]"), kNearFieldNodes, &table.reflectance[0].x);
    glProgramUniform1fv(p.id(), p.uniformLocation("nearFieldTapRadius[0]"), kNearFieldTaps, table.tapRadius.data());
    glProgramUniform3fv(p.id(), p.uniformLocation("nearFieldTapWeight[0]"), kNearFieldTaps, &table.tapWeight[0].x);
    glProgramUniform3fv(p.id(), p.uniformLocation("nearFieldBehind[0]"), kNearFieldNodes, &table.behind[0].x);
    p.set("nearFieldBehindDepth", table.behindDepth);
    if (const GLint at = p.uniformLocation("nearFieldTexturedShare[0]"); at >= 0)
        glProgramUniform3fv(p.id(), at, kNearFieldNodes, &table.texturedShare[0].x);
}

}  // namespace sss::detail
