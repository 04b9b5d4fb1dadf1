#pragma once
/// @file
/// Renders a triangle mesh. Shading modes:
///  - MeshShading::BlinnPhong: Lambert diffuse + Blinn-Phong specular (the thesis's
///    "scattering off" baseline).
/// Directional-dipole subsurface scattering (Dal Corso et al. 2017) arrives as a further mode.

#include "sss/camera.h"
#include "sss/light.h"
#include "sss/mesh.h"
#include "sss/render_target.h"
#include "sss/stats.h"

#include <glm/mat4x4.hpp>

#include <memory>
#include <vector>

namespace sss {

enum class MeshShading { BlinnPhong };

/// Surface parameters of the Blinn-Phong baseline (linear RGB).
struct BlinnPhongMaterial {
    glm::vec3 diffuse{0.8f, 0.75f, 0.7f};   ///< Lambert albedo (default: warm light grey)
    glm::vec3 specular{0.25f};              ///< specular colour (default: 0.25)
    float shininess = 40.0f;                ///< Blinn-Phong exponent, > 0 (default: 40)
    glm::vec3 ambient{0.05f};               ///< ambient light times albedo (default: 0.05)
};

struct MeshRenderOptions {
    MeshShading shading = MeshShading::BlinnPhong;
    /// Output is encoded as colour^(1/gamma); 1 writes linear values (default: 2.2, as the thesis).
    float gamma = 2.2f;
    /// Wait for the GPU after each pass so RenderStats times are GPU times (default: off).
    bool finishEachPass = false;
};

/// Draws one mesh with the scene's lights into a RenderTarget. Needs a current GlContext.
class MeshScatteringRenderer {
public:
    /// Throws Error(InvalidArgument) for invalid options (e.g. gamma <= 0).
    explicit MeshScatteringRenderer(const MeshRenderOptions& options = {});
    ~MeshScatteringRenderer();
    MeshScatteringRenderer(MeshScatteringRenderer&&) noexcept;
    MeshScatteringRenderer& operator=(MeshScatteringRenderer&&) noexcept;

    /// Uploads the mesh (an empty mesh throws); `model` places it in the world.
    void setMesh(const Mesh& mesh, const glm::mat4& model = glm::mat4(1.0f));
    void setModelTransform(const glm::mat4& model);
    void setMaterial(const BlinnPhongMaterial& material);
    /// At most 8 lights; each is validated.
    void setLights(std::vector<Light> lights);
    void setOptions(const MeshRenderOptions& options);
    const MeshRenderOptions& options() const;

    /// Draws over `target` with depth testing (the caller clears it). Throws if no mesh is set.
    void render(const Camera& camera, RenderTarget& target);

    const RenderStats& stats() const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

}  // namespace sss
