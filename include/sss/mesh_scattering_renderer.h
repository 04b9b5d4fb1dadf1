#pragma once
/// @file
/// Renders a triangle mesh. Shading modes:
///  - MeshShading::BlinnPhong: Lambert diffuse + Blinn-Phong specular (the thesis's
///    "scattering off" baseline);
///  - MeshShading::Scattering: subsurface scattering with the directional dipole BSSRDF
///    (Frisvad et al. 2014) by the method of Dal Corso et al. 2017, in three passes:
///      1. light buffer: positions and normals of the surface each light sees;
///      2. scattering maps: the object from K cameras on Halton directions, each texel a Monte
///         Carlo sum of N light-buffer samples weighted by the BSSRDF (view-independent);
///      3. combine: each visible point averages the maps that see it, times exit Fresnel.
///    Passes 1-2 rerun only when what they depend on changes (mesh, transform, lights,
///    material, options); while the scene is static, further map frames are accumulated until
///    `accumulationFrames`. A camera change reruns only the combine pass, and so does a change
///    of the lights' colour or intensity alone, alike for every light (one light's, or all
///    scaled by one factor per channel): the combine scales what the maps hold.

#include "sss/api.h"
#include "sss/bssrdf.h"
#include "sss/camera.h"
#include "sss/light.h"
#include "sss/materials.h"
#include "sss/mesh.h"
#include "sss/render_target.h"
#include "sss/stats.h"

#include <glm/mat4x4.hpp>

#include <memory>
#include <vector>

SSS_BEGIN_API

namespace sss {

namespace detail {
struct SSS_INTERNAL MeshRendererAccess;  // hybrid-scene hooks (src/hybrid/shared_lighting.h)
}

enum class MeshShading { BlinnPhong, Scattering };

/// Surface parameters of the Blinn-Phong baseline (linear RGB).
struct BlinnPhongMaterial {
    glm::vec3 diffuse{0.8f, 0.75f, 0.7f};   ///< Lambert albedo (default: warm light grey)
    glm::vec3 specular{0.25f};              ///< specular colour (default: 0.25)
    float shininess = 40.0f;                ///< Blinn-Phong exponent, > 0 (default: 40)
    glm::vec3 ambient{0.05f};               ///< ambient light times albedo (default: 0.05)
};

/// Where the combine pass reads the scattered light (MeshRenderOptions::combine).
enum class MeshCombine {
    /// Every pixel looks its surface point up in the K scattering maps (Dal Corso et al.; 9
    /// depth taps + 1 map tap per layer per pixel, every frame).
    PerPixel,
    /// Cached: the maps are resolved once per vertex after each map update (the vertex-radiosity
    /// pass, which the per-pixel path already runs for points no layer sees), and every frame
    /// interpolates those values: a fixed frame costs about a Blinn-Phong frame. Detail finer
    /// than the mesh's vertices is lost; the exit Fresnel factor, single scattering and the
    /// highlight stay per pixel.
    PerVertex,
    /// Evaluate-once radiosity: no scattering maps. The radiosity is estimated directly at each
    /// vertex (N samples per light and frame, accumulated over accumulationFrames like the maps,
    /// along one low-discrepancy sequence per vertex) instead of in every map texel that sees the
    /// point, and every frame interpolates it as PerVertex does. Regenerating costs about V x N evaluations instead of K x texels x N
    /// (cameras and mapResolution are unused); detail finer than the vertices is lost, so it
    /// needs a mesh whose edges are short against the diffusion length.
    VertexEstimate,
    /// The default: VertexEstimate when the mesh is fine against the material's diffusion length,
    /// PerPixel otherwise. "Fine": the triangles holding 90 % of the surface have edges of at
    /// most 2 diffusion lengths 1 / sigma_tr (in the narrowest-profile channel that reflects a
    /// tenth of the brightest one's light). Scanned meshes at their real size are fine for every
    /// preset; a box of a few large triangles is not. MeshScatteringRenderer::activeCombine()
    /// says which one renders.
    Automatic,
};

struct MeshRenderOptions {
    MeshShading shading = MeshShading::BlinnPhong;
    // Scattering (MeshShading::Scattering):
    /// The subsurface profile (default: Calibrated, the one measured closest to a random walk;
    /// Dipole reproduces the thesis). Calibrated also corrects for the part of the profile the
    /// sampling disk cuts off (exactly for a flat surface lit head-on) and adds single scattering.
    ScatteringProfile profile = ScatteringProfile::Calibrated;
    /// Per-pixel map lookups (the paper's), the cached per-vertex combine, the evaluate-once
    /// vertex estimate without maps, or Automatic: the vertex estimate on fine meshes, per-pixel
    /// maps on coarse ones (default: Automatic).
    MeshCombine combine = MeshCombine::Automatic;
    int cameras = 8;               ///< K scattering maps, 1..32 (default: 8)
    int samples = 24;              ///< N proposals per light per frame, 1..4096 (default: 24)
    int mapResolution = 512;       ///< scattering-map side in texels, 16..8192 (default: 512)
    int lightMapResolution = 512;  ///< light-buffer side in texels, 16..8192 (default: 512)
    /// Scene scale for the material's mm^-1 coefficients, > 0 (default: 1000, metres; see
    /// ScatteringScale).
    double millimetresPerUnit = 1000.0;
    /// Radius of the sampling disk in scene units; 0 chooses 3 / sigma*, where the acceptance
    /// probability exp(-sigma* r) has fallen to 5 %, widened for the calibrated profile until the
    /// disk holds 99.9 % of every channel's plane integral (default: 0).
    float sampleRadius = 0.0f;
    /// Spreads the samples: sigma* = min(sigma_tr) / spread, >= 0.1 (default: 1).
    float spread = 1.0f;
    /// Radius of the vertex estimate's near field, in the mesh's edge lengths (the edge of
    /// MeshScatteringRenderer::edgeToDiffusionLength), >= 0: the light entering that close to a
    /// point, for a locally flat surface lit like the point, is evaluated finer than the vertices
    /// (see nearFieldSpacing); the vertices interpolate only the rest, which varies little across
    /// a triangle. Where a lit surface hides the point (a thin part lit from behind), the light
    /// entering it is evaluated so too.
    /// Keeps the radiosity right on meshes whose triangles are many diffusion lengths wide
    /// (life-size objects); 0 interpolates all of it, and MeshCombine::Automatic then takes the
    /// maps on coarse meshes (docs/near-field.md) (default: 1).
    float nearField = 1.0f;
    /// Where the near field is evaluated: > 0 once per light change, at points this many
    /// light-buffer texels apart on each triangle (at most 8 per edge), which each pixel
    /// interpolates, so a camera move reads it back instead of evaluating it again; 0 at every
    /// pixel of every frame. At 2 the scale sweep's error is that of the per-pixel near field
    /// (docs/near-field.md) (default: 2).
    float nearFieldSpacing = 2.0f;
    /// Map frames accumulated while the scene is static, >= 1 (default: 8).
    int accumulationFrames = 8;
    /// Visibility depth bias of the map lookup, in texels' worth of depth, >= 0 (default: 1.5).
    float depthBias = 1.5f;
    /// Seam shrink of the map lookup, in texels, >= 0 (default: 2, as the thesis).
    float seamShrink = 2.0f;
    /// Specular highlight on top of the scattering, weighted by the surface's Fresnel
    /// reflectance 1 - T, >= 0 (default: 1; 0 turns it off).
    float specular = 1.0f;
    float shininess = 60.0f;       ///< highlight exponent, > 0 (default: 60)
    /// Radiance of a uniform environment around the mesh, linear RGB, each >= 0: the surface
    /// reflects it with the material's total diffuse reflectance (dipoleDiffuseReflectance), so
    /// faces the lights miss are not black. Blinn-Phong shading uses its material's ambient
    /// instead (default: 0, none; sss-render and sss-viewer use 0.05 in a Cornell box).
    glm::vec3 environment{0.0f};
    /// Wait for the GPU after each pass so RenderStats times are GPU times (default: off).
    bool finishEachPass = false;
    /// Write GL timestamps around each pass; RenderStats then holds each pass's GPU time too,
    /// collected without waiting a frame or more later (PassStats::lastGpuMs) (default: off).
    bool gpuPassTimes = false;
};

/// Throws Error(InvalidArgument) if a colour is negative or non-finite or shininess is not > 0.
void validate(const BlinnPhongMaterial& material);

/// Throws Error(InvalidArgument) naming the first field of `options` that breaks its documented
/// range. The renderer checks its options with it; front ends call it before creating a context.
void validate(const MeshRenderOptions& options);

/// Draws one mesh with the scene's lights into a RenderTarget. Needs a current GlContext.
class MeshScatteringRenderer {
public:
    /// Throws Error(InvalidArgument) for invalid options (e.g. cameras 0).
    explicit MeshScatteringRenderer(const MeshRenderOptions& options = {});
    ~MeshScatteringRenderer();
    MeshScatteringRenderer(MeshScatteringRenderer&&) noexcept;
    MeshScatteringRenderer& operator=(MeshScatteringRenderer&&) noexcept;

    /// Uploads the mesh (an empty mesh throws); `model` places it in the world.
    void setMesh(const Mesh& mesh, const glm::mat4& model = glm::mat4(1.0f));
    void setModelTransform(const glm::mat4& model);
    void setMaterial(const BlinnPhongMaterial& material);
    /// The translucent material of the Scattering mode (validated; default: potato).
    void setScatteringMaterial(const ScatteringMaterial& material);
    /// A textured translucent material instead (validated). Its reflectance texture, or else the
    /// mesh's Mesh::baseColour(), gives each point its coefficients; the mesh needs texture
    /// coordinates. setMesh() and render() throw InvalidArgument when it has none, or when there
    /// is no texture. Setting a ScatteringMaterial again returns to a uniform material.
    void setScatteringMaterial(const TexturedScattering& material);
    /// True once the scattering maps hold `accumulationFrames` frames for the current scene.
    bool converged() const;
    /// At most 8 lights; each is validated.
    void setLights(std::vector<Light> lights);
    void setOptions(const MeshRenderOptions& options);
    const MeshRenderOptions& options() const;
    /// The combine that renders: options().combine, with Automatic resolved for the current mesh,
    /// model transform, material and scale (PerPixel before a mesh is set).
    MeshCombine activeCombine() const;
    /// The Automatic test's measure: the mesh's edge length (surface-weighted 90th percentile,
    /// after the model transform) over the material's diffusion length; 0 before a mesh is set.
    double edgeToDiffusionLength() const;

    /// Draws over `target` with depth testing (the caller clears it). Throws if no mesh is set.
    void render(const Camera& camera, RenderTarget& target);

    const RenderStats& stats() const;

private:
    friend struct detail::MeshRendererAccess;
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

}  // namespace sss

SSS_END_API
