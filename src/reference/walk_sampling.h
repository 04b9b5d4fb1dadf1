#pragma once
// Internal: the sampling pieces the random walks share (sss/random_walk.h): the random streams,
// the exact Fresnel reflectance of a smooth dielectric and Henyey-Greenstein scattering. One copy,
// so that the slab walk and the mesh walk are the same physics.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace sss::detail {

/// |g| below this is sampled (and evaluated) as exactly isotropic.
inline constexpr double kIsotropicG = 1e-3;

/// splitmix64 step: advances `state` and returns a well-mixed 64-bit value.
inline std::uint64_t splitmix64(std::uint64_t& state) {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/// The murmur3 64-bit finaliser: hashes stream identifiers (seed, channel, pixel...) together.
inline std::uint64_t mix64(std::uint64_t z) {
    z = (z ^ (z >> 33)) * 0xff51afd7ed558ccdull;
    z = (z ^ (z >> 33)) * 0xc4ceb9fe1a85ec53ull;
    return z ^ (z >> 33);
}

/// xoshiro256++ (Blackman and Vigna), its state filled by splitmix64 from one 64-bit key as its
/// authors recommend. One instance is one independent stream.
class Xoshiro256 {
public:
    explicit Xoshiro256(std::uint64_t key) {
        for (auto& s : m_s) s = splitmix64(key);
    }
    std::uint64_t next() {
        const std::uint64_t result = rotl(m_s[0] + m_s[3], 23) + m_s[0];
        const std::uint64_t t = m_s[1] << 17;
        m_s[2] ^= m_s[0];
        m_s[3] ^= m_s[1];
        m_s[1] ^= m_s[2];
        m_s[0] ^= m_s[3];
        m_s[2] ^= t;
        m_s[3] = rotl(m_s[3], 45);
        return result;
    }
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)
    double openUniform() { return (static_cast<double>(next() >> 11) + 0.5) * 0x1.0p-53; }  // (0, 1)

private:
    static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
    std::uint64_t m_s[4];
};

/// Exact unpolarised Fresnel reflectance for light crossing from index n1 into n2, ratio =
/// n1 / n2, meeting the interface at cosI in [0, 1] to the normal. Sets cosT to the refracted
/// cosine (0 under total internal reflection, where F = 1).
inline double fresnelReflectance(double ratio, double cosI, double& cosT) {
    cosI = std::clamp(cosI, 0.0, 1.0);
    const double sin2T = ratio * ratio * (1.0 - cosI * cosI);
    if (sin2T >= 1.0) {
        cosT = 0.0;
        return 1.0;
    }
    cosT = std::sqrt(1.0 - sin2T);
    if (ratio == 1.0) return 0.0;
    const double rs = (ratio * cosI - cosT) / (ratio * cosI + cosT);
    const double rp = (cosI - ratio * cosT) / (cosI + ratio * cosT);
    return 0.5 * (rs * rs + rp * rp);
}

/// Henyey-Greenstein phase function, sr^-1, at cosTheta between the propagation directions
/// before and after scattering (positive g = forward).
inline double henyeyGreenstein(double g, double cosTheta) {
    if (std::abs(g) < kIsotropicG) return 0.25 / std::numbers::pi;
    const double denom = 1.0 + g * g - 2.0 * g * cosTheta;
    return (1.0 - g * g) / (4.0 * std::numbers::pi * denom * std::sqrt(denom));
}

/// A new unit direction at angle theta to the unit vector `d` with cos(theta) drawn from HG(g),
/// uniform azimuth. V is any type with members x, y, z built from {x, y, z}.
template <typename V, typename Rng>
V scatterHenyeyGreenstein(const V& d, double g, Rng& rng) {
    const double u1 = rng.uniform();
    const double u2 = rng.uniform();
    double cosT;
    if (std::abs(g) < kIsotropicG) {
        cosT = 1.0 - 2.0 * u1;
    } else {
        const double s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u1);
        cosT = (1.0 + g * g - s * s) / (2.0 * g);
    }
    cosT = std::clamp(cosT, -1.0, 1.0);
    const double sinT = std::sqrt(std::max(0.0, 1.0 - cosT * cosT));
    const double phi = 2.0 * std::numbers::pi * u2;
    const double cp = std::cos(phi) * sinT, sp = std::sin(phi) * sinT;
    // Orthonormal basis around d (Duff et al. 2017).
    const double sign = std::copysign(1.0, d.z);
    const double a = -1.0 / (sign + d.z);
    const double b = d.x * d.y * a;
    const double tx = 1.0 + sign * d.x * d.x * a, ty = sign * b, tz = -sign * d.x;
    const double bx = b, by = sign + d.y * d.y * a, bz = -d.y;
    const double nx = cp * tx + sp * bx + cosT * d.x;
    const double ny = cp * ty + sp * by + cosT * d.y;
    const double nz = cp * tz + sp * bz + cosT * d.z;
    const double len = std::sqrt(nx * nx + ny * ny + nz * nz);
    return V{nx / len, ny / len, nz / len};
}

}  // namespace sss::detail
