#include "sss/mesh_scattering_renderer.h"

#include "light_uniforms.h"
#include "mesh/blinn_phong_pass.h"
#include "mesh/gpu_mesh.h"
#include "sss/error.h"
#include "sss/timing.h"

#include <chrono>
#include <cmath>
#include <optional>
#include <string>

namespace sss {
namespace {

void validate(const MeshRenderOptions& o) {
    if (!(o.gamma > 0.0f) || !std::isfinite(o.gamma))
        throw Error(ErrorKind::InvalidArgument,
                    "MeshRenderOptions::gamma must be a finite value > 0, got " + std::to_string(o.gamma));
}

void validate(const BlinnPhongMaterial& m) {
    auto bad = [](glm::vec3 c) {
        return !(c.x >= 0 && c.y >= 0 && c.z >= 0) || !std::isfinite(c.x + c.y + c.z);
    };
    if (bad(m.diffuse) || bad(m.specular) || bad(m.ambient))
        throw Error(ErrorKind::InvalidArgument, "BlinnPhongMaterial: colours must be finite and >= 0");
    if (!(m.shininess > 0.0f) || !std::isfinite(m.shininess))
        throw Error(ErrorKind::InvalidArgument,
                    "BlinnPhongMaterial::shininess must be finite and > 0, got " + std::to_string(m.shininess));
}

}  // namespace

struct MeshScatteringRenderer::Impl {
    MeshRenderOptions options;
    BlinnPhongMaterial material;
    std::vector<Light> lights{DirectionalLight{}};
    glm::mat4 model{1.0f};
    std::optional<detail::GpuMesh> mesh;
    detail::BlinnPhongPass blinnPhong;
    RenderStats stats;
};

MeshScatteringRenderer::MeshScatteringRenderer(const MeshRenderOptions& options) {
    validate(options);
    m_impl = std::make_unique<Impl>();
    m_impl->options = options;
}

MeshScatteringRenderer::~MeshScatteringRenderer() = default;
MeshScatteringRenderer::MeshScatteringRenderer(MeshScatteringRenderer&&) noexcept = default;
MeshScatteringRenderer& MeshScatteringRenderer::operator=(MeshScatteringRenderer&&) noexcept = default;

void MeshScatteringRenderer::setMesh(const Mesh& mesh, const glm::mat4& model) {
    if (mesh.triangleCount() == 0)
        throw Error(ErrorKind::InvalidArgument, "MeshScatteringRenderer::setMesh: the mesh has no triangles");
    m_impl->mesh = detail::GpuMesh::upload(mesh);
    m_impl->model = model;
}

void MeshScatteringRenderer::setModelTransform(const glm::mat4& model) { m_impl->model = model; }

void MeshScatteringRenderer::setMaterial(const BlinnPhongMaterial& material) {
    validate(material);
    m_impl->material = material;
}

void MeshScatteringRenderer::setLights(std::vector<Light> lights) {
    detail::validateLights(lights, "MeshScatteringRenderer::setLights");
    m_impl->lights = std::move(lights);
}

void MeshScatteringRenderer::setOptions(const MeshRenderOptions& options) {
    validate(options);
    m_impl->options = options;
}

const MeshRenderOptions& MeshScatteringRenderer::options() const { return m_impl->options; }
const RenderStats& MeshScatteringRenderer::stats() const { return m_impl->stats; }

void MeshScatteringRenderer::render(const Camera& camera, RenderTarget& target) {
    if (!m_impl->mesh)
        throw Error(ErrorKind::InvalidArgument, "MeshScatteringRenderer::render: no mesh set (call setMesh first)");
    const auto start = std::chrono::steady_clock::now();
    target.bindForDrawing();
    m_impl->blinnPhong.run(*m_impl->mesh, m_impl->model, m_impl->material, m_impl->lights, camera, target.aspect(),
                           m_impl->options.gamma);
    if (m_impl->options.finishEachPass) finishGpuWork();
    m_impl->stats.record("blinn-phong",
                         std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace sss
