#pragma once
// The profile's near field: the light entering within a radius rho of x_o (measured across the
// light, on the sampling disk of shaders/mesh/radiosity_estimate.glsl), as if the surface there
// were flat and lit like x_o itself; a table over the incidence angle gives it exactly. The
// vertex estimate interpolates its radiosity less this near field, and the combine pass adds the
// near field back per pixel (shaders/mesh/near_field.glsl): with rho about a triangle wide, the
// interpolated part varies little across a triangle while the per-pixel part keeps the detail a
// triangle cannot hold. On triangles many diffusion lengths wide (life-size objects) the near
// field is nearly all of the light. Derivation and measurements: docs/near-field.md.
#include "gl/program.h"
#include "sss/bssrdf.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <vector>

namespace sss::detail {

inline constexpr int kNearFieldNodes = 33;  // cos theta = 0, 1/32, ..., 1 (NEAR_FIELD_NODES in GLSL)
inline constexpr int kNearFieldTaps = 12;   // NEAR_FIELD_TAPS in GLSL
inline constexpr int kNearFieldRingNodes = 33;  // NEAR_FIELD_RING_NODES in GLSL

/// A tap's ring over a surface whose cos theta rises at g per unit length towards the light (the
/// terminator at a distance t from x_o along that rise, t > 0 beyond it): the mean over the tap's
/// annulus of the disk, weighted by the profile, of H = mean over the azimuth of (r cos phi - t)+
/// and Q of its square; g H is the mean lit cos theta, g Q / H that mean weighted by itself.
/// Tabulated at t = outer (2 i / (N - 1) - 1); below -outer every ring is lit and H = -t,
/// Q = t^2 + meanSquareRadius / 2 exactly; from +outer on nothing is lit.
struct NearFieldRingTable {
    float outer = 0.0f;                ///< the annulus's outer radius, scene units
    glm::vec3 meanSquareRadius{0.0f};  ///< per channel, the profile-weighted mean of r^2 over it
    std::array<glm::vec3, kNearFieldRingNodes> h{}, q{};
};

/// The ring means of a unit rise at a ring of radius r, the terminator at t:
/// (mean (r cos phi - t)+, mean ((r cos phi - t)+)^2) over phi.
glm::dvec2 nearFieldRingMoments(double r, double t);

struct NearFieldTable {
    float radius = 0.0f;  ///< rho, scene units (0: no near field)
    /// Per channel, how much of the difference between the light sampled within rho and the
    /// near field the vertex estimate interpolates (shaders/mesh/vertex_estimate.comp):
    /// nearFieldCorrection() of the channel's edge length in reduced mean free paths.
    glm::vec3 correction{1.0f};
    /// Per node i (cos theta_i = i / 32): T(eta, cos theta) times the integral of S_d over the
    /// flat surface points whose light-facing disk offset is within rho, per unit irradiance on
    /// the surface (rgb, 1/sr). The light x_o re-emits is this times E cos theta.
    std::array<glm::vec3, kNearFieldNodes> reflectance{};
    /// Where the near field looks up the light's visibility, so a shadow's edge is blurred as the
    /// profile blurs it: radii on the light's disk (scene units) and per-channel weights summing
    /// to 1, each tap the ring of the profile around its radius (lit head-on).
    std::array<float, kNearFieldTaps> tapRadius{};
    std::array<glm::vec3, kNearFieldTaps> tapWeight{};
    /// Per tap, its annulus's light across a terminator: how the near field's points follow a
    /// surface that turns towards the light (nearFieldRingLit in shaders/mesh/near_field.glsl).
    std::array<NearFieldRingTable, kNearFieldTaps> rings{};
    /// The near field behind: where a lit surface hides x_o from the light (a thin part lit from
    /// behind, an overhang), the light entering it within rho, for a flat surface lit head-on at
    /// a distance d behind x_o and facing away from it. Per node i, at d = behindDepth (i / 32)^2:
    /// the integral of S_d over that disk per unit irradiance (rgb, 1/sr), without Fresnel
    /// factors; zero from behindDepth on.
    std::array<glm::vec3, kNearFieldNodes> behind{};
    float behindDepth = 0.0f;  ///< scene units
    /// A textured material (tabulateTexturedNearFieldShare): per node i, at reduced albedo
    /// 1 - (1 - i / 32)^2, the share of a flat surface's light that enters within rho for that
    /// albedo's material over the widest material's, for which the table is made (a darker
    /// texel's profile is narrower, so more of its light is near). tabulateNearField sets it to 1
    /// (a homogeneous material).
    /// The mean-free-path texture's thinning is not in it.
    std::array<glm::vec3, kNearFieldNodes> texturedShare{};
};

/// The integral of S_d(x_i -> x_o) over the disk of radius `radius` around x_o facing a light at
/// cos theta = `cosIncidence` in (0, 1] to a flat surface, per unit disk area (each disk point
/// stands for the surface point behind it along the light): in the plane's coordinates, x_i =
/// (r cos phi / cos theta, r sin phi). Per channel, without Fresnel factors. At cos theta = 1 it
/// is dipolePlaneIntegral(c, 1, radius); for an unbounded radius, cos theta times
/// dipolePlaneIntegral(c, cos theta).
glm::dvec3 dipoleDiskIntegral(const DipoleConstants& constants, double cosIncidence, double radius);

/// The integral of S_d(x_i -> x_o) over the disk of radius `radius` on a flat surface lit head-on,
/// for x_o a distance `depth` behind the disk's centre and facing away from the surface (the far
/// side of a slab), per unit area, per channel, without Fresnel factors.
glm::dvec3 dipoleDiskIntegralBehind(const DipoleConstants& constants, double depth, double radius);

/// Below this many diffusion lengths per edge (edgeToDiffusionLength) the near field holds
/// almost none of the light and the vertices alone carry it: the same error with and without it
/// in the scale sweep's 20 mm scenes (0.07-0.48 diffusion lengths per edge; Buddha in marble
/// 4.15 % with it, 4.10 % without), so it is left out and its per-pixel work skipped.
inline constexpr double kNearFieldMinEdgeRatio = 0.5;

/// The near field's radius rho (scene units): `nearFieldEdges` edges of `edgeLength`, at most
/// `diskRadius`; 0 (no near field) below kNearFieldMinEdgeRatio diffusion lengths per edge.
float nearFieldRadius(float nearFieldEdges, double edgeLength, double edgeRatio, float diskRadius);

/// The weight of the vertices' near-field difference for edges `edgeFreePaths` reduced mean free
/// paths (1 / sigma_t') long: 1 up to kNearFieldCorrectionFreePaths, then the square of
/// kNearFieldCorrectionFreePaths / edgeFreePaths, the share of a triangle's area within that
/// reach of its corners. Most of the profile's light enters within a few mean free paths, so
/// that is how far a vertex's difference reaches, whatever the diffusion length (measured:
/// docs/near-field.md).
inline constexpr double kNearFieldCorrectionFreePaths = 8.0;
float nearFieldCorrection(double edgeFreePaths);

/// The table for `radius` (scene units, the constants' length unit); radius 0 gives zeros.
/// `edgeLength`: the mesh's edge (scene units), against each channel's diffusion length.
NearFieldTable tabulateNearField(const DipoleConstants& constants, double radius, double edgeLength);

/// Fills table.texturedShare for a textured material whose widest material (g = 0, its reduced
/// extinction the texture's mean free path) is `widest`: the near field of a point is the
/// table's, scaled by what the point gathers (textured_material.glsl) and by this share at its
/// albedo, so that a flat, evenly lit surface of any texel gets its own.
void tabulateTexturedNearFieldShare(NearFieldTable& table, const ScatteringMaterial& widest, double millimetresPerUnit,
                                    ScatteringProfile profile);

/// Sets the uniforms of shaders/mesh/near_field.glsl (radius 0 turns the near field off).
void setNearFieldUniforms(const gl::Program& program, const NearFieldTable& table);

/// The rings' tables as shaders/mesh/near_field.glsl reads them (NEAR_FIELD_CURVATURE) from a
/// storage buffer: per tap (outer, 0, 0, 0), (meanSquareRadius, 0), then per node (h, 0), (q, 0).
std::vector<glm::vec4> packNearFieldRings(const NearFieldTable& table);

}  // namespace sss::detail
