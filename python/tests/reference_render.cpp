// sss_python_reference SCENE OUT.exr: renders one of the scenes of test_render.py's
// "matches C++" tests with the C++ API directly and writes the linear image as OpenEXR, so the
// test can compare the Python module's image with it. The scenes (keep in step with
// python/tests/scenes.py):
//   mesh    procedural UV sphere, subsurface scattering in marble, one directional light
//   volume  procedural blobs (32^3), light-volume scattering with the "bucky" transfer function
//   hybrid  both in one HybridCompositor, the sphere scaled down and moved in front
// Frames follow the Python module's render(): converge the scattering maps, one frame, then
// sub-pixel anti-aliasing over `antialias` frames. Exit code 0 on success, 1 with a message.
#include <sss/sss.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cstdio>
#include <functional>
#include <string>

namespace {

constexpr int kWidth = 96, kHeight = 72, kAntialias = 2;

sss::Camera framedCamera(const std::vector<glm::vec3>& points) {
    sss::Camera camera;
    camera.setYaw(30.0f);
    camera.setPitch(20.0f);
    camera.frameTight(points, float(kWidth) / float(kHeight), 0.04f);
    return camera;
}

std::vector<glm::vec3> corners(const sss::Bounds& b, const glm::mat4& model = glm::mat4(1.0f)) {
    std::vector<glm::vec3> out;
    for (int i = 0; i < 8; ++i)
        out.emplace_back(model * glm::vec4((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y,
                                           (i & 4) ? b.max.z : b.min.z, 1.0f));
    return out;
}

sss::Image picture(sss::Camera camera, const std::function<void(const sss::Camera&, sss::RenderTarget&)>& draw,
                   const std::function<bool()>& converged) {
    sss::RenderTarget target(kWidth, kHeight);
    while (!converged()) draw(camera, target);
    draw(camera, target);
    sss::FrameAccumulator accumulator(kWidth, kHeight);
    for (int i = 0; i < kAntialias; ++i) {
        camera.setSubpixelOffset(sss::FrameAccumulator::subpixelOffset(i, kWidth, kHeight));
        draw(camera, target);
        accumulator.add(target);
    }
    return accumulator.result().readColor();
}

sss::MeshRenderOptions meshOptions() {
    sss::MeshRenderOptions o;
    o.shading = sss::MeshShading::Scattering;
    o.cameras = 4;
    o.samples = 8;
    o.mapResolution = o.lightMapResolution = 128;
    o.accumulationFrames = 2;
    o.millimetresPerUnit = 20.0;
    return o;
}

sss::VolumeRenderOptions volumeOptions() {
    sss::VolumeRenderOptions o;
    o.shading = sss::VolumeShading::Scattering;
    o.lightVolumeScale = 0.5f;
    return o;
}

const sss::Light kLight = sss::DirectionalLight{{-1.0f, -1.0f, -1.0f}, {1.0f, 0.95f, 0.9f}, 2.0f};
const glm::vec4 kBackground = sss::HybridOptions{}.background;

sss::Image render(const std::string& scene) {
    if (scene == "mesh") {
        const sss::Mesh mesh = sss::makeUvSphere(24, 16, 0.5f);
        sss::MeshScatteringRenderer r(meshOptions());
        r.setMesh(mesh);
        r.setScatteringMaterial(sss::materialPreset("marble"));
        r.setLights({kLight});
        return picture(
            framedCamera(mesh.positions()),
            [&](const sss::Camera& c, sss::RenderTarget& t) { t.clear(kBackground); r.render(c, t); },
            [&] { return r.converged(); });
    }
    if (scene == "volume") {
        const sss::Volume volume = sss::makeBlobsVolume(32);
        sss::VolumeScatteringRenderer r(volumeOptions());
        r.setVolume(volume);
        r.setTransferFunction(sss::TransferFunction::preset("bucky"));
        r.setLights({kLight});
        return picture(
            framedCamera(corners(volume.worldBounds())),
            [&](const sss::Camera& c, sss::RenderTarget& t) { t.clear(kBackground); r.render(c, t); },
            [] { return true; });
    }
    if (scene == "hybrid") {
        const sss::Mesh mesh = sss::makeUvSphere(24, 16, 0.5f);
        const sss::Volume volume = sss::makeBlobsVolume(32);
        const glm::mat4 meshModel = glm::translate(glm::mat4(1.0f), glm::vec3(0.2f, 0.0f, 0.6f)) *
                                    glm::scale(glm::mat4(1.0f), glm::vec3(0.4f));
        sss::HybridCompositor c;
        sss::MeshScatteringRenderer& m = c.addMesh(mesh, meshModel, meshOptions());
        m.setScatteringMaterial(sss::materialPreset("skin1"));
        c.addVolume(volume, glm::mat4(1.0f), volumeOptions()).setTransferFunction(sss::TransferFunction::preset("bucky"));
        c.setLights({kLight});
        std::vector<glm::vec3> points;
        for (const glm::vec3& p : mesh.positions()) points.emplace_back(meshModel * glm::vec4(p, 1.0f));
        for (const glm::vec3& p : corners(volume.worldBounds())) points.push_back(p);
        return picture(
            framedCamera(points), [&](const sss::Camera& cam, sss::RenderTarget& t) { c.render(cam, t); },
            [&] { return m.converged(); });
    }
    throw sss::Error(sss::ErrorKind::InvalidArgument, "unknown scene \"" + scene + "\" (mesh, volume, hybrid)");
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: sss_python_reference mesh|volume|hybrid OUT.exr\n");
        return 2;
    }
    try {
        auto context = sss::EglContext::create();
        render(argv[1]).saveExr(argv[2]);
        return 0;
    } catch (const sss::Error& e) {
        std::fprintf(stderr, "sss_python_reference: %s\n", e.what());
        return 1;
    }
}
