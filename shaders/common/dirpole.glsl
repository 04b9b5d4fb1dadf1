// Directional dipole BSSRDF (Frisvad, Hachisuka, Kjeldsen, ACM TOG 34(1), 2014), per point pair.
//
// ONE text, two compilers: GLSL 4.50 (real = float) in the shaders, and C++20 (real = double,
// glm) in src/mesh/dirpole.cpp, which defines SSS_CPP and includes this file. Hence the subset:
// no out/inout parameters, no swizzles beyond .x/.y/.z, only functions with the same meaning in
// GLSL and glm, floating-point literals only (glm has no int * dvec3).
//
// Conventions (spec mesh-scattering.md §1.3-1.4):
//   x_i, n_i  entry point and its outward unit normal
//   w_i       unit vector from x_i TOWARDS the light (not the propagation direction)
//   x_o, n_o  exit point and its outward unit normal; w_o points from x_o towards the viewer
//   x = x_o - x_i; all lengths in the unit the DirpoleParams were derived in.
// S_d is per RGB channel, without Fresnel factors, in length^-2; the full BSSRDF is
// T(eta, w_i.n_i) * S_d * T(eta, w_o.n_o).
//
// Guards (spec §1.5); each touches only a degenerate corner of the model:
//   - r -> 0 or x parallel to n_i: the modified tangent-plane normal n_i* falls back to n_i
//     (returning 0 would darken the kernel centre);
//   - back-facing light (w_i.n_i < 0): only the tangential part of w_i is refracted, so the
//     refracted ray stays a unit vector (T(eta, cos <= 0) = 0 removes such light in the BSSRDF);
//   - the cos(beta) radicand is non-negative by construction (a cross product, not r^2 - (x.w)^2);
//   - source distances are floored at DIRPOLE_MIN_DISTANCE * D: d_r -> 0 only when mu_0 -> 0+
//     at r -> 0 (a crease, or grazing light with eta near 1), where S'_d grows like 1/d_r^3;
//   - sigma_a = 0 (sigma_tr = 0) needs nothing: exp(0) = 1 and every divisor stays > 0;
//   - the result is max(0, real - virtual) with NaN/Inf replaced by 0 explicitly (GLSL max()
//     of NaN is undefined).

#ifndef SSS_CPP
#ifndef real
#define real float
#define real3 vec3
#endif
#endif

// Entry cosines at which the calibrated profile's factor is given: mu = 1 - 0.19 i
// (sss::profileIncidenceNode), interpolated linearly between.
const int DIRPOLE_INCIDENCE_NODES = 6;
// Reduced optical thicknesses at which its transmission factor is given: 0.25 * 2^i
// (sss::profileThicknessNode), its logarithm interpolated linearly in log2 between.
const int DIRPOLE_THICKNESS_NODES = 7;

// Material constants, derived once on the CPU in double (sss::deriveDipoleConstants) and
// uploaded as uniforms, e.g. `uniform DirpoleParams dirpole;` set member by member
// ("dirpole.sigmaTr", ...) from the DipoleConstants fields of the same names, cast to float.
// Per channel (r, g, b) unless noted.
struct DirpoleParams {
    real3 sigmaTr;        // effective transport coefficient sqrt(3 sigma_a sigma_t')
    real3 D;              // diffusion coefficient 1 / (3 sigma_t')
    real3 de;             // extrapolation distance 2.131 D / sqrt(alpha')
    real3 sigmaT;         // UNREDUCED extinction sigma_s + sigma_a (back-lit d_r only)
    real eta;             // relative index n_inside / n_outside
    real cPhi;            // C_phi(eta) = (1 - 2 C_1(eta)) / 4
    real cE;              // C_E(eta) = (1 - 3 C_2(eta)) / 2
    real A;               // (1 - C_E) / (2 C_phi)
    real normalization;   // 1 / (4 C_phi(1/eta)) / (4 pi^2)
    // The profile on top of the dipole (sss::ScatteringProfile): 1, 0 for the paper's dipole.
    real3 profileScale;   // per-channel factor on S_d (the renderer's cut-tail correction)
    real3 incidenceScale[DIRPOLE_INCIDENCE_NODES];  // calibration per channel at the entry cosines
    real3 transmissionScale[DIRPOLE_THICKNESS_NODES];  // calibration per channel at the thicknesses
    real3 albedo;         // single-scattering albedo sigma_s / sigma_t (unreduced)
    real g;               // Henyey-Greenstein mean cosine of the single-scattering term
    real singleScattering;  // weight of the single-scattering term (1 or 0)
};

// Source distances never drop below this fraction of D (see the guards above). The test
// vectors and smooth geometry stay above 0.2 D, so the floor only catches degenerate limits.
const real DIRPOLE_MIN_DISTANCE = 0.1;
// n_i* falls back to n_i when sin(angle(n_i, x))^2 is below this (|sin| < 1e-3): there the
// cross product is dominated by rounding, especially in float.
const real DIRPOLE_PARALLEL_SIN2 = 1e-6;

// Refracted incident direction w_12 = refract(-w_i, n_i, 1/eta); points into the medium.
// Uses the tangential part of w_i only: identical to the textbook formula when w_i.n_i >= 0,
// and still a unit vector for back-facing light or total internal reflection (eta < 1).
real3 dirpoleRefract(real3 wi, real3 ni, real eta) {
    real3 tangential = wi - dot(wi, ni) * ni;
    real sin2 = dot(tangential, tangential) / (eta * eta);  // sin^2 of the refracted angle
    real3 t = tangential / (-eta);
    if (sin2 > 1.0) return t / sqrt(sin2);  // TIR: the grazing limit
    return t - ni * sqrt(1.0 - sin2);
}

// Modified tangent-plane normal n_i* = x^ x (n_i x x^) / |n_i x x^|: n_i made perpendicular to
// x. Falls back to n_i when r <= minR or x is (nearly) parallel to n_i.
real3 dirpoleModifiedNormal(real3 x, real3 ni, real minR) {
    real r = length(x);
    if (!(r > minR)) return ni;
    real3 xh = x / r;  // unit first, so nothing below can underflow
    real3 c = cross(ni, xh);
    if (dot(c, c) <= DIRPOLE_PARALLEL_SIN2) return ni;
    return normalize(cross(xh, c));
}

// S'_d(x, w, r) / N: a ray source in an infinite medium (spec §1.3) without the normalisation N.
// x: geometric vector from the source's surface point to x_o; w: source direction; r: source
// distance (d_r or d_v, > 0).
real dirpoleSourceTerm(real3 x, real3 w, real r, real3 no, real sigmaTr, real D, real cPhi, real cE) {
    real sr = sigmaTr * r;
    real e1 = 1.0 + sr;
    real r2 = r * r;
    real xw = dot(x, w);
    real xn = dot(x, no);
    real phiTerm = cPhi * (r2 / D + 3.0 * e1 * xw);
    real eTerm = cE * (3.0 * D * e1 * dot(w, no) - (e1 + 3.0 * D * (3.0 * e1 + sr * sr) / r2 * xw) * xn);
    return exp(-sr) / (r2 * r) * (phiTerm - eTerm);
}

// One channel of S_d / N = S'_d(real) - S'_d(virtual), unclamped. w12: refracted direction;
// niStar: modified tangent-plane normal; sigmaT: unreduced extinction of this channel.
real dirpoleChannel(real3 x, real3 w12, real3 niStar, real3 no, real sigmaTr, real D, real de, real sigmaT,
                    real A, real cPhi, real cE) {
    real r2 = dot(x, x);
    real minD2 = (DIRPOLE_MIN_DISTANCE * D) * (DIRPOLE_MIN_DISTANCE * D);

    // Real source distance d_r: front-lit (mu0 > 0) or back-lit, the latter with unreduced sigma_t.
    real mu0 = -dot(no, w12);
    real dr2;
    if (mu0 > 0.0) {
        // r^2 - (x.w12)^2 written as |x cross w12|^2 (w12 is a unit vector): no cancellation
        // when x is nearly parallel to w12, where the sqrt would amplify it.
        real3 xCrossW = cross(x, w12);
        real cosBeta = -sqrt(dot(xCrossW, xCrossW) / (r2 + de * de));
        dr2 = r2 + D * mu0 * (D * mu0 - 2.0 * de * cosBeta);
    } else {
        real z = 1.0 / (3.0 * sigmaT);
        dr2 = r2 + z * z;
    }
    real dr = sqrt(max(dr2, minD2));

    // Virtual source x_v = x_i + 2 A d_e n_i*, direction w12 mirrored in the modified tangent plane.
    real3 xv = x - (2.0 * A * de) * niStar;  // x_o - x_v
    real3 wv = w12 - (2.0 * dot(w12, niStar)) * niStar;
    real dv = sqrt(max(dot(xv, xv), minD2));

    return dirpoleSourceTerm(x, w12, dr, no, sigmaTr, D, cPhi, cE) -
           dirpoleSourceTerm(xv, wv, dv, no, sigmaTr, D, cPhi, cE);
}

// max(v, 0) with NaN and Inf mapped to 0.
real dirpoleSanitize(real v) {
    if (isnan(v) || isinf(v)) return 0.0;
    return max(v, 0.0);
}

// The profile's per-channel factor for light entering at cosine mu = w_i . n_i.
real3 dirpoleIncidenceScale(DirpoleParams p, real mu) {
    real x = clamp((1.0 - mu) / 0.19, 0.0, 5.0);
    int i = int(min(floor(x), 4.0));
    real t = x - real(i);
    return p.incidenceScale[i] * (1.0 - t) + p.incidenceScale[i + 1] * t;
}

// The transmission factor of one channel (index c) through a reduced optical thickness tau.
real dirpoleThicknessScale(DirpoleParams p, real tau, int c) {
    real x = clamp(log2(max(tau, 1e-6)) + 2.0, 0.0, 6.0);
    int i = int(min(floor(x), 5.0));
    real t = x - real(i);
    // Log-linear, as the table is interpolated on the CPU (the factor spans orders of magnitude).
    real a = max(p.transmissionScale[i][c], 1e-30);
    return a * pow(max(p.transmissionScale[i + 1][c], 1e-30) / a, t);
}

// The calibration of light that comes back out on the side it went in (mu0 = -n_o.w12 > 0, the
// dipole's front-lit branch: reflection, which it overestimates by 22-37 %) is the half-space
// factor at the entry cosine. Light that goes through (mu0 < 0, the back-lit branch: thin parts
// lit from behind) gets the slab-transmission factor at the thickness between the two points,
// sigma_t' (x.n_o - x.n_i) / 2 (exact for a slab, whatever the pair's lateral offset). The two
// blend smoothly over -0.2 < mu0 < 0.2 (side-lit pairs).
real3 dirpoleTransportScale(DirpoleParams p, real3 wi, real3 ni, real3 w12, real3 x, real3 no) {
    real w = smoothstep(-0.2, 0.2, -dot(no, w12));
    real d = max(0.5 * (dot(x, no) - dot(x, ni)), 0.0);
    real3 tau = d / (3.0 * p.D);  // sigma_t' = 1 / (3 D)
    real3 through = real3(dirpoleThicknessScale(p, tau.x, 0), dirpoleThicknessScale(p, tau.y, 1),
                          dirpoleThicknessScale(p, tau.z, 2));
    return dirpoleIncidenceScale(p, dot(wi, ni)) * w + through * (1.0 - w);
}

// S_d for RGB (length^-2, no Fresnel factors). Normals and w_i must be unit vectors.
real3 dirpoleSd(DirpoleParams p, real3 xi, real3 ni, real3 wi, real3 xo, real3 no) {
    real3 x = xo - xi;
    real3 w12 = dirpoleRefract(wi, ni, p.eta);
    real minR = 1e-6 * min(min(p.D.x, p.D.y), p.D.z);  // "x_o = x_i" relative to the smallest D
    real3 niStar = dirpoleModifiedNormal(x, ni, minR);
    real red = dirpoleChannel(x, w12, niStar, no, p.sigmaTr.x, p.D.x, p.de.x, p.sigmaT.x, p.A, p.cPhi, p.cE);
    real green = dirpoleChannel(x, w12, niStar, no, p.sigmaTr.y, p.D.y, p.de.y, p.sigmaT.y, p.A, p.cPhi, p.cE);
    real blue = dirpoleChannel(x, w12, niStar, no, p.sigmaTr.z, p.D.z, p.de.z, p.sigmaT.z, p.A, p.cPhi, p.cE);
    return real3(dirpoleSanitize(red * p.normalization), dirpoleSanitize(green * p.normalization),
                 dirpoleSanitize(blue * p.normalization)) *
           (p.profileScale * dirpoleTransportScale(p, wi, ni, w12, x, no));
}

// Exact dielectric Fresnel transmittance T = 1 - F_r for light crossing a boundary of relative
// index eta at cosTheta (angle to the normal, measured outside). By reciprocity the same value
// serves entry (cos = w_i.n_i) and exit (cos = w_o.n_o). 0 for cosTheta <= 0 and under total
// internal reflection (eta < 1).
real dirpoleFresnelT(real eta, real cosTheta) {
    if (!(cosTheta > 0.0)) return 0.0;
    real c = min(cosTheta, 1.0);
    real sin2 = (1.0 - c * c) / (eta * eta);
    if (sin2 >= 1.0) return 0.0;
    real ct = sqrt(1.0 - sin2);
    real rs = (c - eta * ct) / (c + eta * ct);
    real rp = (eta * c - ct) / (eta * c + ct);
    return 1.0 - 0.5 * (rs * rs + rp * rp);
}

// Full BSSRDF without the single-scattering term: T(eta, w_i) S_d T(eta, w_o).
real3 dirpoleBssrdf(DirpoleParams p, real3 xi, real3 ni, real3 wi, real3 xo, real3 no, real3 wo) {
    return dirpoleSd(p, xi, ni, wi, xo, no) *
           (dirpoleFresnelT(p.eta, dot(wi, ni)) * dirpoleFresnelT(p.eta, dot(wo, no)));
}

// Henyey-Greenstein phase function (per steradian) at the cosine of the scattering angle.
real dirpolePhaseHG(real g, real cosTheta) {
    real d = 1.0 + g * g - 2.0 * g * cosTheta;
    return (1.0 - g * g) / (4.0 * 3.14159265358979 * d * sqrt(d));
}

// Single scattering of a locally flat half-space (sss::evaluateSingleScattering): radiance
// towards w_o per unit irradiance on the surface from w_i (both outside, unit; n the outward
// unit normal). The refracted beam meets the exit ray at every depth z, with attenuation
// exp(-sigma_t z (1/mu_i' + 1/mu_o')), so integrating over z leaves 1 / (mu_i' + mu_o');
// leaving the medium divides radiance by eta^2.
real3 dirpoleSingleScattering(DirpoleParams p, real3 n, real3 wi, real3 wo) {
    real cosI = dot(wi, n);
    real cosO = dot(wo, n);
    if (!(p.singleScattering > 0.0) || !(cosI > 0.0) || !(cosO > 0.0)) return real3(0.0);
    real3 down = dirpoleRefract(wi, n, p.eta);  // propagation of the refracted beam
    real3 up = -dirpoleRefract(wo, n, p.eta);   // propagation of the light that leaves towards w_o
    real muI = -dot(down, n);
    real muO = dot(up, n);
    if (!(muI > 0.0) || !(muO > 0.0)) return real3(0.0);
    real t = dirpoleFresnelT(p.eta, cosI) * dirpoleFresnelT(p.eta, cosO);
    real f = p.singleScattering * t * dirpolePhaseHG(p.g, dot(down, up)) / (p.eta * p.eta * (muI + muO));
    return p.albedo * f;
}
