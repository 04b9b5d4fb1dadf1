#pragma once
// The command-line options that sss-render, sss-viewer and sss-bench share, declared once on a
// CLI11 app. Each option writes into the library's own option structs, and its default in the
// generated help is read from the struct it is bound to, so every default is written once.
#include "common/scene_inputs.h"

#include <sss/display.h>
#include <sss/mesh_scattering_renderer.h>
#include <sss/option_names.h>
#include <sss/option_table.h>
#include <sss/scene.h>
#include <sss/volume_scattering_renderer.h>

#include <CLI/CLI.hpp>

#include <glm/vec3.hpp>

#include <optional>
#include <string>
#include <utility>

namespace examples {

/// What the command line says about the scene's inputs (meshes and volumes by path, and where
/// to find them).
struct InputArgs {
    std::string mesh;       ///< --mesh PATH|procedural:NAME
    std::string volume;     ///< --volume PATH|procedural:NAME
    std::string scene;      ///< --scene FILE.json (registered by addSceneOption)
    std::string dataDir;    ///< --data-dir DIR
    sss::RawLoadOptions raw;  ///< --dims, --type, --spacing
    std::optional<std::pair<double, double>> tfRange;  ///< --tf-range LO,HI
    std::string tf;         ///< --tf NAME|FILE.json (empty: the front end's default)
};

/// The single light a command line describes.
struct LightArgs {
    sss::DirectionalLight directional{glm::vec3(-1.0f), glm::vec3(1.0f), 1.0f};
    std::optional<glm::vec3> point;  ///< --point-light X,Y,Z
    std::optional<sss::SpotLight> spot;  ///< --spot-light X,Y,Z:DX,DY,DZ:ANGLE[:FALLOFF]
    bool given = false;  ///< a direction or a position was given
    /// The light described: a spot or point light when one was given, else the directional one,
    /// all with --light-color and --light-intensity.
    sss::Light light() const;
};

// Option groups. Each registers its flags on `app` in a help section of its own.
void addInputOptions(CLI::App& app, InputArgs& args);  ///< --mesh --volume --scene --data-dir --dims --type --spacing --tf --tf-range
/// --material --profile --combine --cameras --samples --map-resolution --frames --scale
/// --no-specular --environment (the mesh's scattering options)
/// --material, the option table's mesh fields, --map-resolution, --no-specular and --no-texture.
void addMeshOptions(CLI::App& app, sss::MeshRenderOptions& options, std::string& material, bool& noTexture);
/// --color --shininess (the Blinn-Phong baseline)
void addBaselineOptions(CLI::App& app, sss::BlinnPhongMaterial& material);
/// --step --early-termination --no-jitter --no-skipping --no-gradient-volume --light-volume-scale
/// --light-volume-fallback --anisotropy --volume-model --eye-pass --multiple-scattering --max-bounces
void addVolumeOptions(CLI::App& app, sss::VolumeRenderOptions& options);
void addDisplayOptions(CLI::App& app, sss::DisplayTransform& display);  ///< --exposure --tonemap
void addCameraOptions(CLI::App& app, sss::SceneCamera& camera);  ///< --yaw --pitch --zoom --fov --ortho
void addLightOptions(CLI::App& app, LightArgs& light);  ///< --light-dir --light-color --light-intensity --point-light --spot-light
CLI::Option* addSizeOption(CLI::App& app, int& width, int& height, const char* what);  ///< --size WxH
void addDataDirOption(CLI::App& app, std::string& dataDir);  ///< --data-dir DIR
void addSceneOption(CLI::App& app, std::string& scene, const std::string& help);  ///< --scene FILE.json
void addAntiAliasingOption(CLI::App& app, int& frames, const char* what);  ///< --aa N

/// Adds an option whose value is parsed by `parse` (one of scene_inputs.h's parse functions,
/// which name the option in their messages) into `target`; the help shows `target`'s current
/// value as the default (`defaultText`, when given, replaces it).
template <class T, class Parse>
CLI::Option* addParsed(CLI::App& app, const std::string& name, T& target, Parse parse, const std::string& help,
                       const std::string& typeName, const std::string& defaultText = {});

CLI::Option* addFloat(CLI::App& app, const std::string& name, float& target, const std::string& help,
                      const std::string& typeName = "X");
CLI::Option* addInt(CLI::App& app, const std::string& name, int& target, const std::string& help,
                    const std::string& typeName = "N");
CLI::Option* addVec3(CLI::App& app, const std::string& name, glm::vec3& target, const std::string& help,
                     const std::string& typeName = "X,Y,Z");
/// An enum option spelt as in sss/option_names.h.
template <class Enum>
CLI::Option* addEnum(CLI::App& app, const std::string& name, Enum& target, const std::string& help);

/// Registers every field of an option table (sss/option_table.h) that has a command-line flag:
/// numbers and vectors take a value, enums their names, bools are switches ("--no-jitter" sets
/// false, "--eye-pass" true). Help and default come from the table and `options`.
template <class Owner>
void addTableOptions(CLI::App& app, Owner& options, const std::string& group);

/// Formats a default for help texts ("0.5", "1,1,1").
std::string defaultText(float value);
std::string defaultText(glm::vec3 value);

/// Parses argv with `app`. --help prints the generated help and exits 0; any CLI11 error
/// becomes a UsageError (exit code 2 in runReportingErrors).
void parseCommandLine(CLI::App& app, int argc, char** argv);

/// True if `name` (e.g. "--cameras") was given on the command line.
bool given(const CLI::App& app, const std::string& name);

/// Rejects the options that describe the scene when --scene gives it: "--mesh cannot be
/// combined with --scene".
void rejectWithScene(const CLI::App& app, std::initializer_list<const char*> sceneOptions);

// ---------------------------------------------------------------------------------------------

template <class T, class Parse>
CLI::Option* addParsed(CLI::App& app, const std::string& name, T& target, Parse parse, const std::string& help,
                       const std::string& typeName, const std::string& defaultValue) {
    CLI::Option* option = app.add_option_function<std::string>(
        name, [&target, parse, name](const std::string& text) { target = parse(name, text); }, help);
    option->type_name(typeName);
    if (!defaultValue.empty()) option->default_str(defaultValue);
    return option;
}

template <class Enum>
Enum parseEnum(const std::string& option, const std::string& text) {
    if (const auto value = sss::parseEnumName<Enum>(text)) return *value;
    throw UsageError(option + ": expected " + sss::enumNameList<Enum>() + ", got \"" + text + "\"");
}

/// "a|b|c": the names of `Enum`, for help texts.
template <class Enum>
std::string choices() {
    std::string list;
    for (const auto& entry : sss::enumNames<Enum>()) list += (list.empty() ? "" : "|") + std::string(entry.name);
    return list;
}

template <class Enum>
CLI::Option* addEnum(CLI::App& app, const std::string& name, Enum& target, const std::string& help) {
    return addParsed(app, name, target, parseEnum<Enum>, help, choices<Enum>(), std::string(sss::enumName(target)));
}

template <class Owner>
void addTableOptions(CLI::App& app, Owner& options, const std::string& group) {
    sss::forEachOptionField<Owner>([&](const auto& field) {
        if (field.flag.empty()) return;
        const std::string flag(field.flag), valueName(field.valueName);
        std::string help(field.help);
        auto& member = options.*field.member;
        using T = std::remove_cvref_t<decltype(member)>;
        constexpr bool integer = std::is_same_v<T, int>;
        if constexpr (integer || std::is_floating_point_v<T> || std::is_same_v<T, glm::vec3>) {
            const std::string rule = sss::describeRange(field.range, integer);
            if (rule != "finite" && rule != "an integer") help += ", " + rule;
        }
        CLI::Option* option = nullptr;
        if constexpr (std::is_same_v<T, bool>) {
            const bool value = !flag.starts_with("--no-");
            option = app.add_flag_callback(flag, [&member, value] { member = value; }, help);
        } else if constexpr (std::is_enum_v<T>) {
            option = addEnum(app, flag, member, help);
        } else if constexpr (integer) {
            option = addInt(app, flag, member, help, valueName);
        } else if constexpr (std::is_same_v<T, float>) {
            option = addFloat(app, flag, member, help, valueName);
        } else if constexpr (std::is_same_v<T, double>) {
            option = addParsed(app, flag, member,
                               [](const std::string& name, const std::string& text) { return double(parseFloat(name, text)); },
                               help, valueName, defaultText(float(member)));
        } else {
            option = addVec3(app, flag, member, help, valueName);
        }
        option->group(group);
    });
}

}  // namespace examples
