// The option tables (sss/option_table.h): each field's range is what validate() enforces, errors
// name the field, and scene files read and write every field of the tables.
#include <sss/error.h>
#include <sss/light.h>
#include <sss/option_names.h>
#include <sss/option_table.h>
#include <sss/scene.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

using namespace sss;

namespace {

void validateAny(const MeshRenderOptions& o) { validate(o); }
void validateAny(const VolumeRenderOptions& o) { validate(o); }
void validateAny(const HybridOptions& o) { validate(o); }

// Values of T just outside a range.
template <class T>
std::vector<T> outside(const OptionRange& r) {
    std::vector<T> v;
    const auto below = [](double x) {
        if constexpr (std::is_integral_v<T>) return static_cast<T>(x) - 1;
        else return std::nextafter(static_cast<T>(x), -std::numeric_limits<T>::infinity());
    };
    const auto beyond = [](double x) {
        if constexpr (std::is_integral_v<T>) return static_cast<T>(x) + 1;
        else return std::nextafter(static_cast<T>(x), std::numeric_limits<T>::infinity());
    };
    if (std::isfinite(r.min)) v.push_back(r.minExclusive ? static_cast<T>(r.min) : below(r.min));
    if (std::isfinite(r.max)) v.push_back(r.maxExclusive ? static_cast<T>(r.max) : beyond(r.max));
    return v;
}

std::vector<double> insideBounds(const OptionRange& r) {
    std::vector<double> v;
    if (std::isfinite(r.min) && !r.minExclusive) v.push_back(r.min);
    if (std::isfinite(r.max) && !r.maxExclusive) v.push_back(r.max);
    return v;
}

// Every numeric field: the values just outside its range fail naming it, its closed bounds pass,
// and NaN fails for floating-point fields.
template <class Owner>
int checkRanges() {
    int checked = 0;
    forEachOptionField<Owner>([&](const auto& field) {
        using T = std::remove_cvref_t<decltype(Owner{}.*field.member)>;
        if constexpr (std::is_same_v<T, int> || std::is_floating_point_v<T>) {
            constexpr bool integer = std::is_same_v<T, int>;
            INFO(std::string(OptionTable<Owner>::name) << "::" << field.name);
            for (T bad : outside<T>(field.range)) {
                Owner o;
                o.*field.member = bad;
                INFO("value " << bad);
                try {
                    validateAny(o);
                    FAIL("accepted");
                } catch (const Error& e) {
                    CHECK(e.field() == field.name);
                    CHECK(e.reason().rfind("must be ", 0) == 0);
                    CHECK(std::string(e.what()).rfind(std::string(OptionTable<Owner>::name) + "::" +
                                                          std::string(field.name) + " must be ", 0) == 0);
                }
                ++checked;
            }
            for (double good : insideBounds(field.range)) {
                Owner o;
                o.*field.member = static_cast<T>(good);
                if (field.name == "stepSize") continue;  // its own lower limit (0.01) is above the range's
                INFO("value " << good);
                CHECK_NOTHROW(validateAny(o));
            }
            if constexpr (!integer) {
                Owner o;
                o.*field.member = std::numeric_limits<T>::quiet_NaN();
                CHECK_THROWS_AS(validateAny(o), Error);
            }
        }
    });
    return checked;
}

// {"cameras": 8, ...}: every field of Owner's table at its default, as JSON text.
template <class Owner>
std::string defaultsAsJson() {
    std::string text;
    const Owner defaults{};
    forEachOptionField<Owner>([&](const auto& field) {
        const auto& v = defaults.*field.member;
        using T = std::remove_cvref_t<decltype(v)>;
        std::string value;
        if constexpr (std::is_same_v<T, bool>) value = v ? "true" : "false";
        else if constexpr (std::is_enum_v<T>) value = "\"" + std::string(enumName(v)) + "\"";
        else if constexpr (std::is_arithmetic_v<T>) value = std::to_string(v);
        else {
            for (int i = 0; i < T::length(); ++i) value += (i ? ", " : "[") + std::to_string(v[i]);
            value += "]";
        }
        text += (text.empty() ? "{" : ", ") + ("\"" + std::string(field.name) + "\": ") + value;
    });
    return text + "}";
}

}  // namespace

TEST_CASE("option tables: validate() enforces each table range and names the field", "[options]") {
    CHECK(checkRanges<MeshRenderOptions>() >= 15);
    CHECK(checkRanges<VolumeRenderOptions>() >= 15);
    CHECK(checkRanges<HybridOptions>() == 2);
    // The defaults are valid.
    CHECK_NOTHROW(validate(MeshRenderOptions{}));
    CHECK_NOTHROW(validate(VolumeRenderOptions{}));
    CHECK_NOTHROW(validate(HybridOptions{}));
}

TEST_CASE("option tables: ranges read as messages say them", "[options]") {
    CHECK(describeRange(between(1, 32), true) == "in 1..32");
    CHECK(describeRange(atLeast(1), true) == ">= 1");
    CHECK(describeRange(above(0), false) == "finite and > 0");
    CHECK(describeRange(atLeast(0.1), false) == "finite and >= 0.1");
    CHECK(describeRange(between(0, 1, true), false) == "in (0, 1]");
    CHECK(describeRange(between(-1, 1, true, true), false) == "in (-1, 1)");
    CHECK(describeRange({}, false) == "finite");
    CHECK(snakeCase("millimetresPerUnit") == "millimetres_per_unit");
    MeshRenderOptions mesh;
    mesh.environment = {0.0f, -1.0f, 0.0f};
    CHECK_THROWS_WITH(validate(mesh), "MeshRenderOptions::environment must be finite and >= 0 in every channel, got -1");
    VolumeRenderOptions volume;
    volume.stepSize = -1.0f;
    CHECK_THROWS_WITH(validate(volume), "VolumeRenderOptions::stepSize must be finite and > 0 (voxels), got -1");
}


TEST_CASE("option tables: a scene file reads every field of every table, and writes what differs", "[options][scene]") {
    // Every key of the tables is a field the scene reader knows (an unknown one is an error).
    const std::string text = R"({"version": 1, "meshes": [{"source": "procedural:sphere", "options": )" +
                             defaultsAsJson<MeshRenderOptions>() + R"(}], "volumes": [{"source": "procedural:blobs", "options": )" +
                             defaultsAsJson<VolumeRenderOptions>() + R"(}], "options": )" + defaultsAsJson<HybridOptions>() + "}";
    INFO(text);
    CHECK_NOTHROW(parseScene(text, "defaults.json"));
    // Changed fields go out and come back.
    SceneDescription scene;
    SceneMesh mesh;
    mesh.source = "procedural:sphere";
    mesh.options.cameras = 3;
    mesh.options.environment = {0.1f, 0.2f, 0.3f};
    scene.meshes.push_back(mesh);
    SceneVolume volume;
    volume.source = "procedural:blobs";
    volume.options.lightVolumeReach = 2.5f;
    volume.options.lightVolumeFallback = LightVolumeFallback::Fail;
    scene.volumes.push_back(volume);
    scene.options.shadowMapResolution = 512;
    const SceneDescription back = parseScene(sceneToJson(scene), "round-trip");
    REQUIRE(back.meshes.size() == 1);
    REQUIRE(back.volumes.size() == 1);
    CHECK(back.meshes[0].options.cameras == 3);
    CHECK(back.meshes[0].options.environment == glm::vec3(0.1f, 0.2f, 0.3f));
    CHECK(back.volumes[0].options.lightVolumeReach == 2.5f);
    CHECK(back.volumes[0].options.lightVolumeFallback == LightVolumeFallback::Fail);
    CHECK(back.options.shadowMapResolution == 512);
}

TEST_CASE("errors about a field carry it: scene files name the JSON path without parsing messages", "[options]") {
    try {
        validateLight(SpotLight{.coneAngle = 120.0f}, "--light");
        FAIL("accepted");
    } catch (const Error& e) {
        CHECK(e.field() == "coneAngle");
        CHECK(e.reason() == "must be in (0, 90] degrees, got 120");
        CHECK(std::string(e.what()) == "--light: SpotLight::coneAngle must be in (0, 90] degrees, got 120");
    }
    CHECK_THROWS_WITH(parseScene(R"({"version": 1, "meshes": [{"source": "procedural:sphere",
                                   "options": {"samples": 0}}]})", "s.json"),
                      "s.json: meshes[0].options.samples: must be in 1..4096, got 0");
    CHECK_THROWS_WITH(parseScene(R"({"version": 1, "lights": [{"type": "spot", "coneAngle": 95}]})", "s.json"),
                      Catch::Contains("s.json: lights[0].coneAngle: must be in (0, 90] degrees, got 95"));
}
