#include "common/cli_options.h"

#include <sss/error.h>
#include <sss/image.h>
#include <sss/option_names.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>

namespace examples {
namespace {

/// The description holds the whole usage text ("usage: sss-render [--mesh PATH] ..."), so the
/// generated "Usage:" line is left out; wide option columns keep the help readable.
class Formatter : public CLI::Formatter {
public:
    std::string make_usage(const CLI::App*, std::string) const override { return {}; }

    /// "  --cameras K          scattering maps K, 1..32 (default: 8)", the description wrapped
    /// at kWidth columns under its own column.
    std::string make_option(const CLI::Option* option, bool positional) const override {
        std::string name = "  " + make_option_name(option, positional);
        if (option->get_type_size() != 0 && !option->get_type_name().empty()) name += " " + option->get_type_name();
        std::string text = option->get_description();
        if (!option->get_default_str().empty()) text += " (default: " + option->get_default_str() + ")";
        std::string out = name;
        std::size_t column = name.size();
        if (column + 2 > kDescriptionColumn) {
            out += "\n";
            column = 0;
        }
        std::istringstream words(text);
        std::string word;
        bool lineStart = true;
        while (words >> word) {
            if (!lineStart && column + 1 + word.size() > kWidth) {
                out += "\n";
                column = 0;
                lineStart = true;
            }
            if (lineStart) {
                out += std::string(kDescriptionColumn - column, ' ');
                column = kDescriptionColumn;
            } else {
                out += ' ';
                ++column;
            }
            out += word;
            column += word.size();
            lineStart = false;
        }
        return out + "\n";
    }

private:
    static constexpr std::size_t kDescriptionColumn = 30, kWidth = 100;
};

sss::SpotLight parseSpotLight(const std::string& option, const std::string& text) {
    const auto parts = split(text, ':');
    if (parts.size() != 3 && parts.size() != 4)
        throw UsageError(option + ": expected X,Y,Z:DX,DY,DZ:ANGLE[:FALLOFF], got \"" + text + "\"");
    sss::SpotLight spot;
    spot.position = parseVec3(option, parts[0]);
    spot.direction = parseVec3(option, parts[1]);
    spot.coneAngle = parseFloat(option, parts[2]);
    if (parts.size() == 4) spot.falloff = parseFloat(option, parts[3]);
    return spot;
}

}  // namespace

std::string defaultText(float value) {
    std::ostringstream s;
    s << value;
    return s.str();
}

std::string defaultText(glm::vec3 value) {
    return defaultText(value.x) + "," + defaultText(value.y) + "," + defaultText(value.z);
}

CLI::Option* addFloat(CLI::App& app, const std::string& name, float& target, const std::string& help,
                      const std::string& typeName) {
    return addParsed(app, name, target, parseFloat, help, typeName, defaultText(target));
}

CLI::Option* addInt(CLI::App& app, const std::string& name, int& target, const std::string& help,
                    const std::string& typeName) {
    return addParsed(app, name, target, parseInt, help, typeName, std::to_string(target));
}

CLI::Option* addVec3(CLI::App& app, const std::string& name, glm::vec3& target, const std::string& help,
                     const std::string& typeName) {
    return addParsed(app, name, target, parseVec3, help, typeName, defaultText(target));
}

sss::Light LightArgs::light() const {
    if (spot) {
        sss::SpotLight s = *spot;
        s.color = directional.color;
        s.intensity = directional.intensity;
        return s;
    }
    if (point) return sss::PointLight{*point, directional.color, directional.intensity};
    return directional;
}

void addInputOptions(CLI::App& app, InputArgs& args) {
    const std::string group = "input";
    app.add_option("--mesh", args.mesh,
                   "triangle mesh: OBJ, PLY, STL, glTF 2.0 (.gltf/.glb) or OFF, or procedural:sphere|torus|slab|folds")
        ->type_name("PATH")
        ->group(group);
    app.add_option("--volume", args.volume,
                   "volume: NRRD, MetaImage, NIfTI, VTK .vti or a DICOM directory (dims, type, spacing and "
                   "orientation from the header), headerless raw data with dims/type parsed from names like "
                   "bonsai_256x256x256_uint8.raw, or procedural:blobs|shell|bucky")
        ->type_name("PATH")
        ->group(group);
    addSceneOption(app, args.scene,
                   "a JSON scene file (meshes, volumes, lights, camera, output; docs/scene-files.md) instead of "
                   "--mesh/--volume and the options that describe them");
    addDataDirOption(app, args.dataDir);
    addParsed(app, "--dims", args.raw.dims, parseDims, "raw volume dimensions (overrides the name)", "XxYxZ")
        ->group(group);
    addParsed(app, "--type", args.raw.type, parseEnum<sss::VoxelType>,
              "raw voxel type (overrides the name; default uint8)", choices<sss::VoxelType>())
        ->group(group);
    addParsed(app, "--spacing", args.raw.spacing, parseVec3, "raw voxel spacing", "X,Y,Z", "1,1,1")->group(group);
    app.add_option("--tf", args.tf, "transfer-function preset (see --list-tf) or a ParaView JSON colour map")
        ->type_name("NAME|FILE.json")
        ->group(group);
    addParsed(app, "--tf-range", args.tfRange, parseRange,
              "value window: the data values (e.g. Hounsfield units) that the transfer function's domain spans; "
              "values outside clamp to its ends (default: 0..255 for uint8, else the data's min..max)",
              "LO,HI")
        ->group(group);
}

void addDataDirOption(CLI::App& app, std::string& dataDir) {
    app.add_option("--data-dir", dataDir,
                   "where relative paths are looked up (and its meshes/ and volumes/ folders); default: "
                   "$SSS_DATA_DIR, else ../shared/data if it exists")
        ->type_name("DIR")
        ->group("input");
}

void addSceneOption(CLI::App& app, std::string& scene, const std::string& help) {
    app.add_option("--scene", scene, help)->type_name("FILE.json")->group("input");
}

void addMeshOptions(CLI::App& app, sss::MeshRenderOptions& options, std::string& material, bool& noTexture) {
    const std::string group = "mesh scattering";
    app.add_option("--material", material, "translucent material preset (see --list-materials)")
        ->type_name("NAME")
        ->default_str(material)
        ->group(group);
    addTableOptions(app, options, group);
    // Front-end shorthands over several fields.
    addParsed(app, "--map-resolution", options.mapResolution,
              [&options](const std::string& name, const std::string& text) {
                  return options.lightMapResolution = parseInt(name, text);
              },
              "scattering-map and light-buffer side in texels", "R", std::to_string(options.mapResolution))
        ->group(group);
    app.add_flag_callback("--no-specular", [&options] { options.specular = 0.0f; },
                          "no specular highlight on the translucent surface")
        ->group(group);
    app.add_flag("--no-texture", noTexture,
                 "ignore the mesh's base-colour texture (OBJ map_Kd, glTF baseColorTexture); with one, the "
                 "translucent material takes its reflectance from it and only the mean free path and eta from "
                 "--material")
        ->group(group);
}

void addBaselineOptions(CLI::App& app, sss::BlinnPhongMaterial& material) {
    const std::string group = "mesh Blinn-Phong";
    addVec3(app, "--color", material.diffuse, "mesh diffuse colour", "R,G,B")->group(group);
    addFloat(app, "--shininess", material.shininess, "mesh Blinn-Phong exponent", "S")->group(group);
}

void addVolumeOptions(CLI::App& app, sss::VolumeRenderOptions& options) {
    const std::string group = "volume";
    addTableOptions(app, options, group);
    app.add_flag_callback("--preintegration", [&options] { options.preintegration = true; },
                          "pre-integrated classification: each sample shades the segment since the previous one "
                          "with the transfer function integrated over it (catches thin structures between samples)")
        ->group(group);
}

void addDisplayOptions(CLI::App& app, sss::DisplayTransform& display) {
    const std::string group = "display";
    addParsed(app, "--exposure", display.exposure, parseExposure, "exposure in stops for the display image", "EV",
              defaultText(display.exposure))
        ->group(group);
    addEnum(app, "--tonemap", display.toneMap, "tone mapping for the display image (none: values above 1 clip)")
        ->group(group);
}

void addCameraOptions(CLI::App& app, sss::SceneCamera& camera) {
    const std::string group = "camera";
    addFloat(app, "--yaw", camera.yaw, "orbit angle around the scene centre", "DEG")->group(group);
    addFloat(app, "--pitch", camera.pitch, "orbit elevation", "DEG")->group(group);
    addParsed(app, "--zoom", camera.zoom,
              [](const std::string& name, const std::string& text) {
                  const float zoom = parseFloat(name, text);
                  if (!(zoom > 0.0f)) throw UsageError(name + ": must be > 0");
                  return zoom;
              },
              "distance factor after framing the scene (< 1 moves closer; scales the orthographic view too)",
              "F", defaultText(camera.zoom))
        ->group(group);
    addParsed(app, "--fov", camera.fovY,
              [](const std::string& name, const std::string& text) {
                  const float fov = parseFloat(name, text);
                  if (!(fov > 0.0f && fov < 180.0f)) throw UsageError(name + ": must be in (0, 180) degrees");
                  return fov;
              },
              "vertical field of view", "DEG", defaultText(camera.fovY))
        ->group(group);
    app.add_flag_callback("--ortho", [&camera] { camera.projection = sss::Projection::Orthographic; },
                          "orthographic projection")
        ->group(group);
}

void addLightOptions(CLI::App& app, LightArgs& light) {
    const std::string group = "light";
    addParsed(app, "--light-dir", light.directional.direction,
              [&light](const std::string& name, const std::string& text) {
                  light.given = true;
                  return parseVec3(name, text);
              },
              "direction a directional light travels", "X,Y,Z", defaultText(light.directional.direction))
        ->group(group);
    addVec3(app, "--light-color", light.directional.color, "light colour", "R,G,B")->group(group);
    addFloat(app, "--light-intensity", light.directional.intensity, "light intensity", "I")->group(group);
    addParsed(app, "--point-light", light.point,
              [&light](const std::string& name, const std::string& text) {
                  light.given = true;
                  return std::optional(parseVec3(name, text));
              },
              "a point light at this position instead", "X,Y,Z")
        ->group(group);
    addParsed(app, "--spot-light", light.spot,
              [&light](const std::string& name, const std::string& text) {
                  light.given = true;
                  return std::optional(parseSpotLight(name, text));
              },
              "a spot light instead: position, cone axis, cone half-angle in degrees and the share of it over "
              "which the edge fades (default 0.2)",
              "X,Y,Z:DX,DY,DZ:ANGLE[:FALLOFF]")
        ->group(group);
}

CLI::Option* addSizeOption(CLI::App& app, int& width, int& height, const char* what) {
    return addParsed(app, "--size", width,
              [&height](const std::string& name, const std::string& text) {
                  const auto parts = split(text, 'x');
                  if (parts.size() != 2) throw UsageError(name + ": expected WxH, got \"" + text + "\"");
                  const int w = parseInt(name, parts[0]), h = parseInt(name, parts[1]);
                  if (w <= 0 || h <= 0 || w > sss::kMaxImageSide || h > sss::kMaxImageSide)
                      throw UsageError(name + ": width and height must be in 1.." +
                                       std::to_string(sss::kMaxImageSide) + ", got \"" + text + "\"");
                  height = h;
                  return w;
              },
              what, "WxH", std::to_string(width) + "x" + std::to_string(height))
        ->group("output");
}

void addAntiAliasingOption(CLI::App& app, int& frames, const char* what) {
    addParsed(app, "--aa", frames,
              [](const std::string& name, const std::string& text) {
                  const int n = parseInt(name, text);
                  if (n < 1 || n > 256) throw UsageError(name + ": must be in 1..256");
                  return n;
              },
              what, "N", std::to_string(frames))
        ->group("output");
}

void parseCommandLine(CLI::App& app, int argc, char** argv) {
    app.formatter(std::make_shared<Formatter>());
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp&) {
        std::cout << app.help();
        std::exit(0);
    } catch (const CLI::ParseError& e) {
        throw UsageError(e.what());
    }
}

bool given(const CLI::App& app, const std::string& name) {
    const CLI::Option* option = app.get_option_no_throw(name);
    return option && option->count() > 0;
}

void rejectWithScene(const CLI::App& app, std::initializer_list<const char*> sceneOptions) {
    for (const char* name : sceneOptions)
        if (given(app, name))
            throw UsageError(std::string(name) + " cannot be combined with --scene: the scene file describes it");
}

}  // namespace examples
