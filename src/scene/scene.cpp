#include "sss/scene.h"

#include "util/format.h"

#include "sss/error.h"
#include "sss/materials.h"
#include "sss/option_names.h"
#include "sss/option_table.h"
#include "sss/procedural.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <regex>
#include <set>
#include <sstream>

namespace fs = std::filesystem;
// Ordered, so files list version, meshes, volumes, lights, camera, options and output in that order.
using json = nlohmann::ordered_json;

namespace sss {
namespace {

// ---------------------------------------------------------------------------------------------
// The fields of the structs, for reading and writing: f(name, member). The renderers' options
// come from their tables (sss/option_table.h).

template <class F>
void fields(MeshRenderOptions& o, F&& f) {
    forEachOptionField<MeshRenderOptions>([&](const auto& field) { f(field.name, o.*field.member); });
}

template <class F>
void fields(VolumeRenderOptions& o, F&& f) {
    forEachOptionField<VolumeRenderOptions>([&](const auto& field) { f(field.name, o.*field.member); });
}

template <class F>
void fields(HybridOptions& o, F&& f) {
    forEachOptionField<HybridOptions>([&](const auto& field) { f(field.name, o.*field.member); });
}

template <class F>
void fields(BlinnPhongMaterial& o, F&& f) {
    f("diffuse", o.diffuse);
    f("specular", o.specular);
    f("shininess", o.shininess);
    f("ambient", o.ambient);
}

template <class F>
void fields(SceneTransform& o, F&& f) {
    f("translate", o.translate);
    f("rotate", o.rotate);
    f("scale", o.scale);
}

template <class F>
void fields(SceneCamera& o, F&& f) {
    f("yaw", o.yaw);
    f("pitch", o.pitch);
    f("zoom", o.zoom);
    f("fovY", o.fovY);
    f("projection", o.projection);
    f("margin", o.margin);
    f("target", o.target);
    f("distance", o.distance);
}

template <class F>
void fields(SceneOutput& o, F&& f) {
    f("width", o.width);
    f("height", o.height);
    f("antiAliasing", o.antiAliasing);
    f("exposure", o.display.exposure);
    f("toneMap", o.display.toneMap);
}

template <class F>
void fields(DirectionalLight& o, F&& f) {
    f("direction", o.direction);
    f("color", o.color);
    f("intensity", o.intensity);
}

template <class F>
void fields(PointLight& o, F&& f) {
    f("position", o.position);
    f("color", o.color);
    f("intensity", o.intensity);
}

template <class F>
void fields(SpotLight& o, F&& f) {
    f("position", o.position);
    f("direction", o.direction);
    f("coneAngle", o.coneAngle);
    f("falloff", o.falloff);
    f("color", o.color);
    f("intensity", o.intensity);
}

// ---------------------------------------------------------------------------------------------
// Reading, with the JSON path of every value for messages.

template <class T>
inline constexpr bool kIsEnum = std::is_enum_v<T>;

[[noreturn]] void fail(const std::string& file, const std::string& path, const std::string& problem) {
    throw Error(ErrorKind::InvalidArgument, file + ": " + path + ": " + problem);
}

std::string typeName(const json& j) {
    if (j.is_number()) return "a number";
    if (j.is_string()) return "a string";
    if (j.is_boolean()) return "a boolean";
    if (j.is_array()) return "an array";
    if (j.is_object()) return "an object";
    return "null";
}

class ObjectReader {
public:
    ObjectReader(const json& j, std::string path, const std::string& file)
        : m_json(j), m_path(std::move(path)), m_file(file) {
        if (!j.is_object()) fail(m_file, m_path, "expected an object, got " + typeName(j));
    }

    std::string path(std::string_view key) const {
        return m_path.empty() ? std::string(key) : m_path + "." + std::string(key);
    }
    const std::string& path() const { return m_path; }
    const std::string& file() const { return m_file; }

    const json* find(std::string_view key) {
        m_used.insert(std::string(key));
        const auto it = m_json.find(std::string(key));
        return it == m_json.end() ? nullptr : &*it;
    }

    /// Reads `key` into `out` if present.
    template <class T>
    void operator()(std::string_view key, T& out) {
        if (const json* j = find(key)) read(*j, path(key), out);
    }

    /// Fails for keys nobody asked for (a misspelt field would otherwise be ignored silently).
    void finish() const {
        for (const auto& [key, value] : m_json.items())
            if (!m_used.count(key)) fail(m_file, path(key), "unknown field");
    }

    void read(const json& j, const std::string& at, bool& out) const {
        if (!j.is_boolean()) fail(m_file, at, "expected true or false, got " + typeName(j));
        out = j.get<bool>();
    }
    void read(const json& j, const std::string& at, double& out) const {
        if (!j.is_number()) fail(m_file, at, "expected a number, got " + typeName(j));
        out = j.get<double>();
        if (!std::isfinite(out)) fail(m_file, at, "expected a finite number");
    }
    void read(const json& j, const std::string& at, float& out) const {
        double d = 0.0;
        read(j, at, d);
        if (!(std::abs(d) <= double(std::numeric_limits<float>::max())))
            fail(m_file, at, "the number " + j.dump() + " is outside the range of a float");
        out = static_cast<float>(d);
    }
    void read(const json& j, const std::string& at, int& out) const {
        if (!j.is_number_integer()) fail(m_file, at, "expected an integer, got " + (j.is_number() ? j.dump() : typeName(j)));
        const auto v = j.get<long long>();
        if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
            fail(m_file, at, "the integer " + j.dump() + " is out of range");
        out = static_cast<int>(v);
    }
    void read(const json& j, const std::string& at, std::string& out) const {
        if (!j.is_string()) fail(m_file, at, "expected a string, got " + typeName(j));
        out = j.get<std::string>();
    }
    template <int N, class T>
    void read(const json& j, const std::string& at, glm::vec<N, T>& out) const {
        if (!j.is_array() || j.size() != N)
            fail(m_file, at, "expected an array of " + std::to_string(N) + " numbers, got " + j.dump());
        for (int i = 0; i < N; ++i) read(j[i], at + "[" + std::to_string(i) + "]", out[i]);
    }
    template <class T>
    void read(const json& j, const std::string& at, std::optional<T>& out) const {
        read(j, at, out.emplace());
    }
    template <class E>
        requires kIsEnum<E>
    void read(const json& j, const std::string& at, E& out) const {
        std::string name;
        read(j, at, name);
        const auto value = parseEnumName<E>(name);
        if (!value) fail(m_file, at, "expected " + enumNameList<E>() + ", got \"" + name + "\"");
        out = *value;
    }

private:
    const json& m_json;
    std::string m_path;
    const std::string& m_file;
    std::set<std::string> m_used;
};

template <class T>
void readFields(const json& j, const std::string& path, const std::string& file, T& out) {
    ObjectReader reader(j, path, file);
    fields(out, reader);
    reader.finish();
}

const json& arrayAt(const json& root, const char* key, const std::string& file) {
    static const json empty = json::array();
    const auto it = root.find(key);
    if (it == root.end()) return empty;
    if (!it->is_array()) fail(file, key, "expected an array, got " + typeName(*it));
    return *it;
}

std::string indexed(std::string_view array, std::size_t i) { return std::string(array) + "[" + std::to_string(i) + "]"; }

/// Runs a library validation and names the JSON path of the field it rejects: "MeshRenderOptions::
/// cameras must be in 1..32, got 0" becomes "scene.json: meshes[0].options.cameras: must be ...".
template <class F>
void validateAt(const std::string& file, const std::string& path, F&& validation) {
    try {
        validation();
    } catch (const Error& e) {
        if (!e.field().empty()) fail(file, path + "." + e.field(), e.reason());
        fail(file, path, e.what());
    }
}

ScatteringMaterial readMaterial(const json& j, const std::string& path, const std::string& file) {
    if (j.is_string()) {
        try {
            return materialPreset(j.get<std::string>());
        } catch (const Error& e) {
            fail(file, path, e.what());
        }
    }
    ScatteringMaterial material;
    material.name = "custom";
    ObjectReader reader(j, path, file);
    reader("name", material.name);
    reader("sigmaA", material.sigmaA);
    reader("sigmaS", material.sigmaS);
    reader("g", material.g);
    reader("eta", material.eta);
    reader.finish();
    return material;
}

SceneTransferFunction readTransferFunction(const json& j, const std::string& path, const std::string& file) {
    SceneTransferFunction tf;
    if (j.is_string()) {
        tf.preset = j.get<std::string>();
        return tf;
    }
    ObjectReader reader(j, path, file);
    reader("preset", tf.preset);
    reader("file", tf.file);
    if (const json* points = reader.find("points")) {
        if (!points->is_array() || points->empty())
            fail(file, reader.path("points"), "expected a non-empty array of [value, r, g, b, opacity]");
        for (std::size_t i = 0; i < points->size(); ++i) {
            const std::string at = reader.path("points") + "[" + std::to_string(i) + "]";
            float p[5] = {};
            const json& e = (*points)[i];
            if (!e.is_array() || e.size() != 5) fail(file, at, "expected [value, r, g, b, opacity], got " + e.dump());
            for (int c = 0; c < 5; ++c) reader.read(e[c], at + "[" + std::to_string(c) + "]", p[c]);
            tf.points.push_back({p[0], {p[1], p[2], p[3]}, p[4]});
        }
        validateAt(file, reader.path("points"), [&] { (void)TransferFunction(tf.points); });
    }
    reader.finish();
    return tf;
}

SceneIsosurface readIsosurface(const json& j, const std::string& path, const std::string& file) {
    SceneIsosurface iso;
    ObjectReader reader(j, path, file);
    reader("volume", iso.volume);
    if (iso.volume < 0) fail(file, reader.path("volume"), "must be the index of a scene volume, >= 0");
    if (!reader.find("value")) fail(file, reader.path("value"), "an isosurface needs a value (in the data's units)");
    reader("value", iso.options.value);
    reader("smoothingIterations", iso.options.smoothingIterations);
    reader("maxTriangles", iso.options.maxTriangles);
    reader("millimetresPerVolumeUnit", iso.millimetresPerVolumeUnit);
    if (iso.options.smoothingIterations < 0) fail(file, reader.path("smoothingIterations"), "must be >= 0");
    if (iso.options.maxTriangles < 0) fail(file, reader.path("maxTriangles"), "must be >= 0");
    if (!(iso.millimetresPerVolumeUnit > 0.0 && iso.millimetresPerVolumeUnit <= 1e9))
        fail(file, reader.path("millimetresPerVolumeUnit"), "must be in (0, 1e9]");
    reader.finish();
    return iso;
}

SceneMesh readMesh(const json& j, const std::string& path, const std::string& file) {
    SceneMesh mesh;
    ObjectReader reader(j, path, file);
    reader("source", mesh.source);
    if (const json* iso = reader.find("isosurface")) {
        if (!mesh.source.empty()) fail(file, reader.path("isosurface"), "a mesh has either a source or an isosurface");
        mesh.isosurface = readIsosurface(*iso, reader.path("isosurface"), file);
    } else if (mesh.source.empty()) {
        fail(file, reader.path("source"), "a mesh needs a non-empty source (or an isosurface)");
    }
    if (const json* size = reader.find("size")) {
        float s = 0.0f;
        reader.read(*size, reader.path("size"), s);
        if (!(s > 0.0f && s <= 1e6f)) fail(file, reader.path("size"), "must be in (0, 1e6] scene units");
        if (mesh.isosurface) fail(file, reader.path("size"), "an isosurface keeps its volume's size");
        mesh.size = s;
    }
    if (const json* t = reader.find("transform")) readFields(*t, reader.path("transform"), file, mesh.transform);
    if (const json* o = reader.find("options")) readFields(*o, reader.path("options"), file, mesh.options);
    if (const json* m = reader.find("material")) mesh.material = readMaterial(*m, reader.path("material"), file);
    reader("texture", mesh.texture);
    if (const json* b = reader.find("baseline")) readFields(*b, reader.path("baseline"), file, mesh.baseline);
    reader.finish();
    validateAt(file, reader.path("options"), [&] { validate(mesh.options); });
    validateAt(file, reader.path("material"), [&] { mesh.material.validate(); });
    validateAt(file, reader.path("baseline"), [&] { validate(mesh.baseline); });
    return mesh;
}

VolumeClip readClip(const json& j, const std::string& path, const std::string& file) {
    VolumeClip clip;
    ObjectReader reader(j, path, file);
    if (const json* planes = reader.find("planes")) {
        if (!planes->is_array()) fail(file, reader.path("planes"), "expected an array, got " + typeName(*planes));
        for (std::size_t i = 0; i < planes->size(); ++i) {
            ObjectReader r((*planes)[i], reader.path(indexed("planes", i)), file);
            ClipPlane& plane = clip.planes.emplace_back();
            r("point", plane.point);
            r("normal", plane.normal);
            r.finish();
        }
    }
    reader("planeSpace", clip.planeSpace);
    reader("cropMin", clip.cropMin);
    reader("cropMax", clip.cropMax);
    reader("cropSpace", clip.cropSpace);
    reader("clippedMatterCastsShadows", clip.clippedMatterCastsShadows);
    reader.finish();
    validateAt(file, path, [&] { validate(clip); });
    return clip;
}

json writeClip(const VolumeClip& clip) {
    json j = json::object();
    if (!clip.planes.empty()) {
        json planes = json::array();
        for (const ClipPlane& p : clip.planes)
            planes.push_back({{"point", {p.point.x, p.point.y, p.point.z}}, {"normal", {p.normal.x, p.normal.y, p.normal.z}}});
        j["planes"] = planes;
        if (clip.planeSpace != CropSpace::World) j["planeSpace"] = std::string(enumName(clip.planeSpace));
    }
    if (clip.cropMin != glm::vec3(0.0f)) j["cropMin"] = {clip.cropMin.x, clip.cropMin.y, clip.cropMin.z};
    if (clip.cropMax != glm::vec3(1.0f)) j["cropMax"] = {clip.cropMax.x, clip.cropMax.y, clip.cropMax.z};
    if (clip.cropSpace != CropSpace::Data) j["cropSpace"] = std::string(enumName(clip.cropSpace));
    if (clip.clippedMatterCastsShadows) j["clippedMatterCastsShadows"] = true;
    return j;
}

SceneVolume readVolume(const json& j, const std::string& path, const std::string& file) {
    SceneVolume volume;
    ObjectReader reader(j, path, file);
    reader("source", volume.source);
    if (volume.source.empty()) fail(file, reader.path("source"), "a volume needs a non-empty source");
    if (const json* raw = reader.find("raw")) {
        ObjectReader r(*raw, reader.path("raw"), file);
        if (const json* dims = r.find("dims")) r.read(*dims, r.path("dims"), volume.raw.dims.emplace());
        if (const json* type = r.find("type")) r.read(*type, r.path("type"), volume.raw.type.emplace());
        if (const json* spacing = r.find("spacing")) r.read(*spacing, r.path("spacing"), volume.raw.spacing.emplace());
        r.finish();
    }
    if (const json* window = reader.find("valueWindow")) {
        glm::dvec2 w{};
        reader.read(*window, reader.path("valueWindow"), w);
        if (!(w.x < w.y)) fail(file, reader.path("valueWindow"), "LO must be less than HI, got " + window->dump());
        volume.valueWindow = std::pair(w.x, w.y);
    }
    if (const json* tf = reader.find("transferFunction"))
        volume.transferFunction = readTransferFunction(*tf, reader.path("transferFunction"), file);
    if (const json* t = reader.find("transform")) readFields(*t, reader.path("transform"), file, volume.transform);
    if (const json* o = reader.find("options")) readFields(*o, reader.path("options"), file, volume.options);
    reader("visible", volume.visible);
    if (const json* clip = reader.find("clip")) volume.clip = readClip(*clip, reader.path("clip"), file);
    reader.finish();
    validateAt(file, reader.path("options"), [&] { validate(volume.options); });
    return volume;
}

Light readLight(const json& j, const std::string& path, const std::string& file) {
    ObjectReader reader(j, path, file);
    std::string type;
    reader("type", type);
    Light light;
    if (type == "directional") light = DirectionalLight{};
    else if (type == "point") light = PointLight{};
    else if (type == "spot") light = SpotLight{};
    else fail(file, reader.path("type"), "expected directional, point or spot, got \"" + type + "\"");
    std::visit([&](auto& l) { fields(l, reader); }, light);
    reader.finish();
    validateAt(file, path, [&] { validateLight(light, ""); });
    return light;
}

void checkTransform(const SceneTransform& t, const std::string& path, const std::string& file) {
    for (int i = 0; i < 3; ++i)
        if (!(std::abs(t.translate[i]) <= Mesh::kMaxCoordinate))
            fail(file, path + ".translate", "components must be within +-1e18 (scene units)");
    if (!(t.scale.x != 0.0f && t.scale.y != 0.0f && t.scale.z != 0.0f))
        fail(file, path + ".scale", "components must be non-zero, got " + detail::formatVec(t.scale));
}

// ---------------------------------------------------------------------------------------------
// Writing: every field, then those equal to a default-constructed struct's are dropped.

/// The double with the fewest decimal digits that reads back as `v` ("0.05", not
/// "0.05000000074505806"), so files stay readable and round trips exact.
double shortest(float v) {
    for (int digits = 6; digits < 9; ++digits) {
        char text[32];
        std::snprintf(text, sizeof text, "%.*g", digits, double(v));
        const double parsed = std::strtod(text, nullptr);
        if (static_cast<float>(parsed) == v) return parsed;
    }
    return double(v);
}

struct FieldWriter {
    json& out;
    void operator()(std::string_view key, bool v) { out[std::string(key)] = v; }
    void operator()(std::string_view key, int v) { out[std::string(key)] = v; }
    void operator()(std::string_view key, float v) { out[std::string(key)] = shortest(v); }
    void operator()(std::string_view key, double v) { out[std::string(key)] = v; }
    template <int N, class T>
    void operator()(std::string_view key, const glm::vec<N, T>& v) {
        json a = json::array();
        for (int i = 0; i < N; ++i) {
            if constexpr (std::is_same_v<T, float>) a.push_back(shortest(v[i]));
            else a.push_back(static_cast<double>(v[i]));
        }
        out[std::string(key)] = a;
    }
    template <class E>
        requires kIsEnum<E>
    void operator()(std::string_view key, E v) { out[std::string(key)] = std::string(enumName(v)); }
    template <class T>
    void operator()(std::string_view key, const std::optional<T>& v) {
        if (v) (*this)(key, *v);
    }
};

template <class T>
json writeFields(T value, bool dropDefaults = true) {
    json all = json::object(), defaults = json::object();
    FieldWriter writer{all};
    fields(value, writer);
    if (!dropDefaults) return all;
    T fallback{};
    FieldWriter defaultWriter{defaults};
    fields(fallback, defaultWriter);
    json changed = json::object();
    for (const auto& [key, v] : all.items())
        if (v != defaults[key]) changed[key] = v;
    return changed;
}

json writeMaterial(const ScatteringMaterial& m) {
    // A preset by its name, when the coefficients are the preset's own.
    try {
        const ScatteringMaterial preset = materialPreset(m.name);
        if (preset.sigmaA == m.sigmaA && preset.sigmaS == m.sigmaS && preset.g == m.g && preset.eta == m.eta)
            return m.name;
    } catch (const Error&) {
    }
    json j = json::object();
    j["name"] = m.name;
    FieldWriter w{j};
    w("sigmaA", m.sigmaA);
    w("sigmaS", m.sigmaS);
    w("g", m.g);
    w("eta", m.eta);
    return j;
}

json writeTransferFunction(const SceneTransferFunction& tf) {
    if (tf.points.empty() && tf.file.empty()) return tf.preset;
    json j = json::object();
    if (!tf.points.empty()) {
        json points = json::array();
        for (const ControlPoint& p : tf.points)
            points.push_back({shortest(p.value), shortest(p.color.r), shortest(p.color.g), shortest(p.color.b),
                              shortest(p.opacity)});
        j["points"] = points;
    } else {
        j["file"] = tf.file;
    }
    return j;
}

const char* lightType(const Light& light) {
    if (std::holds_alternative<DirectionalLight>(light)) return "directional";
    if (std::holds_alternative<PointLight>(light)) return "point";
    return "spot";
}

// ---------------------------------------------------------------------------------------------
// Assets.

std::optional<std::string> proceduralName(std::string_view source) {
    constexpr std::string_view prefix = "procedural:";
    if (source.substr(0, prefix.size()) == prefix) return std::string(source.substr(prefix.size()));
    return std::nullopt;
}

fs::path resolve(std::string_view source, std::span<const fs::path> searchDirs, const char* subfolder) {
    const fs::path given(source);
    if (fs::exists(given) || given.is_absolute()) return given;
    for (const fs::path& dir : searchDirs) {
        if (dir.empty()) continue;
        for (const fs::path& candidate : {dir / given, dir / subfolder / given})
            if (fs::exists(candidate)) return candidate;
    }
    return given;  // the loader reports the missing file by the name the user gave
}

bool hasHeaderedVolumeExtension(const fs::path& path) {
    std::string name = path.filename().string();
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    for (const char* ext : {".nrrd", ".nhdr", ".mhd", ".mha", ".nii", ".nii.gz", ".vti"})
        if (name.size() >= std::strlen(ext) && name.compare(name.size() - std::strlen(ext), std::string::npos, ext) == 0)
            return true;
    return false;
}

std::vector<fs::path> searchList(const SceneDescription& scene, std::span<const fs::path> searchDirs) {
    std::vector<fs::path> dirs;
    if (!scene.baseDirectory.empty()) dirs.push_back(scene.baseDirectory);
    dirs.insert(dirs.end(), searchDirs.begin(), searchDirs.end());
    return dirs;
}

/// Prefixes a loader's message with the scene field, keeping its kind (a missing file stays an
/// I/O error, a bad value an invalid argument).
template <class F>
auto atField(const std::string& path, F&& load) {
    try {
        return load();
    } catch (const Error& e) {
        throw Error(e.kind(), path + ": " + e.what());
    }
}

}  // namespace

glm::mat4 SceneTransform::matrix() const {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), translate);
    m = glm::rotate(m, glm::radians(rotate.z), glm::vec3(0, 0, 1));
    m = glm::rotate(m, glm::radians(rotate.y), glm::vec3(0, 1, 0));
    m = glm::rotate(m, glm::radians(rotate.x), glm::vec3(1, 0, 0));
    return glm::scale(m, scale);
}

SceneDescription parseScene(std::string_view text, std::string_view name) {
    const std::string file(name);
    json root;
    try {
        root = json::parse(text);
    } catch (const json::exception& e) {  // parse_error, and out_of_range for a number beyond a double
        throw Error(ErrorKind::Parse, file + ": not valid JSON: " + e.what());
    }
    SceneDescription scene;
    ObjectReader reader(root, "", file);
    if (const json* version = reader.find("version"); version && *version != 1)
        fail(file, "version", "this libsss reads scene files of version 1, got " + version->dump());
    auto list = [&](const char* key) -> const json& {
        reader.find(key);
        return arrayAt(root, key, file);
    };
    const json& meshes = list("meshes");
    for (std::size_t i = 0; i < meshes.size(); ++i) scene.meshes.push_back(readMesh(meshes[i], indexed("meshes", i), file));
    const json& volumes = list("volumes");
    for (std::size_t i = 0; i < volumes.size(); ++i)
        scene.volumes.push_back(readVolume(volumes[i], indexed("volumes", i), file));
    const json& lights = list("lights");
    if (lights.size() > 8) fail(file, "lights", "at most 8 lights are supported, got " + std::to_string(lights.size()));
    for (std::size_t i = 0; i < lights.size(); ++i) scene.lights.push_back(readLight(lights[i], indexed("lights", i), file));
    if (const json* c = reader.find("camera")) readFields(*c, "camera", file, scene.camera);
    if (const json* o = reader.find("options")) readFields(*o, "options", file, scene.options);
    if (const json* o = reader.find("output")) readFields(*o, "output", file, scene.output);
    reader.finish();
    if (scene.meshes.empty() && scene.volumes.empty()) fail(file, "meshes", "the scene holds no mesh and no volume");

    for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
        checkTransform(scene.meshes[i].transform, indexed("meshes", i) + ".transform", file);
        if (const auto& iso = scene.meshes[i].isosurface; iso && iso->volume >= static_cast<int>(scene.volumes.size()))
            fail(file, indexed("meshes", i) + ".isosurface.volume",
                 "no volume " + std::to_string(iso->volume) + " (the scene has " + std::to_string(scene.volumes.size()) + ")");
    }
    for (std::size_t i = 0; i < scene.volumes.size(); ++i)
        checkTransform(scene.volumes[i].transform, indexed("volumes", i) + ".transform", file);
    const SceneCamera& c = scene.camera;
    if (!(c.zoom > 0.0f)) fail(file, "camera.zoom", "must be > 0");
    if (!(c.fovY > 0.0f && c.fovY < 180.0f)) fail(file, "camera.fovY", "must be in (0, 180) degrees");
    if (!(c.margin >= 0.0f && c.margin <= 0.5f)) fail(file, "camera.margin", "must be in [0, 0.5]");
    if (c.target.has_value() != c.distance.has_value())
        fail(file, c.target ? "camera.distance" : "camera.target", "target and distance go together");
    if (c.distance && !(*c.distance > 0.0f)) fail(file, "camera.distance", "must be > 0");
    if (c.target && !(glm::all(glm::lessThanEqual(glm::abs(*c.target), glm::vec3(Mesh::kMaxCoordinate)))))
        fail(file, "camera.target", "components must be within +-1e18 (scene units)");
    const SceneOutput& o = scene.output;
    if (o.width < 1 || o.width > kMaxImageSide) fail(file, "output.width", "must be in 1..16384");
    if (o.height < 1 || o.height > kMaxImageSide) fail(file, "output.height", "must be in 1..16384");
    if (o.antiAliasing < 1 || o.antiAliasing > 256) fail(file, "output.antiAliasing", "must be in 1..256");
    if (!(std::abs(o.display.exposure) <= 64.0f)) fail(file, "output.exposure", "must be within [-64, 64] stops");
    validateAt(file, "options", [&] { validate(scene.options); });
    return scene;
}

SceneDescription loadSceneFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(ErrorKind::Io, path.string() + ": cannot open the scene file");
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) throw Error(ErrorKind::Io, path.string() + ": cannot read the scene file");
    SceneDescription scene = parseScene(text.str(), path.string());
    scene.baseDirectory = path.parent_path();
    return scene;
}

std::string sceneToJson(const SceneDescription& scene) {
    json root = json::object();
    root["version"] = 1;
    json meshes = json::array();
    for (const SceneMesh& m : scene.meshes) {
        json j = json::object();
        if (m.isosurface) {
            const SceneIsosurface& iso = *m.isosurface;
            const SceneIsosurface defaults;
            json i = {{"volume", iso.volume}, {"value", iso.options.value}};
            if (iso.options.smoothingIterations != defaults.options.smoothingIterations)
                i["smoothingIterations"] = iso.options.smoothingIterations;
            if (iso.options.maxTriangles != defaults.options.maxTriangles) i["maxTriangles"] = iso.options.maxTriangles;
            if (iso.millimetresPerVolumeUnit != defaults.millimetresPerVolumeUnit)
                i["millimetresPerVolumeUnit"] = iso.millimetresPerVolumeUnit;
            j["isosurface"] = i;
        } else {
            j["source"] = m.source;
        }
        if (m.size) j["size"] = double(*m.size);
        if (json t = writeFields(m.transform); !t.empty()) j["transform"] = t;
        if (json o = writeFields(m.options); !o.empty()) j["options"] = o;
        j["material"] = writeMaterial(m.material);
        if (!m.texture) j["texture"] = false;
        if (json b = writeFields(m.baseline); !b.empty()) j["baseline"] = b;
        meshes.push_back(j);
    }
    if (!meshes.empty()) root["meshes"] = meshes;
    json volumes = json::array();
    for (const SceneVolume& v : scene.volumes) {
        json j = json::object();
        j["source"] = v.source;
        json raw = json::object();
        FieldWriter rawWriter{raw};
        if (v.raw.dims) raw["dims"] = {v.raw.dims->x, v.raw.dims->y, v.raw.dims->z};
        if (v.raw.type) rawWriter("type", *v.raw.type);
        if (v.raw.spacing) rawWriter("spacing", *v.raw.spacing);
        if (!raw.empty()) j["raw"] = raw;
        if (v.valueWindow) j["valueWindow"] = {v.valueWindow->first, v.valueWindow->second};
        j["transferFunction"] = writeTransferFunction(v.transferFunction);
        if (json t = writeFields(v.transform); !t.empty()) j["transform"] = t;
        if (json o = writeFields(v.options); !o.empty()) j["options"] = o;
        if (!v.visible) j["visible"] = false;
        if (!(v.clip == VolumeClip{})) j["clip"] = writeClip(v.clip);
        volumes.push_back(j);
    }
    if (!volumes.empty()) root["volumes"] = volumes;
    json lights = json::array();
    for (const Light& light : scene.lights) {
        json j = json::object();
        j["type"] = lightType(light);
        FieldWriter w{j};
        std::visit([&](auto l) { fields(l, w); }, light);
        lights.push_back(j);
    }
    if (!lights.empty()) root["lights"] = lights;
    root["camera"] = writeFields(scene.camera, false);
    if (json o = writeFields(scene.options); !o.empty()) root["options"] = o;
    root["output"] = writeFields(scene.output, false);
    // Arrays of numbers on one line each ([1, 0.5, 0]), everything else indented.
    static const std::regex numbers(R"(\[\s*([-+0-9.eE]+(?:,\s*[-+0-9.eE]+)*)\s*\])");
    std::string text = root.dump(2);
    std::string compact;
    auto begin = text.cbegin();
    for (std::smatch m; std::regex_search(begin, text.cend(), m, numbers); begin = m.suffix().first) {
        compact.append(m.prefix().first, m.prefix().second);
        std::string inner = m[1].str();
        inner = std::regex_replace(inner, std::regex(R"(,\s*)"), ", ");
        compact += "[" + inner + "]";
    }
    compact.append(begin, text.cend());
    return compact + "\n";
}

void saveSceneFile(const SceneDescription& scene, const fs::path& path) {
    const std::string text = sceneToJson(scene);
    std::ofstream out(path, std::ios::binary);
    out << text;
    out.flush();
    if (!out) throw Error(ErrorKind::Io, path.string() + ": cannot write the scene file");
}

Mesh loadMeshSource(std::string_view source, std::span<const fs::path> searchDirs) {
    if (auto name = proceduralName(source)) {
        if (*name == "sphere") return makeUvSphere();  // the thesis sphere, 382 v / 800 tri
        if (*name == "torus") return makeTorus();
        if (*name == "slab") return makeSlab();
        if (*name == "folds") return makeFolds();  // concave, with overhangs: 20 322 v / 40 960 tri
        throw Error(ErrorKind::InvalidArgument, "unknown procedural mesh \"" + *name + "\" (sphere, torus, slab, folds)");
    }
    if (source.empty()) throw Error(ErrorKind::InvalidArgument, "empty mesh path");
    return Mesh::load(resolve(source, searchDirs, "meshes"));
}

Volume loadVolumeSource(std::string_view source, const RawLoadOptions& raw, std::span<const fs::path> searchDirs) {
    if (auto name = proceduralName(source)) {
        if (*name == "blobs") return makeBlobsVolume();
        if (*name == "shell") return makeShellVolume();
        if (*name == "bucky") return makeBuckyLikeVolume();
        throw Error(ErrorKind::InvalidArgument, "unknown procedural volume \"" + *name + "\" (blobs, shell, bucky)");
    }
    if (source.empty()) throw Error(ErrorKind::InvalidArgument, "empty volume path");
    const fs::path resolved = resolve(source, searchDirs, "volumes");
    // Headered formats and DICOM directories go to Volume::load; anything else is headerless raw
    // data (names other than .raw included).
    if (fs::is_directory(resolved) || hasHeaderedVolumeExtension(resolved)) return Volume::load(resolved);
    return Volume::loadRaw(resolved, raw);
}

SceneAssets loadSceneAssets(const SceneDescription& scene, std::span<const fs::path> searchDirs) {
    const std::vector<fs::path> dirs = searchList(scene, searchDirs);
    SceneAssets assets;
    // Volumes first: isosurface meshes are made from them.
    for (std::size_t i = 0; i < scene.volumes.size(); ++i) {
        const SceneVolume& v = scene.volumes[i];
        const std::string path = indexed("volumes", i);
        Volume volume = atField(path, [&] { return loadVolumeSource(v.source, v.raw, dirs); });
        atField(path, [&] { volume.setValueWindow(v.valueWindow); return 0; });
        const SceneTransferFunction& tf = v.transferFunction;
        assets.transferFunctions.push_back(atField(path + ".transferFunction", [&] {
            if (!tf.points.empty()) return TransferFunction(tf.points);
            if (!tf.file.empty()) {
                return TransferFunction::loadParaViewJson(resolve(tf.file, dirs, "transfer-functions"), v.valueWindow);
            }
            return TransferFunction::preset(tf.preset);
        }));
        assets.volumes.push_back(std::move(volume));
    }
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
        const SceneMesh& m = scene.meshes[i];
        double millimetresPerUnit = 0.0;
        Mesh mesh = atField(indexed("meshes", i), [&] {
            if (!m.isosurface) return loadMeshSource(m.source, dirs);
            const Volume& volume = assets.volumes.at(static_cast<std::size_t>(m.isosurface->volume));
            WorldIsosurface surface =
                extractIsosurfaceInWorldBox(volume, m.isosurface->options, m.isosurface->millimetresPerVolumeUnit);
            millimetresPerUnit = surface.millimetresPerUnit;
            return std::move(surface.mesh);
        });
        assets.isosurfaceMillimetresPerUnit.push_back(millimetresPerUnit);
        if (m.size) {
            const Bounds b = mesh.bounds();
            const glm::vec3 size = b.size();
            const float largest = std::max({size.x, size.y, size.z, 1e-30f});
            mesh = mesh.transformed(glm::scale(glm::mat4(1.0f), glm::vec3(*m.size / largest)) *
                                    glm::translate(glm::mat4(1.0f), -b.center()));
        }
        assets.meshes.push_back(std::move(mesh));
    }
    return assets;
}

std::vector<Light> defaultSceneLights(const SceneDescription& scene, const Bounds& content) {
    if (!scene.options.cornellBox) return {DirectionalLight{glm::vec3(-1.0f), glm::vec3(1.0f), 1.0f}};
    // Under the ceiling, as in the classic scene, with the intensity scaled to the box's size.
    const Bounds box = makeCornellBox(content).bounds;
    return {PointLight{box.center() + glm::vec3(0.0f, 0.4f * box.size().y, 0.0f), glm::vec3(1.0f),
                       0.5f * box.size().y * box.size().y}};
}

void populateCompositor(HybridCompositor& compositor, const SceneDescription& scene, const SceneAssets& assets) {
    compositor.clear();
    compositor.setOptions(scene.options);
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
        const SceneMesh& m = scene.meshes[i];
        MeshRenderOptions options = m.options;
        if (m.isosurface && i < assets.isosurfaceMillimetresPerUnit.size())
            options.millimetresPerUnit = assets.isosurfaceMillimetresPerUnit[i];
        MeshScatteringRenderer& renderer = compositor.addMesh(assets.meshes[i], m.transform.matrix(), options);
        if (m.texture && assets.meshes[i].baseColour())
            renderer.setScatteringMaterial(texturedScattering(m.material));
        else
            renderer.setScatteringMaterial(m.material);
        renderer.setMaterial(m.baseline);
    }
    for (std::size_t i = 0; i < scene.volumes.size(); ++i) {
        if (!scene.volumes[i].visible) continue;
        // GPU limits are named with the file, which is what the user knows.
        atField(scene.volumes[i].source, [&] {
            VolumeScatteringRenderer& renderer =
                compositor.addVolume(assets.volumes[i], scene.volumes[i].transform.matrix(), scene.volumes[i].options);
            renderer.setTransferFunction(assets.transferFunctions[i]);
            renderer.setClip(scene.volumes[i].clip);
            return 0;
        });
    }
    compositor.setLights(scene.lights.empty() ? defaultSceneLights(scene, compositor.bounds()) : scene.lights);
}

Camera sceneCamera(const SceneDescription& scene, const SceneAssets& assets, const Bounds& content, float aspect) {
    const SceneCamera& c = scene.camera;
    std::vector<glm::vec3> framed;
    auto addBox = [&](const Bounds& b, const glm::mat4& model) {
        for (int i = 0; i < 8; ++i)
            framed.push_back(glm::vec3(model * glm::vec4((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y,
                                                         (i & 4) ? b.max.z : b.min.z, 1.0f)));
    };
    for (std::size_t i = 0; i < assets.meshes.size(); ++i) {
        const glm::mat4 model = scene.meshes[i].transform.matrix();
        for (const glm::vec3& p : assets.meshes[i].positions()) framed.push_back(glm::vec3(model * glm::vec4(p, 1.0f)));
    }
    for (std::size_t i = 0; i < assets.volumes.size(); ++i)
        if (scene.volumes[i].visible) addBox(assets.volumes[i].worldBounds(), scene.volumes[i].transform.matrix());
    if (scene.options.cornellBox) {
        framed.clear();
        addBox(makeCornellBox(content).bounds, glm::mat4(1.0f));
    }
    Camera camera;
    camera.setFovY(c.fovY);
    camera.setYaw(c.yaw);
    camera.setPitch(c.pitch);
    camera.setProjectionType(c.projection);
    if (c.target && c.distance) {
        camera.setTarget(*c.target);
        camera.setDistance(*c.distance);
        // Orthographic: the height the perspective view has at the target.
        camera.setOrthoHeight(2.0f * *c.distance * std::tan(glm::radians(c.fovY) * 0.5f));
        // Near and far enclose everything in view.
        float nearest = std::numeric_limits<float>::max(), farthest = 0.0f;
        for (const glm::vec3& p : framed) {
            const float depth = glm::dot(p - camera.position(), camera.forward());
            nearest = std::min(nearest, depth);
            farthest = std::max(farthest, depth);
        }
        farthest = std::max(farthest * 1.05f, 1e-3f * *c.distance);
        camera.setClipPlanes(std::max(nearest * 0.95f, farthest * 1e-4f), farthest);
    } else {
        camera.frameTight(framed, aspect, c.margin);
    }
    if (c.zoom != 1.0f) {
        camera.zoom(c.zoom);
        camera.setClipPlanes(camera.nearPlane() * std::min(c.zoom, 1.0f), camera.farPlane() * std::max(c.zoom, 1.0f));
    }
    return camera;
}

}  // namespace sss
