// Mesh subsurface scattering (Dal Corso et al. 2017 with the directional dipole): golden images,
// translucency, caching of the view-independent passes, and parameter validation.
#include "support/gl_test.h"
#include "support/scenes.h"
#include "support/golden.h"

#include <catch2/catch.hpp>
#include <sss/error.h>
#include <sss/image_compare.h>
#include <sss/materials.h>
#include <sss/mesh_scattering_renderer.h>
#include <sss/option_names.h>
#include <sss/procedural.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>

using namespace sss;
using sss::test::orbitCamera;

namespace {

constexpr int kWidth = 256, kHeight = 144;
const glm::vec4 kBackground{0.1f, 0.1f, 0.12f, 1.0f};

// Small maps and few frames keep llvmpipe fast; the procedural meshes are 1 unit in radius, so
// 20 mm per unit makes them 4 cm objects, where potato and cream are visibly translucent.
MeshRenderOptions testOptions(int cameras = 8) {
    MeshRenderOptions o;
    o.shading = MeshShading::Scattering;
    o.cameras = cameras;
    o.samples = 16;
    o.mapResolution = 256;
    o.lightMapResolution = 256;
    o.accumulationFrames = 4;
    o.millimetresPerUnit = 20.0;
    return o;
}

// Renders until the maps have converged and returns the last frame.
Image renderConverged(MeshScatteringRenderer& renderer, const Camera& camera, int width = kWidth,
                      int height = kHeight) {
    RenderTarget target(width, height);
    do {
        target.clear(kBackground);
        renderer.render(camera, target);
    } while (!renderer.converged());
    return target.readColor();
}

// The cached-combine scene: a marble torus tipped 60 degrees, lit from above, specular off (it is
// view-dependent in both combines: they are compared on the radiosity alone).
struct MarbleTorusScene {
    Mesh torus;
    Camera camera = orbitCamera(torus.bounds(), -25.0f, 10.0f);

    explicit MarbleTorusScene(int segments, int rings) : torus(makeTorus(0.7f, 0.3f, segments, rings)) {}

    void setUp(MeshScatteringRenderer& renderer) const {
        renderer.setMesh(torus, glm::rotate(glm::mat4(1.0f), glm::radians(60.0f), glm::vec3(1, 0, 0)));
        renderer.setScatteringMaterial(materialPreset("marble"));
        renderer.setLights({DirectionalLight{.direction = {0.4f, -1.0f, -0.5f}}});
    }
};

}  // namespace

TEST_CASE("cream sphere lit from the front matches the golden image", "[gl][mesh][scattering][golden]") {
    test::GlTestScope gl;
    const Mesh sphere = makeUvSphere(48, 32);
    MeshScatteringRenderer renderer(testOptions());
    renderer.setMesh(sphere);
    renderer.setScatteringMaterial(materialPreset("cream"));
    renderer.setLights({DirectionalLight{.direction = {-0.3f, -0.3f, -1.0f}}});
    const Image image = renderConverged(renderer, orbitCamera(sphere.bounds(), 15.0f, 10.0f));
    test::requireMatchesGolden(image, "mesh_sss_cream_sphere");
    gl.requireNoErrors();
}

TEST_CASE("a thin potato slab lit from behind glows through (translucency)", "[gl][mesh][scattering][golden]") {
    test::GlTestScope gl;
    // 1.6 x 1.0 units and 0.2 thick: 4 mm of potato at 20 mm per unit, lit only from behind.
    const Mesh slab = makeSlab({1.6f, 1.0f, 0.2f});
    MeshScatteringRenderer renderer(testOptions());
    renderer.setMesh(slab);
    renderer.setScatteringMaterial(materialPreset("potato"));
    renderer.setLights({DirectionalLight{.direction = {0.0f, 0.0f, 1.0f}}});  // travels towards the viewer
    Camera camera;
    camera.setDistance(2.5f);  // looking at the front face, which the light never reaches directly
    const Image image = renderConverged(renderer, camera);
    const glm::vec4 centre = image.at(kWidth / 2, kHeight / 2);
    INFO("front-face centre " << centre.r << " " << centre.g << " " << centre.b);
    CHECK(centre.r > 0.03f);  // light came through (linear; 0.2 when this test wrote gamma 2.2)
    // Potato absorbs blue most (sigma_a 0.0024 / 0.0090 / 0.12 per mm): red leads.
    CHECK(centre.r > centre.g);
    CHECK(centre.g > centre.b);
    test::requireMatchesGolden(image, "mesh_sss_potato_slab_backlit");

    // The same slab 30 times thicker lets (next to) nothing through.
    MeshScatteringRenderer thick(testOptions());
    thick.setMesh(makeSlab({1.6f, 1.0f, 6.0f}));
    thick.setScatteringMaterial(materialPreset("potato"));
    thick.setLights({DirectionalLight{.direction = {0.0f, 0.0f, 1.0f}}});
    Camera far;
    far.setDistance(6.0f);
    const glm::vec4 dark = renderConverged(thick, far).at(kWidth / 2, kHeight / 2);
    INFO("thick slab front centre " << dark.r);
    CHECK(dark.r < 0.25f * centre.r);
    gl.requireNoErrors();
}

TEST_CASE("torus with concavities at K = 4 and K = 16 matches the golden images", "[gl][mesh][scattering][golden]") {
    test::GlTestScope gl;
    const Mesh torus = makeTorus(0.7f, 0.3f, 64, 32);
    const glm::mat4 tilt = glm::rotate(glm::mat4(1.0f), glm::radians(60.0f), glm::vec3(1, 0, 0));
    for (int cameras : {4, 16}) {
        MeshRenderOptions options = testOptions(cameras);
        options.combine = MeshCombine::PerPixel;  // the maps' K is what this golden pins
        MeshScatteringRenderer renderer(options);
        renderer.setMesh(torus, tilt);
        renderer.setScatteringMaterial(materialPreset("marble"));
        renderer.setLights({DirectionalLight{.direction = {0.4f, -1.0f, -0.5f}}});
        const Image image = renderConverged(renderer, orbitCamera(torus.bounds(), -25.0f, 10.0f));
        test::requireMatchesGolden(image, "mesh_sss_marble_torus_k" + std::to_string(cameras));
    }
    gl.requireNoErrors();
}

TEST_CASE("the cached per-vertex combine follows the per-pixel combine of the same maps, closer on finer meshes",
          "[gl][mesh][scattering][caching]") {
    test::GlTestScope gl;
    // The same maps resolved once per vertex (MeshCombine::PerVertex) instead of per pixel: switching
    // reuses the maps and the vertices' radiosity (the per-pixel combine already keeps it for
    // points no layer sees). The images differ by what interpolation between vertices loses and
    // by the maps' Monte Carlo noise, which a pixel and a vertex read at different texels; the
    // first shrinks with the triangles, the second does not. Measured (llvmpipe, 256 x 144, marble,
    // K 16, 4 frames of N 16, specular off): torus 32 x 16 0.0361, 64 x 32 0.0309, 128 x 64 0.0264;
    // bounds 1.25x those.
    struct Case {
        int segments, rings;
        double bound;
    };
    double previous = 1.0;
    for (const Case c : {Case{32, 16, 0.045}, Case{64, 32, 0.039}, Case{128, 64, 0.033}}) {
        const MarbleTorusScene scene(c.segments, c.rings);
        const Camera& camera = scene.camera;
        MeshRenderOptions options = testOptions(16);
        options.combine = MeshCombine::PerPixel;
        options.specular = 0.0f;
        MeshScatteringRenderer renderer(options);
        scene.setUp(renderer);
        const Image perPixel = renderConverged(renderer, camera);
        const std::uint64_t maps = renderer.stats().runs("scattering-maps");
        const std::uint64_t resolves = renderer.stats().runs("vertex-radiosity");
        options.combine = MeshCombine::PerVertex;
        renderer.setOptions(options);
        const Image perVertex = renderConverged(renderer, camera);
        CHECK(renderer.stats().runs("scattering-maps") == maps);  // the maps were reused
        CHECK(renderer.stats().runs("vertex-radiosity") == resolves);
        const double difference = computeErrorMetrics(perVertex, perPixel).relRmse;
        std::printf("[cached combine] torus %d x %d: per-vertex against per-pixel relRMSE %.4f\n", c.segments, c.rings,
                    difference);
        CHECK(difference < c.bound);
        CHECK(difference < previous);
        previous = difference;
    }
    gl.requireNoErrors();
}

TEST_CASE("with converged maps on a fine mesh, the cached combine is within 0.5 % of the per-pixel one",
          "[gl][mesh][scattering][caching]") {
    test::GlTestScope gl;
    // The difference above is mostly the maps' Monte Carlo noise: it halves with every 4x
    // frames. Measured (llvmpipe, the same scene, K 16, N 16 per frame): torus 128 x 64 0.0264 /
    // 0.0135 / 0.0069 and 256 x 128 0.0166 / 0.0084 / 0.0043 after 4 / 16 / 64 frames (16 frames
    // of N 64: 0.0043 too). So with the maps converged (1024 samples per texel here) and vertices
    // a few texels apart, the per-vertex image is within the 0.5 % of the per-pixel one that
    // issue 11 asked for. Bound: 0.5 %, 1.16x the measured 0.43 % (the noise is seeded, so the
    // same on every run of one driver).
    const MarbleTorusScene scene(256, 128);
    const Camera& camera = scene.camera;
    MeshRenderOptions options = testOptions(16);
    options.accumulationFrames = 16;
    options.samples = 64;
    options.combine = MeshCombine::PerPixel;
    options.specular = 0.0f;
    MeshScatteringRenderer renderer(options);
    scene.setUp(renderer);
    const Image perPixel = renderConverged(renderer, camera);
    options.combine = MeshCombine::PerVertex;
    renderer.setOptions(options);
    const double difference = computeErrorMetrics(renderConverged(renderer, camera), perPixel).relRmse;
    std::printf("[cached combine] converged maps, torus 256 x 128: per-vertex against per-pixel relRMSE %.4f\n",
                difference);
    CHECK(difference < 0.005);
    gl.requireNoErrors();
}

TEST_CASE("a camera-only change reruns only the combine pass", "[gl][mesh][scattering][caching]") {
    test::GlTestScope gl;
    // Both ways of estimating the radiosity cache alike (explicit: Automatic would switch between
    // them when the material changes).
    const MeshCombine combine = GENERATE(MeshCombine::PerPixel, MeshCombine::VertexEstimate);
    const char* radiosity = combine == MeshCombine::PerPixel ? "scattering-maps" : "vertex-estimate";
    INFO("combine " << enumName(combine));
    MeshRenderOptions options = testOptions();
    options.combine = combine;
    const Mesh sphere = makeUvSphere();
    MeshScatteringRenderer renderer(options);
    renderer.setMesh(sphere);
    Camera camera = orbitCamera(sphere.bounds(), 0, 0);
    RenderTarget target(64, 36);
    auto frame = [&] {
        target.clear(kBackground);
        renderer.render(camera, target);
    };
    auto runs = [&](const char* pass) { return renderer.stats().runs(pass); };
    do frame();
    while (!renderer.converged());
    CHECK(runs("light-buffer") == 1);
    CHECK(runs(radiosity) == 4);  // accumulationFrames
    CHECK(runs("profile") == 1);
    for (int i = 0; i < 3; ++i) {
        camera.orbit(20.0f, 5.0f);
        frame();
    }
    CHECK(runs("light-buffer") == 1);
    CHECK(runs(radiosity) == 4);
    CHECK(runs("combine") == 7);
    SECTION("a material change reruns the maps, not the light buffer") {
        renderer.setScatteringMaterial(materialPreset("ketchup"));
        frame();
        CHECK(runs("light-buffer") == 1);
        CHECK(runs(radiosity) == 5);
        CHECK(runs("profile") == 2);
    }
    SECTION("a light change reruns both, not the profile's derivation") {
        renderer.setLights({DirectionalLight{.direction = {1, 0, 0}}});
        frame();
        CHECK(runs("light-buffer") == 2);
        CHECK(runs(radiosity) == 5);
        CHECK(runs("profile") == 1);
        // The same image as a renderer that starts with that light.
        const Image changed = renderConverged(renderer, camera, 64, 36);
        MeshScatteringRenderer fresh(options);
        fresh.setMesh(sphere);
        fresh.setLights({DirectionalLight{.direction = {1, 0, 0}}});
        CHECK(computeErrorMetrics(changed, renderConverged(fresh, camera, 64, 36)).maxAbsError == 0.0f);
    }
    SECTION("a change of the light's colour or intensity alone reruns only the combine pass") {
        // The radiosity and the near field's points are linear in the light: the combine scales
        // them, and the picture is a fresh renderer's with that light.
        const DirectionalLight orange{.color = {1.0f, 0.6f, 0.3f}, .intensity = 2.5f};
        renderer.setLights({orange});
        const Image changed = renderConverged(renderer, camera, 64, 36);
        CHECK(runs("light-buffer") == 1);
        CHECK(runs(radiosity) == 4);
        MeshScatteringRenderer fresh(options);
        fresh.setMesh(sphere);
        fresh.setLights({orange});
        const double error = computeErrorMetrics(changed, renderConverged(fresh, camera, 64, 36)).relRmse;
        INFO("against a fresh renderer: relRMSE " << error);
        CHECK(error < 1e-3);  // measured on llvmpipe: below 1e-4 (the near field's points are half floats)
        // A channel that was dark in the light the maps hold, now lit: accumulated again.
        renderer.setLights({DirectionalLight{.direction = {1, 0, 0}, .color = {1.0f, 0.0f, 0.0f}}});
        frame();
        CHECK(runs(radiosity) == 5);
        renderer.setLights({DirectionalLight{.direction = {1, 0, 0}}});
        frame();
        CHECK(runs(radiosity) == 6);
    }
    SECTION("an object transform change reruns both and the profile (its disk follows the size)") {
        renderer.setModelTransform(glm::translate(glm::mat4(1.0f), {0.1f, 0, 0}));
        frame();
        CHECK(runs("light-buffer") == 2);
        CHECK(runs(radiosity) == 5);
        CHECK(runs("profile") == 2);
    }
    SECTION("changing only the specular term reruns nothing but the combine pass") {
        MeshRenderOptions o = renderer.options();
        o.specular = 0.0f;
        renderer.setOptions(o);
        frame();
        CHECK(runs("light-buffer") == 1);
        CHECK(runs(radiosity) == 4);
    }
    SECTION("switching scattering off and on again keeps the maps") {
        MeshRenderOptions o = renderer.options();
        o.shading = MeshShading::BlinnPhong;
        renderer.setOptions(o);
        frame();
        o.shading = MeshShading::Scattering;
        renderer.setOptions(o);
        frame();
        CHECK(runs("blinn-phong") == 1);
        CHECK(runs(radiosity) == 4);
    }
    gl.requireNoErrors();
}

TEST_CASE("bad scattering parameters give clear errors", "[gl][mesh][scattering][errors]") {
    test::GlTestScope gl;
    MeshScatteringRenderer renderer;
    ScatteringMaterial negative = materialPreset("potato");
    negative.sigmaA.x = -0.1;
    CHECK_THROWS_WITH(renderer.setScatteringMaterial(negative), Catch::Contains("sigmaA"));
    ScatteringMaterial badEta = materialPreset("potato");
    badEta.eta = 0.0;
    CHECK_THROWS_WITH(renderer.setScatteringMaterial(badEta), Catch::Contains("eta"));
    MeshRenderOptions o;
    o.cameras = 0;
    CHECK_THROWS_WITH(MeshScatteringRenderer(o), Catch::Contains("cameras"));
    o = {};
    o.samples = 0;
    CHECK_THROWS_WITH(MeshScatteringRenderer(o), Catch::Contains("samples"));
    o = {};
    o.millimetresPerUnit = -1.0;
    CHECK_THROWS_WITH(MeshScatteringRenderer(o), Catch::Contains("millimetresPerUnit"));
    CHECK_THROWS_WITH(Mesh::fromArrays({}, {}), Catch::Contains("no triangles"));
    CHECK_THROWS_WITH(materialPreset("unobtainium"), Catch::Contains("unobtainium"));
    gl.requireNoErrors();
}

TEST_CASE("a point light lights the translucent mesh (no GL errors, finite, non-empty)", "[gl][mesh][scattering]") {
    test::GlTestScope gl;
    MeshScatteringRenderer renderer(testOptions(4));
    renderer.setMesh(makeTorus());
    renderer.setLights({PointLight{.position = {0.0f, 3.0f, 1.0f}, .intensity = 8.0f}});
    Camera camera;
    camera.setDistance(4.0f);
    camera.setPitch(30.0f);
    const Image image = renderConverged(renderer, camera, 64, 48);
    int lit = 0;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            const glm::vec4 p = image.at(x, y);
            REQUIRE(std::isfinite(p.r + p.g + p.b));
            lit += p.r > kBackground.r + 0.05f ? 1 : 0;
        }
    CHECK(lit > 100);
    gl.requireNoErrors();
}

TEST_CASE("points no scattering map sees take the radiosity of the surface around them", "[gl][mesh][scattering]") {
    test::GlTestScope gl;
    // One map sees one side of the sphere; the viewer looks at the other side, lit from the
    // viewer. Everything the viewer sees beyond the map's horizon comes from the vertex pass's
    // neighbour fill, which must look like the K = 16 image there, not dark or patchy.
    const Mesh sphere = makeUvSphere(48, 32);
    auto render = [&](int cameras) {
        MeshScatteringRenderer renderer(testOptions(cameras));
        renderer.setMesh(sphere);
        renderer.setScatteringMaterial(materialPreset("marble"));
        renderer.setLights({DirectionalLight{.direction = {0.3f, 0.2f, 1.0f}}});
        return renderConverged(renderer, orbitCamera(sphere.bounds(), 180.0f, 0.0f));
    };
    const Image one = render(1), many = render(16);
    const ErrorMetrics error = computeErrorMetrics(one, many);
    INFO("K = 1 against K = 16: relRMSE " << error.relRmse << ", specks " << error.speckShare);
    // Measured on llvmpipe: relRMSE 0.18, no specks (one map cannot resolve what 16 do; the
    // fill is smooth). Leaving the unseen points black gives 0.54 and 15 % specks.
    CHECK(error.speckShare < 0.01);
    CHECK(error.relRmse < 0.25);
    gl.requireNoErrors();
}
