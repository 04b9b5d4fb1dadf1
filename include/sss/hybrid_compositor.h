#pragma once
/// @file
/// A hybrid scene: any number of translucent or opaque meshes and scattering volumes, rendered
/// together with correct depth, optionally inside a Cornell box.
///
/// Compositing: meshes (and the box) are drawn first with depth; volumes are then ray cast back
/// to front, each stopping its rays at the depth of what is already drawn. So a mesh in front of
/// a volume hides it, a volume in front of a mesh composites over it, and a mesh inside a volume
/// cuts its rays at the surface. Volumes whose boxes overlap each other along a view ray are
/// composited box by box (ordered by their centres' distance), not sample by sample.
///
/// Shadows between every pair of objects (each kind can be turned off, see HybridOptions):
///  - meshes shadow the volumes: a ray-cast sample that a mesh hides from a light (shadow map of
///    the meshes from that light) gets none of its light. The light volume itself stays the
///    volume's own, so moving a mesh does not recompute it;
///  - meshes shadow meshes and the Cornell box through the same maps (3x3 percentage-closer
///    filtering for Blinn-Phong surfaces and the box; scattering meshes test each point where
///    light enters, so their subsurface transport blurs the shadow's edge). A mesh is shadowed by
///    the other meshes only: a scattering mesh's light buffer already holds its self-shadowing,
///    and a Blinn-Phong mesh's n.l its attached shadows (its cast self-shadows are not drawn);
///  - every scattering volume tints and dims the light reaching meshes and the box: a mesh
///    point's light from each light is multiplied by the light-volume value (c, l) where that
///    light's ray leaves the volume box towards the point (or at the point, inside the box); a
///    volume in VolumeModel::Physical (grey extinction) has c = 1 and only dims it. Up to
///    16 volume-light pairs do so (16 volumes with one light, 2 with eight); a warning names
///    the volumes left out. Light scattered by a volume does not illuminate meshes.
/// Every renderer keeps its own caches: a camera move reruns neither the scattering maps nor the
/// light volumes; moving a mesh redraws the meshes' shadow maps and the mesh's own scattering
/// passes; changing a light or the volume reruns both renderers' passes.

#include "sss/api.h"
#include "sss/camera.h"
#include "sss/light.h"
#include "sss/mesh.h"
#include "sss/mesh_scattering_renderer.h"
#include "sss/render_target.h"
#include "sss/stats.h"
#include "sss/volume.h"
#include "sss/volume_scattering_renderer.h"

#include <glm/mat4x4.hpp>

#include <memory>
#include <vector>

SSS_BEGIN_API

namespace sss {

struct HybridOptions {
    /// Clear colour, linear like everything in the target (default: the dark grey-blue whose
    /// display value is sRGB (0.1, 0.1, 0.12)).
    glm::vec4 background{0.010f, 0.010f, 0.0137f, 1.0f};
    bool cornellBox = false;          ///< surround the content with a Cornell box (default: off)
    bool meshShadowsInVolumes = true;   ///< meshes shadow the volumes' light volumes (default: on)
    bool meshShadowsOnMeshes = true;    ///< meshes shadow meshes and the Cornell box (default: on)
    bool volumeShadowsOnMeshes = true;  ///< volumes tint and dim the light reaching meshes (default: on)
    int shadowMapResolution = 1024;   ///< the meshes' shadow maps, texels per side, 64..8192 (default: 1024)
    /// Clear the target to `background` (depth to far) before drawing (default: on). Off: draw
    /// over what the target holds, its depth included, as in a HostTarget frame.
    bool clearTarget = true;
};

/// Throws Error(InvalidArgument) naming the bad field of `options`.
void validate(const HybridOptions& options);

class HybridCompositor {
public:
    explicit HybridCompositor(const HybridOptions& options = {});
    ~HybridCompositor();
    HybridCompositor(HybridCompositor&&) noexcept;
    HybridCompositor& operator=(HybridCompositor&&) noexcept;

    /// Adds a mesh; the returned renderer (owned by the compositor, valid until clear()) sets its
    /// material and options. Its lights are the compositor's.
    MeshScatteringRenderer& addMesh(const Mesh& mesh, const glm::mat4& model = glm::mat4(1.0f),
                                    const MeshRenderOptions& options = {});
    /// Adds a volume; the returned renderer sets its transfer function and options.
    VolumeScatteringRenderer& addVolume(const Volume& volume, const glm::mat4& model = glm::mat4(1.0f),
                                        const VolumeRenderOptions& options = {});
    std::size_t meshCount() const;
    std::size_t volumeCount() const;
    MeshScatteringRenderer& mesh(std::size_t index);
    VolumeScatteringRenderer& volume(std::size_t index);
    /// Moves mesh `index` (use this rather than the renderer's own setModelTransform, so the
    /// shadows it casts into volumes follow).
    void setMeshTransform(std::size_t index, const glm::mat4& model);
    void clear();

    /// The scene's lights, given to every mesh, volume and the Cornell box (at most 8).
    void setLights(std::vector<Light> lights);
    const std::vector<Light>& lights() const;
    void setOptions(const HybridOptions& options);
    const HybridOptions& options() const;

    /// World bounds of the content (without the Cornell box); empty if nothing was added.
    Bounds bounds() const;

    /// Clears the target to the background and draws the whole scene.
    void render(const Camera& camera, RenderTarget& target);

    /// Passes of the compositor itself ("mesh-shadow-maps", "cornell-box"); each renderer keeps
    /// its own statistics.
    const RenderStats& stats() const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

}  // namespace sss

SSS_END_API
