// Scene files (sss/scene.h): JSON round trips, errors that name the JSON path of the bad field,
// and the assets a scene names.
#include "sss/scene.h"

#include "sss/error.h"
#include "sss/option_names.h"
#include "support/temp_dir.h"
#include "test_helpers.h"

#include <random>
#include <string>

using Catch::Contains;
using namespace sss;

namespace {

/// A scene that sets a field of nearly every kind away from its default.
SceneDescription everyKindOfField() {
    SceneDescription scene;
    SceneMesh bunny;
    bunny.source = "procedural:torus";
    bunny.size = 0.75f;
    bunny.transform = {{0.1f, -0.2f, 0.3f}, {10.0f, 20.0f, 30.0f}, {1.0f, 2.0f, 0.5f}};
    bunny.options.shading = MeshShading::Scattering;
    bunny.options.combine = MeshCombine::PerVertex;
    bunny.options.profile = ScatteringProfile::Dipole;
    bunny.options.cameras = 5;
    bunny.options.millimetresPerUnit = 37.5;
    bunny.options.environment = {0.05f, 0.01f, 0.3f};
    bunny.material = materialPreset("ketchup");
    scene.meshes.push_back(bunny);
    SceneMesh custom;
    custom.source = "procedural:sphere";
    custom.material.name = "my jade";
    custom.material.sigmaA = {0.01, 0.02, 0.03};
    custom.material.sigmaS = {1.1, 1.2, 1.3};
    custom.material.g = 0.25;
    custom.material.eta = 1.45;
    custom.baseline.diffuse = {0.2f, 0.3f, 0.4f};
    custom.baseline.shininess = 12.0f;
    scene.meshes.push_back(custom);

    SceneVolume volume;
    volume.source = "head_16x16x8_int16.raw";
    volume.raw.dims = glm::ivec3(16, 16, 8);
    volume.raw.type = VoxelType::Int16;
    volume.raw.spacing = glm::vec3(1.0f, 1.0f, 2.5f);
    volume.valueWindow = std::pair(-1000.0, 2000.5);
    volume.transferFunction.points = {{0.0f, {0.0f, 0.1f, 0.2f}, 0.0f}, {1.0f, {1.0f, 0.9f, 0.8f}, 0.7f}};
    volume.transform.translate = {0.6f, 0.3f, 0.0f};
    volume.options.shading = VolumeShading::ScatteringGradient;
    volume.options.model = VolumeModel::Physical;
    volume.options.lightVolumeFallback = LightVolumeFallback::Fail;
    volume.options.stepSize = 0.5f;
    volume.options.jitter = false;
    volume.clip.planes = {{{0.1f, 0.0f, -0.2f}, {1.0f, 0.5f, 0.0f}}, {{0.0f, 0.3f, 0.0f}, {0.0f, -1.0f, 0.0f}}};
    volume.clip.cropMin = {0.0f, 0.25f, 0.0f};
    volume.clip.cropMax = {0.75f, 1.0f, 1.0f};
    volume.clip.clippedMatterCastsShadows = true;
    scene.volumes.push_back(volume);
    SceneVolume fromFile;
    fromFile.source = "procedural:bucky";
    fromFile.transferFunction.file = "maps/ember.json";
    fromFile.clip.cropSpace = CropSpace::World;
    fromFile.clip.cropMin = {-2.0f, -0.5f, 0.0f};
    fromFile.clip.cropMax = {0.0f, 3.0f, 1.5f};
    fromFile.clip.planeSpace = CropSpace::Data;
    fromFile.clip.planes = {{{0.5f, 0.0f, 0.0f}, {-1.0f, 0.0f, 0.0f}}};
    scene.volumes.push_back(fromFile);

    scene.lights = {DirectionalLight{{-1.0f, -2.0f, 0.5f}, {1.0f, 0.9f, 0.8f}, 2.0f},
                    PointLight{{0.0f, 2.0f, 1.0f}, {0.5f, 0.5f, 1.0f}, 3.0f},
                    SpotLight{{1.0f, 2.0f, 3.0f}, {0.0f, -1.0f, -0.5f}, 25.0f, 0.3f, {1.0f, 1.0f, 0.5f}, 4.0f}};
    scene.camera = {15.0f, -5.0f, 0.8f, 35.0f, Projection::Orthographic, 0.1f, glm::vec3(0.1f, 0.2f, 0.3f), 2.5f};
    scene.options.cornellBox = true;
    scene.options.background = {0.1f, 0.2f, 0.3f, 1.0f};
    scene.options.shadowMapResolution = 512;
    scene.output.width = 320;
    scene.output.height = 200;
    scene.output.antiAliasing = 8;
    scene.output.display = {1.5f, ToneMap::Filmic, true};
    return scene;
}

/// parseScene(json) must fail with InvalidArgument and a message that starts with `message`.
void requireSceneError(const std::string& json, const std::string& message) {
    INFO(json);
    try {
        parseScene(json, "scene.json");
        FAIL("no error for a bad scene");
    } catch (const Error& e) {
        CHECK(e.kind() == ErrorKind::InvalidArgument);
        CHECK(std::string(e.what()).substr(0, message.size()) == message);
    }
}

}  // namespace

TEST_CASE("a scene survives a JSON round trip field for field", "[scene]") {
    const SceneDescription scene = everyKindOfField();
    const std::string json = sceneToJson(scene);
    const SceneDescription back = parseScene(json, "round-trip.json");
    // The text is a fixed point, and every field came back exactly.
    CHECK(sceneToJson(back) == json);
    REQUIRE(back.meshes.size() == 2);
    CHECK(back.meshes[0].size == scene.meshes[0].size);
    CHECK(back.meshes[0].transform == scene.meshes[0].transform);
    CHECK(back.meshes[0].options.combine == MeshCombine::PerVertex);
    CHECK(back.meshes[0].options.profile == ScatteringProfile::Dipole);
    CHECK(back.meshes[0].options.millimetresPerUnit == 37.5);
    CHECK(back.meshes[0].options.environment == scene.meshes[0].options.environment);
    CHECK(back.meshes[0].material.name == "ketchup");
    CHECK(back.meshes[0].material.sigmaS == materialPreset("ketchup").sigmaS);
    CHECK(back.meshes[1].material.name == "my jade");
    CHECK(back.meshes[1].material.sigmaA == scene.meshes[1].material.sigmaA);
    CHECK(back.meshes[1].material.eta == 1.45);
    CHECK(back.meshes[1].baseline.diffuse == scene.meshes[1].baseline.diffuse);
    REQUIRE(back.volumes.size() == 2);
    CHECK(back.volumes[0].raw.dims == scene.volumes[0].raw.dims);
    CHECK(back.volumes[0].raw.type == VoxelType::Int16);
    CHECK(back.volumes[0].raw.spacing == scene.volumes[0].raw.spacing);
    CHECK(back.volumes[0].valueWindow == scene.volumes[0].valueWindow);
    REQUIRE(back.volumes[0].transferFunction.points.size() == 2);
    CHECK(back.volumes[0].transferFunction.points[1].color == glm::vec3(1.0f, 0.9f, 0.8f));
    CHECK(back.volumes[0].options.shading == VolumeShading::ScatteringGradient);
    CHECK(back.volumes[0].options.stepSize == 0.5f);
    CHECK_FALSE(back.volumes[0].options.jitter);
    CHECK(back.volumes[0].clip == scene.volumes[0].clip);
    CHECK(back.volumes[1].clip == scene.volumes[1].clip);
    CHECK(back.volumes[1].clip.cropSpace == CropSpace::World);
    CHECK(back.volumes[1].clip.planeSpace == CropSpace::Data);
    CHECK(back.volumes[0].clip.planeSpace == CropSpace::World);
    CHECK(back.volumes[1].transferFunction.file == "maps/ember.json");
    CHECK(back.lights == scene.lights);
    CHECK(back.camera == scene.camera);
    CHECK(back.options.background == scene.options.background);
    CHECK(back.options.shadowMapResolution == 512);
    CHECK(back.output.width == 320);
    CHECK(back.output.display.toneMap == ToneMap::Filmic);
    CHECK(back.output.display.exposure == 1.5f);
}

TEST_CASE("scene files keep floats short and leave defaults out", "[scene]") {
    SceneDescription scene;
    scene.meshes.emplace_back().source = "procedural:sphere";
    scene.meshes[0].options.environment = glm::vec3(0.05f);
    const std::string json = sceneToJson(scene);
    CHECK_THAT(json, Contains("\"environment\": [0.05, 0.05, 0.05]"));
    CHECK_THAT(json, !Contains("cameras"));  // at its default
    CHECK(parseScene(json).meshes[0].options.environment == glm::vec3(0.05f));
}

TEST_CASE("bad scene fields are reported with their JSON path", "[scene]") {
    const std::string mesh = R"("meshes": [{"source": "procedural:sphere"}])";
    requireSceneError(R"({"meshes": [{"source": "procedural:sphere"}], "lights": [{"type": "point"}, {"type": "point"},
                         {"type": "directional", "direction": [0, 0, 0]}]})",
                      "scene.json: lights[2].direction: must be finite and non-zero, got (0, 0, 0)");
    requireSceneError("{" + mesh + R"(, "lights": [{"type": "spot", "coneAngle": 120}]})",
                      "scene.json: lights[0].coneAngle: must be in (0, 90] degrees, got 120");
    requireSceneError("{" + mesh + R"(, "lights": [{"type": "area"}]})",
                      "scene.json: lights[0].type: expected directional, point or spot, got \"area\"");
    requireSceneError(R"({"meshes": [{"source": "procedural:sphere", "options": {"cameras": 0}}]})",
                      "scene.json: meshes[0].options.cameras: must be in 1..32, got 0");
    requireSceneError(R"({"meshes": [{"source": "procedural:sphere", "options": {"camras": 4}}]})",
                      "scene.json: meshes[0].options.camras: unknown field");
    requireSceneError(R"({"meshes": [{"source": "procedural:sphere", "options": {"cameras": 4.5}}]})",
                      "scene.json: meshes[0].options.cameras: expected an integer, got 4.5");
    requireSceneError(R"({"meshes": [{"source": "procedural:sphere", "material": "unobtainium"}]})",
                      "scene.json: meshes[0].material: materialPreset: unknown material \"unobtainium\"; known: apple,");
    requireSceneError(R"({"meshes": [{"source": ""}]})", "scene.json: meshes[0].source: a mesh needs a non-empty source");
    requireSceneError(R"({"meshes": [{"source": "procedural:sphere", "transform": {"scale": [1, 0, 1]}}]})",
                      "scene.json: meshes[0].transform.scale: components must be non-zero, got (1, 0, 1)");
    requireSceneError(R"({"volumes": [{"source": "procedural:blobs", "options": {"shading": "xray"}}]})",
                      "scene.json: volumes[0].options.shading: expected emission-absorption, gradient, scattering or "
                      "scattering-gradient, got \"xray\"");
    requireSceneError(R"({"volumes": [{"source": "procedural:blobs", "options": {"stepSize": -1}}]})",
                      "scene.json: volumes[0].options.stepSize: must be finite and > 0 (voxels), got -1");
    requireSceneError(R"({"volumes": [{"source": "procedural:blobs", "clip": {"planes": [{"normal": [0, 0, 0]}]}}]})",
                      "scene.json: volumes[0].clip.planes[0].normal: must be non-zero");
    requireSceneError(R"({"volumes": [{"source": "procedural:blobs", "clip": {"cropMin": [0.5, 0, 0], "cropMax": [0.4, 1, 1]}}]})",
                      "scene.json: volumes[0].clip.cropMin: must be below cropMax on every axis, both in [0, 1] "
                      "(normalised data coordinates), got x from 0.500000 to 0.400000");
    requireSceneError(R"({"volumes": [{"source": "procedural:blobs", "clip": {"planes": [{"point": [0, 0, 0], "normall": [1, 0, 0]}]}}]})",
                      "scene.json: volumes[0].clip.planes[0].normall: unknown field");
    requireSceneError(R"({"volumes": [{"source": "procedural:blobs", "clip": {"cropSpace": "model"}}]})",
                      "scene.json: volumes[0].clip.cropSpace: expected data or world, got \"model\"");
    requireSceneError(R"({"volumes": [{"source": "procedural:blobs", "valueWindow": [5, 1]}]})",
                      "scene.json: volumes[0].valueWindow: LO must be less than HI, got [5,1]");
    requireSceneError(R"({"volumes": [{"source": "procedural:blobs", "transferFunction": {"points": [[0, 1, 1]]}}]})",
                      "scene.json: volumes[0].transferFunction.points[0]: expected [value, r, g, b, opacity], got "
                      "[0,1,1]");
    requireSceneError("{" + mesh + R"(, "camera": {"yaw": "left"}})",
                      "scene.json: camera.yaw: expected a number, got a string");
    requireSceneError("{" + mesh + R"(, "camera": {"fovY": 180}})", "scene.json: camera.fovY: must be in (0, 180) degrees");
    requireSceneError("{" + mesh + R"(, "output": {"width": 0}})", "scene.json: output.width: must be in 1..16384");
    requireSceneError("{" + mesh + R"(, "options": {"shadowMapResolution": 10}})",
                      "scene.json: options.shadowMapResolution: must be in 64..8192, got 10");
    requireSceneError("{" + mesh + R"(, "version": 2})",
                      "scene.json: version: this libsss reads scene files of version 1, got 2");
    requireSceneError(R"({"lights": []})", "scene.json: meshes: the scene holds no mesh and no volume");
    requireSceneError(R"({"meshes": {"source": "procedural:sphere"}})", "scene.json: meshes: expected an array, got an object");
}

TEST_CASE("scene files that are not JSON or missing name the file", "[scene]") {
    test::TempDir dir;
    const auto broken = dir.write("broken.json", "{\"meshes\": [");
    try {
        loadSceneFile(broken);
        FAIL("no error");
    } catch (const Error& e) {
        CHECK(e.kind() == ErrorKind::Parse);
        CHECK_THAT(e.what(), Contains("broken.json: not valid JSON"));
    }
    try {
        loadSceneFile(dir.path() / "missing.json");
        FAIL("no error");
    } catch (const Error& e) {
        CHECK(e.kind() == ErrorKind::Io);
        CHECK_THAT(e.what(), Contains("missing.json: cannot open the scene file"));
    }
}

TEST_CASE("scene assets are found next to the scene file and named in errors", "[scene]") {
    test::TempDir dir;
    // A 2x2x2 raw volume next to the scene, named relative to it.
    dir.write("tiny_2x2x2_uint8.raw", std::string("\x00\x40\x80\xff\x00\x40\x80\xff", 8));
    const auto file = dir.write("scene.json", R"({"meshes": [{"source": "procedural:slab", "size": 2}],
        "volumes": [{"source": "tiny_2x2x2_uint8.raw", "valueWindow": [0, 128], "transferFunction": "bucky"}]})");
    const SceneDescription scene = loadSceneFile(file);
    CHECK(scene.baseDirectory == dir.path());
    const SceneAssets assets = loadSceneAssets(scene);
    REQUIRE(assets.meshes.size() == 1);
    const glm::vec3 size = assets.meshes[0].bounds().size();
    CHECK(std::max({size.x, size.y, size.z}) == Approx(2.0f));  // resized to "size"
    CHECK(glm::length(assets.meshes[0].bounds().center()) < 1e-5f);
    REQUIRE(assets.volumes.size() == 1);
    CHECK(assets.volumes[0].dims() == glm::ivec3(2));
    CHECK(assets.volumes[0].transferFunctionRange() == std::pair(0.0, 128.0));
    CHECK(assets.transferFunctions.size() == 1);

    const auto missing = dir.write("missing.json", R"({"meshes": [{"source": "procedural:slab"}, {"source": "nowhere.ply"}]})");
    try {
        loadSceneAssets(loadSceneFile(missing));
        FAIL("no error");
    } catch (const Error& e) {
        CHECK_THAT(e.what(), Contains("meshes[1]: "));
        CHECK_THAT(e.what(), Contains("nowhere.ply"));
    }
    const auto badTf = dir.write("bad_tf.json", R"({"volumes": [{"source": "procedural:blobs", "transferFunction": "nope"}]})");
    try {
        loadSceneAssets(loadSceneFile(badTf));
        FAIL("no error");
    } catch (const Error& e) {
        CHECK(e.kind() == ErrorKind::InvalidArgument);
        CHECK_THAT(e.what(), Contains("volumes[0].transferFunction: "));
        CHECK_THAT(e.what(), Contains("nope"));
    }
}

TEST_CASE("every option enum name parses back to its value", "[scene]") {
    for (const auto& entry : enumNames<VolumeShading>()) CHECK(parseEnumName<VolumeShading>(entry.name) == entry.value);
    for (const auto& entry : enumNames<MeshCombine>()) CHECK(parseEnumName<MeshCombine>(entry.name) == entry.value);
    CHECK(enumName(MeshShading::Scattering) == "sss");
    CHECK_FALSE(parseEnumName<ToneMap>("aces").has_value());
    CHECK(enumNameList<LightVolumeFallback>() == "reduce or fail");
}

TEST_CASE("damaged scene files raise sss::Error and nothing else", "[scene]") {
    // Deterministic mutations of a full scene's text: byte changes, cuts, repeats, and values
    // replaced by others of every JSON type and edge (huge, negative, non-integer, wrong kind).
    // Anything but sss::Error escaping parseScene (a nlohmann type error, a bad_variant_access,
    // a crash under the sanitizer builds) fails.
    SceneDescription full = everyKindOfField();
    full.lights.push_back(SpotLight{});
    const std::vector<std::string> seeds = {sceneToJson(full), R"({"meshes": [{"source": "procedural:sphere"}]})"};
    const char* const values[] = {"-1", "1e40", "\"x\"", "[]", "{}", "null", "true", "0", "1e-45", "[1,2]",
                                  "[0,0,0]", "18446744073709551615", "-9223372036854775808", "2147483648",
                                  "\"spot\"", "[[0,1,1,1,1]]", "4.5"};
    std::mt19937 rng(20261123);
    int parsed = 0, rejected = 0;
    for (int iteration = 0; iteration < 20000; ++iteration) {
        std::string text = seeds[rng() % seeds.size()];
        for (int edit = 0, edits = 1 + int(rng() % 3); edit < edits && !text.empty(); ++edit) {
            const std::size_t at = rng() % text.size();
            switch (rng() % 5) {
            case 0: text[at] = static_cast<char>(rng() % 128); break;
            case 1: text.erase(at, 1 + rng() % 8); break;
            case 2: text.resize(at); break;
            case 3: text.insert(at, text.substr(rng() % text.size(), 1 + rng() % 20)); break;
            default: {
                const std::size_t colon = text.find(':', at);
                if (colon == std::string::npos) break;
                const std::size_t end = text.find_first_of(",}\n", colon);
                text.replace(colon + 1, end == std::string::npos ? std::string::npos : end - colon - 1,
                             values[rng() % std::size(values)]);
            }
            }
        }
        try {
            parseScene(text, "damaged.json");
            ++parsed;
        } catch (const Error&) {
            ++rejected;
        } catch (const std::exception& e) {
            INFO(text);
            FAIL("not an sss::Error: " << e.what());
        }
    }
    INFO(parsed << " parsed, " << rejected << " rejected");
    CHECK(rejected > 10000);  // most damage is caught...
    CHECK(parsed > 100);      // ...and some leaves a valid scene (e.g. a changed number)
}
