// Physical ground truth: the analog random walk in a half-space below a smooth dielectric, and
// the exact H-function references it is validated against (see sss/random_walk.h).
#include "sss/random_walk.h"

#include "util/parallel.h"
#include "reference/walk_sampling.h"

#include "sss/error.h"
#include "util/format.h"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <numbers>
#include <string>
#include <thread>
#include <vector>

namespace sss {
namespace {

using detail::formatNumber;

constexpr std::int64_t kChunkPaths = 16384;  // paths per random stream (fixed: determinism)

[[noreturn]] void invalid(const std::string& where, const std::string& message) {
    throw Error(ErrorKind::InvalidArgument, where + ": " + message);
}

void validateOptions(const SlabRandomWalkOptions& o) {
    const std::string w = "simulateSlab";
    if (o.paths < 1) invalid(w, "SlabRandomWalkOptions::paths must be >= 1, got " + formatNumber(o.paths));
    if (o.threads < 0) invalid(w, "SlabRandomWalkOptions::threads must be >= 0, got " + formatNumber(o.threads));
    if (o.maxEvents < 1) invalid(w, "SlabRandomWalkOptions::maxEvents must be >= 1, got " + formatNumber(o.maxEvents));
    if (!std::isfinite(o.coneHalfAngleDeg) || o.coneHalfAngleDeg <= 0.0 || o.coneHalfAngleDeg > 90.0)
        invalid(w, "SlabRandomWalkOptions::coneHalfAngleDeg must be in (0, 90], got " +
                   formatNumber(o.coneHalfAngleDeg));
    if (o.angleBins < 1 || o.angleBins > 100000)
        invalid(w, "SlabRandomWalkOptions::angleBins must be in [1, 100000], got " + formatNumber(o.angleBins));
    if (!std::isfinite(o.profileMaxRadius) || o.profileMaxRadius <= 0.0)
        invalid(w, "SlabRandomWalkOptions::profileMaxRadius must be finite and > 0, got " +
                   formatNumber(o.profileMaxRadius));
    if (o.profileBins < 1 || o.profileBins > 1000000)
        invalid(w, "SlabRandomWalkOptions::profileBins must be in [1, 1000000], got " + formatNumber(o.profileBins));
    if (std::isnan(o.thickness) || o.thickness <= 0.0)
        invalid(w, "SlabRandomWalkOptions::thickness must be > 0 (infinity: a half-space), got " +
                   formatNumber(o.thickness));
}

void validateIncidence(const std::string& where, double incidenceDeg) {
    if (!std::isfinite(incidenceDeg) || incidenceDeg < 0.0 || incidenceDeg >= 90.0)
        invalid(where, "incidenceDeg must be in [0, 90), got " + formatNumber(incidenceDeg));
}

double radians(double degrees) { return degrees * (std::numbers::pi / 180.0); }

double fresnel(double ratio, double cosI, double& cosT) { return detail::fresnelReflectance(ratio, cosI, cosT); }

// ---- random numbers ---------------------------------------------------------------------------

// One stream per (seed, channel, chunk).
class Rng : public detail::Xoshiro256 {
public:
    Rng(std::uint64_t seed, std::uint64_t channel, std::uint64_t chunk) : Xoshiro256(key(seed, channel, chunk)) {}

private:
    static std::uint64_t key(std::uint64_t seed, std::uint64_t channel, std::uint64_t chunk) {
        std::uint64_t h = detail::mix64(seed + 0x9e3779b97f4a7c15ull);
        h = detail::mix64(h ^ (channel + 0x632be59bd9b4e019ull));
        return detail::mix64(h ^ (chunk + 0x85157af5ull));
    }
};

// ---- the walk ---------------------------------------------------------------------------------

struct Dir {
    double x, y, z;
};

Dir scatter(const Dir& d, double g, Rng& rng) { return detail::scatterHenyeyGreenstein(d, g, rng); }

// A path meets a smooth boundary from inside at cosine cosI to its normal: true if it leaves
// (refracted, at cosOut to the normal outside), false if it is reflected, with the exact
// unpolarised Fresnel probability (always under total internal reflection). One draw.
bool leavesThroughBoundary(double eta, double cosI, Rng& rng, double& cosOut) {
    const double f = fresnel(eta, cosI, cosOut);
    return !(f >= 1.0 || rng.uniform() < f);
}

enum class Collision { Absorbed, Truncated, Scattered };

// A real collision in a medium of single-scattering albedo `albedo` and HG parameter g: absorbed
// with probability 1 - albedo; else truncated if the path has already scattered maxEvents times;
// else it scatters (++events, a new direction d).
Collision collide(double albedo, double g, std::int64_t maxEvents, std::int64_t& events, Dir& d, Rng& rng) {
    if (rng.uniform() >= albedo) return Collision::Absorbed;
    if (events == maxEvents) return Collision::Truncated;
    ++events;
    d = scatter(d, g, rng);
    return Collision::Scattered;
}

// Runs `paths` paths per channel: chunks of kChunkPaths paths in a fixed order, the chunk's own
// stream Rng(seed, channel, chunk), spread over `threads`; path(channel, rng, tally) runs one path
// into tally[channel] of a per-thread copy of the (zero) `counts`, added into `counts` at the end
// (Counts::add, integer sums: the result does not depend on the thread count).
template <typename Counts, typename PathFn>
void runChannelChunks(std::int64_t paths, int threads, std::uint64_t seed, std::vector<Counts>& counts, PathFn path) {
    const std::vector<Counts> zero = counts;
    const std::int64_t chunks = (paths + kChunkPaths - 1) / kChunkPaths;
    const int channels = static_cast<int>(counts.size());
    detail::parallelFor(
        threads, channels * chunks, [&] { return zero; },
        [&](std::vector<Counts>& local, std::int64_t u) {
            const int channel = static_cast<int>(u % channels);
            const std::int64_t chunk = u / channels;
            Rng rng(seed, static_cast<std::uint64_t>(channel), static_cast<std::uint64_t>(chunk));
            const std::int64_t n = std::min(kChunkPaths, paths - chunk * kChunkPaths);
            for (std::int64_t p = 0; p < n; ++p) path(channel, rng, local[channel]);
        },
        [&](const std::vector<Counts>& local) {
            for (size_t c = 0; c < counts.size(); ++c) counts[c].add(local[c]);
        });
}

// weight * (count / paths) / normalisation and its binomial standard error.
Estimate binomialEstimate(std::int64_t count, std::int64_t paths, double weight, double normalisation) {
    const double n = static_cast<double>(paths);
    const double p = static_cast<double>(count) / n;
    return Estimate{weight * p / normalisation, weight * std::sqrt(p * (1.0 - p) / n) / normalisation};
}

// Integer tallies of one channel (order-independent sums: thread-count independent results).
struct Counts {
    std::int64_t single = 0, multiple = 0, absorbed = 0, truncated = 0, events = 0;
    std::int64_t cone = 0, coneSingle = 0;
    std::int64_t transmitted = 0, transmittedSingle = 0, ballistic = 0, transmittedCone = 0;
    std::vector<std::int64_t> angle, angleSingle, profile, profileSingle;

    Counts(int angleBins, int profileBins)
        : angle(angleBins, 0), angleSingle(angleBins, 0), profile(profileBins, 0), profileSingle(profileBins, 0) {}
    void add(const Counts& o) {
        single += o.single;
        multiple += o.multiple;
        absorbed += o.absorbed;
        truncated += o.truncated;
        events += o.events;
        cone += o.cone;
        coneSingle += o.coneSingle;
        transmitted += o.transmitted;
        transmittedSingle += o.transmittedSingle;
        ballistic += o.ballistic;
        transmittedCone += o.transmittedCone;
        for (size_t i = 0; i < angle.size(); ++i) angle[i] += o.angle[i], angleSingle[i] += o.angleSingle[i];
        for (size_t i = 0; i < profile.size(); ++i) profile[i] += o.profile[i], profileSingle[i] += o.profileSingle[i];
    }
};

struct ChannelMedium {
    double sigmaT = 0.0;
    double albedo = 0.0;
};

struct Walk {
    double g = 0.0;
    double eta = 1.0;
    Dir entry{0.0, 0.0, -1.0};  // refracted direction of the beam
    std::int64_t maxEvents = 0;
    double coneCos = 1.0;
    int angleBins = 1;
    double profileMaxRadius = 1.0;
    int profileBins = 1;
    double thickness = std::numeric_limits<double>::infinity();

    void path(const ChannelMedium& m, Rng& rng, Counts& c) const {
        double px = 0.0, py = 0.0, pz = 0.0;
        Dir d = entry;
        std::int64_t events = 0;
        for (;;) {
            const double s = -std::log(rng.openUniform()) / m.sigmaT;
            if (d.z > 0.0 && s * d.z >= -pz) {
                // Reaches the boundary before the next collision.
                const double t = -pz / d.z;
                px += t * d.x;
                py += t * d.y;
                pz = 0.0;
                double cosT;
                if (!leavesThroughBoundary(eta, d.z, rng, cosT)) {
                    d.z = -d.z;  // internal (possibly total) reflection
                    continue;
                }
                if (events == 0)
                    ++c.ballistic;  // back out unreflected by the medium: only off a finite slab's bottom
                else
                    tallyExit(events, cosT, std::sqrt(px * px + py * py), c);
                break;
            }
            if (d.z < 0.0 && s * -d.z >= pz + thickness) {
                // Reaches the bottom of a finite slab first (never for the half-space).
                const double t = (pz + thickness) / -d.z;
                px += t * d.x;
                py += t * d.y;
                pz = -thickness;
                double cosT;
                if (!leavesThroughBoundary(eta, -d.z, rng, cosT)) {
                    d.z = -d.z;
                    continue;
                }
                if (events == 0) {
                    ++c.ballistic;
                } else {
                    ++c.transmitted;
                    if (events == 1) ++c.transmittedSingle;
                    if (cosT >= coneCos) ++c.transmittedCone;
                }
                break;
            }
            px += s * d.x;
            py += s * d.y;
            pz += s * d.z;
            const Collision k = collide(m.albedo, g, maxEvents, events, d, rng);
            if (k == Collision::Absorbed) {
                ++c.absorbed;
                break;
            }
            if (k == Collision::Truncated) {
                ++c.truncated;
                break;
            }
        }
        c.events += events;
    }

    void tallyExit(std::int64_t events, double cosOut, double r, Counts& c) const {
        assert(events >= 1);
        const bool single = events == 1;
        (single ? c.single : c.multiple) += 1;
        const int a = std::min(static_cast<int>(cosOut * angleBins), angleBins - 1);
        ++c.angle[a];
        if (single) ++c.angleSingle[a];
        if (cosOut >= coneCos) {
            ++c.cone;
            if (single) ++c.coneSingle;
        }
        if (r < profileMaxRadius) {
            const int b = std::min(static_cast<int>(r / profileMaxRadius * profileBins), profileBins - 1);
            ++c.profile[b];
            if (single) ++c.profileSingle[b];
        }
    }
};

}  // namespace

SlabRandomWalkResult simulateSlab(const ScatteringMaterial& material, double incidenceDeg,
                                  const SlabRandomWalkOptions& options) {
    material.validate();
    validateIncidence("simulateSlab", incidenceDeg);
    validateOptions(options);

    SlabRandomWalkResult result;
    result.incidenceDeg = incidenceDeg;
    result.paths = options.paths;
    result.coneHalfAngleDeg = options.coneHalfAngleDeg;
    for (int i = 0; i <= options.angleBins; ++i) result.angleBinEdges.push_back(double(i) / options.angleBins);
    for (int i = 0; i <= options.profileBins; ++i)
        result.profileBinEdges.push_back(options.profileMaxRadius * i / options.profileBins);

    // Entry: specular reflection (exact) and the refracted beam.
    const double thetaI = radians(incidenceDeg);
    double cosT;
    result.specular = fresnel(1.0 / material.eta, std::cos(thetaI), cosT);
    const double w0 = 1.0 - result.specular;

    Walk walk;
    walk.g = material.g;
    walk.eta = material.eta;
    const double sinT = std::sin(thetaI) / material.eta;
    walk.entry = {sinT, 0.0, -std::sqrt(std::max(0.0, 1.0 - sinT * sinT))};
    walk.maxEvents = options.maxEvents;
    walk.coneCos = std::cos(radians(options.coneHalfAngleDeg));
    walk.angleBins = options.angleBins;
    walk.profileMaxRadius = options.profileMaxRadius;
    walk.profileBins = options.profileBins;
    walk.thickness = options.thickness;

    std::array<ChannelMedium, 3> media;
    for (int c = 0; c < 3; ++c) {
        media[c].sigmaT = material.sigmaA[c] + material.sigmaS[c];
        media[c].albedo = material.sigmaS[c] / media[c].sigmaT;
    }

    std::vector<Counts> counts(3, Counts(options.angleBins, options.profileBins));
    if (w0 > 0.0)  // else total reflection at entry (eta < 1, beyond the critical angle)
        runChannelChunks(options.paths, options.threads, options.seed, counts,
                         [&](int channel, Rng& rng, Counts& c) { walk.path(media[channel], rng, c); });

    const double n = static_cast<double>(options.paths);
    auto estimate = [&](std::int64_t count, double normalisation) {
        return binomialEstimate(count, options.paths, w0, normalisation);
    };
    const double pi = std::numbers::pi;
    const double sinC = std::sin(radians(options.coneHalfAngleDeg));
    const double coneSolidAngle = pi * sinC * sinC;  // projected
    for (int c = 0; c < 3; ++c) {
        const Counts& k = counts[c];
        SlabChannelResult& r = result.channels[c];
        r.diffuse = estimate(k.single + k.multiple, 1.0);
        r.single = estimate(k.single, 1.0);
        r.multiple = estimate(k.multiple, 1.0);
        r.absorbed = estimate(k.absorbed, 1.0);
        r.truncated = estimate(k.truncated, 1.0);
        r.coneRadiance = estimate(k.cone, coneSolidAngle);
        r.coneRadianceSingle = estimate(k.coneSingle, coneSolidAngle);
        r.transmitted = estimate(k.transmitted, 1.0);
        r.transmittedSingle = estimate(k.transmittedSingle, 1.0);
        r.ballistic = estimate(k.ballistic, 1.0);
        r.transmittedConeRadiance = estimate(k.transmittedCone, coneSolidAngle);
        for (int i = 0; i < options.angleBins; ++i) {
            const double m1 = result.angleBinEdges[i], m2 = result.angleBinEdges[i + 1];
            const double omega = pi * (m2 * m2 - m1 * m1);
            r.angleRadiance.push_back(estimate(k.angle[i], omega));
            r.angleRadianceSingle.push_back(estimate(k.angleSingle[i], omega));
        }
        for (int i = 0; i < options.profileBins; ++i) {
            const double r1 = result.profileBinEdges[i], r2 = result.profileBinEdges[i + 1];
            const double area = pi * (r2 * r2 - r1 * r1);
            r.profile.push_back(estimate(k.profile[i], area));
            r.profileSingle.push_back(estimate(k.profileSingle[i], area));
        }
        r.truncatedPaths = k.truncated;
        r.meanEvents = static_cast<double>(k.events) / n;
    }
    return result;
}

// ---- two materials side by side ---------------------------------------------------------------

namespace {

// Salt of the split walk's stream family: it draws from Rng(mix64(seed ^ salt), channel, chunk),
// streams apart from simulateSlab()'s Rng(seed, channel, chunk) for the same seed.
constexpr std::uint64_t kSplitStreams = 0x5b1f'7a3c'd2e4'9061ull;

void validateSplitOptions(const SplitSlabOptions& o) {
    const auto bad = [](const char* field, const std::string& reason) {
        throw Error(ErrorKind::InvalidArgument, "SplitSlabOptions", field, reason, "simulateSplitSlab");
    };
    if (o.paths < 1) bad("paths", "must be >= 1, got " + formatNumber(o.paths));
    if (o.threads < 0) bad("threads", "must be >= 0, got " + formatNumber(o.threads));
    if (o.maxEvents < 1) bad("maxEvents", "must be >= 1, got " + formatNumber(o.maxEvents));
    if (!std::isfinite(o.entryHalfWidth) || o.entryHalfWidth <= 0.0)
        bad("entryHalfWidth", "must be finite and > 0, got " + formatNumber(o.entryHalfWidth));
    if (!std::isfinite(o.tallyHalfWidth) || o.tallyHalfWidth <= 0.0 || o.tallyHalfWidth > o.entryHalfWidth)
        bad("tallyHalfWidth", "must be finite, > 0 and <= entryHalfWidth (" +
            formatNumber(o.entryHalfWidth) + "), got " +
                                  formatNumber(o.tallyHalfWidth));
    if (o.bins < 1 || o.bins > 1000000) bad("bins", "must be in [1, 1000000], got " + formatNumber(o.bins));
}

// Validates one of the two materials; the message says which.
void validateSide(const ScatteringMaterial& m, const char* side) {
    try {
        m.validate();
    } catch (const Error& e) {
        const std::string context = std::string("simulateSplitSlab: ") + side + " material \"" + m.name + "\"";
        if (!e.field().empty()) throw Error(e.kind(), "ScatteringMaterial", e.field(), e.reason(), context);
        throw Error(e.kind(), context + ": " + e.what());
    }
}

// Integer tallies of one channel.
struct SplitCounts {
    std::int64_t leaving = 0, absorbed = 0, truncated = 0, events = 0;  // leaving: anywhere on z = 0
    std::vector<std::int64_t> bins;

    explicit SplitCounts(int n) : bins(n, 0) {}
    void add(const SplitCounts& o) {
        leaving += o.leaving;
        absorbed += o.absorbed;
        truncated += o.truncated;
        events += o.events;
        for (size_t i = 0; i < bins.size(); ++i) bins[i] += o.bins[i];
    }
};

struct SplitWalk {
    std::array<double, 2> g{};  // left, right
    double eta = 1.0;
    std::int64_t maxEvents = 0;
    double entryHalfWidth = 1.0;
    double tallyHalfWidth = 1.0;
    int bins = 1;

    // One path of one channel; m[0] is the left material (x < 0), m[1] the right (x >= 0).
    void path(const std::array<ChannelMedium, 2>& m, Rng& rng, SplitCounts& c) const {
        const double inf = std::numeric_limits<double>::infinity();
        // Entry on the strip at normal incidence (y is irrelevant: translation invariance).
        double px = entryHalfWidth * (2.0 * rng.uniform() - 1.0), pz = 0.0;
        int side = px < 0.0 ? 0 : 1;  // kept with the position: a crossing sets px = 0 exactly
        Dir d{0.0, 0.0, -1.0};
        std::int64_t events = 0;
        for (;;) {
            // A free flight: optical depth tau spent at the local sigma_t, across x = 0 if need be.
            double tau = -std::log(rng.openUniform());
            bool atTop = false;
            for (;;) {
                const double sigmaT = m[side].sigmaT;
                const double s = tau / sigmaT;
                const double tTop = d.z > 0.0 ? -pz / d.z : inf;
                const bool towardsPlane = side == 0 ? d.x > 0.0 : d.x < 0.0;
                const double tPlane = towardsPlane ? std::max(0.0, -px / d.x) : inf;
                if (tPlane < s && tPlane < tTop) {
                    pz += tPlane * d.z;
                    px = 0.0;
                    tau = std::max(0.0, tau - tPlane * sigmaT);
                    side ^= 1;
                    continue;
                }
                if (tTop <= s) {
                    px += tTop * d.x;
                    pz = 0.0;
                    atTop = true;
                } else {
                    px += s * d.x;
                    pz += s * d.z;
                }
                break;
            }
            if (atTop) {
                double cosOut;
                if (!leavesThroughBoundary(eta, d.z, rng, cosOut)) {
                    d.z = -d.z;  // internal (possibly total) reflection, then a new flight
                    continue;
                }
                assert(events >= 1);  // at normal incidence nothing comes back up unscattered
                ++c.leaving;
                if (px >= -tallyHalfWidth && px <= tallyHalfWidth) {
                    const int b = static_cast<int>((px + tallyHalfWidth) / (2.0 * tallyHalfWidth) * bins);
                    ++c.bins[std::clamp(b, 0, bins - 1)];
                }
                break;
            }
            const Collision k = collide(m[side].albedo, g[side], maxEvents, events, d, rng);
            if (k == Collision::Absorbed) {
                ++c.absorbed;
                break;
            }
            if (k == Collision::Truncated) {
                ++c.truncated;
                break;
            }
        }
        c.events += events;
    }
};

}  // namespace

SplitSlabResult simulateSplitSlab(const ScatteringMaterial& left, const ScatteringMaterial& right,
                                  const SplitSlabOptions& options) {
    validateSide(left, "left");
    validateSide(right, "right");
    if (left.eta != right.eta)
        invalid("simulateSplitSlab", "the two materials must have the same eta (the interface x = 0 is index-matched), "
                                     "got left \"" + left.name + "\" eta " + formatNumber(left.eta) + " and right \"" +
                                     right.name + "\" eta " + formatNumber(right.eta));
    validateSplitOptions(options);

    SplitSlabResult result;
    result.paths = options.paths;
    result.entryHalfWidth = options.entryHalfWidth;
    result.tallyHalfWidth = options.tallyHalfWidth;
    // Edges and centres odd-symmetric about x = 0 to the last bit (0 exactly where one falls there).
    const double halfT = options.tallyHalfWidth;
    const int bins = options.bins;
    const double width = 2.0 * halfT / bins;
    for (int i = 0; i <= bins; ++i) result.binEdges.push_back(halfT * (2.0 * i - bins) / bins);
    for (int i = 0; i < bins; ++i) result.binCentres.push_back(halfT * (2.0 * i + 1.0 - bins) / bins);

    // Entry at normal incidence: the exact specular reflection, the rest goes straight down.
    double cosT;
    result.specular = fresnel(1.0 / left.eta, 1.0, cosT);
    const double w0 = 1.0 - result.specular;

    SplitWalk walk;
    walk.g = {left.g, right.g};
    walk.eta = left.eta;
    walk.maxEvents = options.maxEvents;
    walk.entryHalfWidth = options.entryHalfWidth;
    walk.tallyHalfWidth = halfT;
    walk.bins = options.bins;

    std::array<std::array<ChannelMedium, 2>, 3> media;
    for (int c = 0; c < 3; ++c) {
        int s = 0;
        for (const ScatteringMaterial* m : {&left, &right}) {
            media[c][s].sigmaT = m->sigmaA[c] + m->sigmaS[c];
            media[c][s].albedo = m->sigmaS[c] / media[c][s].sigmaT;
            ++s;
        }
    }

    std::vector<SplitCounts> counts(3, SplitCounts(options.bins));
    runChannelChunks(options.paths, options.threads, detail::mix64(options.seed ^ kSplitStreams), counts,
                     [&](int channel, Rng& rng, SplitCounts& c) { walk.path(media[channel], rng, c); });

    // A path carries the power 2 W w0 / paths per unit length in y; a bin's area per unit length
    // in y is its width: radiosity = w0 (k / paths) / (width / 2 W).
    const double binShare = width / (2.0 * options.entryHalfWidth);
    for (int c = 0; c < 3; ++c) {
        const SplitCounts& k = counts[c];
        for (int i = 0; i < options.bins; ++i)
            result.radiosity[c].push_back(binomialEstimate(k.bins[i], options.paths, w0, binShare));
        result.diffuse[c] = binomialEstimate(k.leaving, options.paths, w0, 1.0);
        result.absorbed[c] = binomialEstimate(k.absorbed, options.paths, w0, 1.0);
        result.truncated[c] = binomialEstimate(k.truncated, options.paths, w0, 1.0);
        result.truncatedPaths[c] = k.truncated;
        result.meanEvents[c] = static_cast<double>(k.events) / static_cast<double>(options.paths);
    }
    return result;
}

// ---- exact references -------------------------------------------------------------------------

namespace {

struct Quadrature {
    std::vector<double> x, w;
};

// Legendre polynomial P_n(z) and its derivative.
void legendre(int n, double z, double& p, double& dp) {
    double p0 = 1.0, p1 = z;
    for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
    }
    p = p1;
    dp = n * (z * p1 - p0) / (z * z - 1.0);
}

// n-point (n >= 2) Gauss-Legendre rule on [a, b] appended to q.
void gaussLegendre(int n, double a, double b, Quadrature& q) {
    for (int i = 0; i < n; ++i) {
        double z = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
        double p, dp;
        for (int it = 0; it < 100; ++it) {
            legendre(n, z, p, dp);
            const double dz = p / dp;
            z -= dz;
            if (std::abs(dz) < 1e-16) break;
        }
        legendre(n, z, p, dp);
        q.x.push_back(0.5 * (a + b) + 0.5 * (b - a) * z);
        q.w.push_back((b - a) / ((1.0 - z * z) * dp * dp));
    }
}

constexpr int kNodesPerPanel = 16;

// Composite rule on [a, b], panels graded geometrically towards a (H and the kernels vary on the
// scale of mu near 0).
void gradedRule(double a, double b, Quadrature& q) {
    if (!(b > a)) return;
    const double breaks[] = {0.0, 1e-5, 1e-4, 1e-3, 1e-2, 0.04, 0.1, 0.2, 0.35, 0.5, 0.7, 1.0};
    for (size_t i = 0; i + 1 < std::size(breaks); ++i)
        gaussLegendre(kNodesPerPanel, a + (b - a) * breaks[i], a + (b - a) * breaks[i + 1], q);
}

// Rule on [a, b] for integrands with a square-root edge at a (Fresnel transmittance at the
// critical angle): mu = a + (b - a) t^2, graded in t.
void sqrtEdgeRule(double a, double b, Quadrature& q) {
    if (!(b > a)) return;
    Quadrature t;
    const double breaks[] = {0.0, 0.02, 0.1, 0.25, 0.5, 0.75, 1.0};
    for (size_t i = 0; i + 1 < std::size(breaks); ++i) gaussLegendre(kNodesPerPanel, breaks[i], breaks[i + 1], t);
    for (size_t i = 0; i < t.x.size(); ++i) {
        q.x.push_back(a + (b - a) * t.x[i] * t.x[i]);
        q.w.push_back(t.w[i] * 2.0 * (b - a) * t.x[i]);
    }
}

void checkAlbedo(const std::string& where, double albedo) {
    if (!std::isfinite(albedo) || albedo < 0.0 || albedo > 1.0)
        invalid(where, "albedo must be in [0, 1], got " + formatNumber(albedo));
}

// Solves A x = b in place (Gaussian elimination with partial pivoting); A is n x n row-major.
void solve(std::vector<double>& a, std::vector<double>& b) {
    const size_t n = b.size();
    for (size_t k = 0; k < n; ++k) {
        size_t p = k;
        for (size_t i = k + 1; i < n; ++i)
            if (std::abs(a[i * n + k]) > std::abs(a[p * n + k])) p = i;
        if (p != k) {
            for (size_t j = 0; j < n; ++j) std::swap(a[k * n + j], a[p * n + j]);
            std::swap(b[k], b[p]);
        }
        for (size_t i = k + 1; i < n; ++i) {
            const double f = a[i * n + k] / a[k * n + k];
            if (f == 0.0) continue;
            for (size_t j = k; j < n; ++j) a[i * n + j] -= f * a[k * n + j];
            b[i] -= f * b[k];
        }
    }
    for (size_t k = n; k-- > 0;) {
        double s = b[k];
        for (size_t j = k + 1; j < n; ++j) s -= a[k * n + j] * b[j];
        b[k] = s / a[k * n + k];
    }
}

// H on the nodes of a graded rule, and its evaluation anywhere by the defining equation.
// Started by 200 sweeps of H = 1 / (1 - (albedo / 2) mu integral H(mu') / (mu + mu') dmu'),
// which rises monotonically towards the solution (slowly for albedo near 1), then polished by
// Newton's method on the discretised 1 / H form (quadratic, also at albedo = 1).
class HFunction {
public:
    explicit HFunction(double albedo) : m_albedo(albedo), m_s(std::sqrt(1.0 - albedo)) {
        gradedRule(0.0, 1.0, m_q);
        const size_t n = m_q.x.size();
        const std::vector<double>& x = m_q.x;
        const std::vector<double>& w = m_q.w;
        m_h.assign(n, 1.0);
        std::vector<double> next(n);
        for (int it = 0; it < 200; ++it) {
            for (size_t i = 0; i < n; ++i) {
                double sum = 0.0;
                for (size_t j = 0; j < n; ++j) sum += w[j] * m_h[j] / (x[i] + x[j]);
                next[i] = 1.0 / (1.0 - 0.5 * albedo * x[i] * sum);
            }
            m_h.swap(next);
        }
        // Newton on G_i = H_i (s + (albedo / 2) sum_j w_j mu_j H_j / (mu_i + mu_j)) - 1.
        std::vector<double> jac(n * n), g(n);
        for (int it = 0; it < 50; ++it) {
            for (size_t i = 0; i < n; ++i) {
                const double inv = inverse(x[i]);
                g[i] = -(m_h[i] * inv - 1.0);
                for (size_t k = 0; k < n; ++k)
                    jac[i * n + k] = m_h[i] * 0.5 * albedo * w[k] * x[k] / (x[i] + x[k]) + (i == k ? inv : 0.0);
            }
            solve(jac, g);
            double change = 0.0;
            for (size_t i = 0; i < n; ++i) {
                m_h[i] += g[i];
                change = std::max(change, std::abs(g[i]) / m_h[i]);
            }
            if (change < 1e-14) break;
        }
    }
    double operator()(double mu) const { return 1.0 / inverse(mu); }

private:
    double inverse(double mu) const {
        double sum = 0.0;
        for (size_t j = 0; j < m_q.x.size(); ++j) sum += m_q.w[j] * m_q.x[j] * m_h[j] / (mu + m_q.x[j]);
        return m_s + 0.5 * m_albedo * sum;
    }
    double m_albedo, m_s;
    Quadrature m_q;
    std::vector<double> m_h;
};

}  // namespace

double chandrasekharH(double albedo, double mu) {
    checkAlbedo("chandrasekharH", albedo);
    if (!std::isfinite(mu) || mu < 0.0 || mu > 1.0) invalid("chandrasekharH", "mu must be in [0, 1], got " +
                                                            formatNumber(mu));
    return HFunction(albedo)(mu);
}

HalfSpaceReflectance isotropicHalfSpaceReflectance(double albedo, double eta, double incidenceDeg,
                                                   double coneHalfAngleDeg) {
    const std::string where = "isotropicHalfSpaceReflectance";
    checkAlbedo(where, albedo);
    if (!std::isfinite(eta) || eta < 0.4 || eta > 2.5) invalid(where, "eta must be in [0.4, 2.5], got " +
                                                                      formatNumber(eta));
    validateIncidence(where, incidenceDeg);
    if (!std::isfinite(coneHalfAngleDeg) || coneHalfAngleDeg <= 0.0 || coneHalfAngleDeg > 90.0)
        invalid(where, "coneHalfAngleDeg must be in (0, 90], got " + formatNumber(coneHalfAngleDeg));

    HalfSpaceReflectance out;
    const double pi = std::numbers::pi;
    double mu0;  // cosine of the refracted beam inside
    out.specular = fresnel(1.0 / eta, std::cos(radians(incidenceDeg)), mu0);
    const double e = 1.0 - out.specular;  // refracted irradiance
    if (e <= 0.0 || albedo == 0.0) return out;

    // Inside-to-outside crossing: reflectance and (for the outgoing radiance) refracted cosine.
    auto fresnelIn = [&](double mu) {
        double c;
        return fresnel(eta, mu, c);
    };
    // Critical cosine inside (TIR for mu < muC).
    const double muC = eta > 1.0 ? std::sqrt(1.0 - 1.0 / (eta * eta)) : 0.0;

    const HFunction h(albedo);
    const double h0 = h(mu0);
    auto rho = [&](double mu, double hmu, double muP, double hmuP) {
        return albedo / (4.0 * pi) * hmu * hmuP / (mu + muP);
    };

    // Nodes of the adding equation: graded on [0, muC] (F_in = 1), square-root edge on [muC, 1].
    Quadrature q;
    gradedRule(0.0, muC, q);
    if (muC > 0.0)
        sqrtEdgeRule(muC, 1.0, q);
    else
        gradedRule(0.0, 1.0, q);
    const size_t n = q.x.size();
    std::vector<double> hq(n), fq(n);
    for (size_t i = 0; i < n; ++i) hq[i] = h(q.x[i]), fq[i] = fresnelIn(q.x[i]);

    // (I - K) u = b with K_ij = 2 pi w_j rho(mu_i, mu_j) F_in(mu_j) mu_j, b_i = rho(mu_i, mu0) e.
    std::vector<double> a(n * n), u(n);
    for (size_t i = 0; i < n; ++i) {
        u[i] = rho(q.x[i], hq[i], mu0, h0) * e;
        for (size_t j = 0; j < n; ++j)
            a[i * n + j] = (i == j ? 1.0 : 0.0) - 2.0 * pi * q.w[j] * rho(q.x[i], hq[i], q.x[j], hq[j]) * fq[j] * q.x[j];
    }
    solve(a, u);
    auto upward = [&](double mu) {  // L_up(mu) by the Nystrom interpolant
        const double hmu = h(mu);
        double s = rho(mu, hmu, mu0, h0) * e;
        for (size_t j = 0; j < n; ++j) s += 2.0 * pi * q.w[j] * rho(mu, hmu, q.x[j], hq[j]) * fq[j] * q.x[j] * u[j];
        return s;
    };
    auto upwardSingle = [&](double mu) { return albedo / (4.0 * pi) * e / (mu + mu0); };

    for (size_t j = 0; j < n; ++j) {
        out.diffuse += 2.0 * pi * q.w[j] * (1.0 - fq[j]) * u[j] * q.x[j];
        out.single += 2.0 * pi * q.w[j] * (1.0 - fq[j]) * upwardSingle(q.x[j]) * q.x[j];
    }
    out.multiple = out.diffuse - out.single;

    // Cone: outside cos(theta_o) >= cos(half angle) <=> inside mu >= muCone.
    const double sinC = std::sin(radians(coneHalfAngleDeg));
    const double muCone = std::sqrt(std::max(0.0, 1.0 - sinC * sinC / (eta * eta)));
    Quadrature qc;
    sqrtEdgeRule(std::max(muCone, muC), 1.0, qc);
    double power = 0.0;
    for (size_t j = 0; j < qc.x.size(); ++j)
        power += 2.0 * pi * qc.w[j] * (1.0 - fresnelIn(qc.x[j])) * upward(qc.x[j]) * qc.x[j];
    out.coneRadiance = power / (pi * sinC * sinC);
    return out;
}

}  // namespace sss
