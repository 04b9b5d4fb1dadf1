#include "common/scene_inputs.h"

#include <sss/error.h>
#include <sss/scene.h>

#include <cmath>
#include <cstdio>
#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <sstream>

namespace fs = std::filesystem;

namespace examples {
namespace {

}  // namespace

float parseFloat(const std::string& option, const std::string& text) {
    try {
        size_t used = 0;
        const float v = std::stof(text, &used);
        if (used == text.size() && std::isfinite(v)) return v;
    } catch (const std::exception&) {
    }
    throw UsageError(option + ": expected a finite number, got \"" + text + "\"");
}

int parseInt(const std::string& option, const std::string& text) {
    try {
        size_t used = 0;
        const int v = std::stoi(text, &used);
        if (used == text.size()) return v;
    } catch (const std::exception&) {
    }
    throw UsageError(option + ": expected an integer, got \"" + text + "\"");
}

float parseExposure(const std::string& option, const std::string& text) {
    const float stops = parseFloat(option, text);
    if (!(std::abs(stops) <= 64.0f)) throw UsageError(option + ": must be within [-64, 64] stops");
    return stops;
}

std::vector<std::string> split(const std::string& text, char separator) {
    std::vector<std::string> parts;
    std::stringstream ss(text);
    std::string part;
    while (std::getline(ss, part, separator)) parts.push_back(part);
    return parts;
}

glm::vec3 parseVec3(const std::string& option, const std::string& text) {
    const auto parts = split(text, ',');
    if (parts.size() != 3) throw UsageError(option + ": expected X,Y,Z, got \"" + text + "\"");
    return {parseFloat(option, parts[0]), parseFloat(option, parts[1]), parseFloat(option, parts[2])};
}

namespace {

std::vector<float> parseSix(const std::string& option, const std::string& text, const char* form) {
    const auto parts = split(text, ',');
    if (parts.size() != 6) throw UsageError(option + ": expected " + form + ", got \"" + text + "\"");
    std::vector<float> values;
    for (const auto& part : parts) values.push_back(parseFloat(option, part));
    return values;
}

}  // namespace

ParsedClipPlane parseClipPlane(const std::string& option, const std::string& text) {
    const auto parts = split(text, ',');
    if (parts.size() != 4 && parts.size() != 6)
        throw UsageError(option + ": expected NX,NY,NZ,D (normalised data coordinates) or PX,PY,PZ,NX,NY,NZ (world: a "
                                  "point, then the normal of the side kept), got \"" + text + "\"");
    std::vector<float> v;
    for (const auto& part : parts) v.push_back(parseFloat(option, part));
    const bool data = v.size() == 4;
    const glm::vec3 normal = data ? glm::vec3(v[0], v[1], v[2]) : glm::vec3(v[3], v[4], v[5]);
    if (normal == glm::vec3(0.0f)) throw UsageError(option + ": the normal must be non-zero, got \"" + text + "\"");
    // n . p + d >= 0 is the plane through -d n / |n|^2 with normal n.
    const glm::vec3 point = data ? -v[3] * normal / glm::dot(normal, normal) : glm::vec3(v[0], v[1], v[2]);
    return {{point, normal}, data ? sss::CropSpace::Data : sss::CropSpace::World};
}

void addClipPlanes(const std::string& option, const std::vector<std::string>& texts, sss::VolumeClip& clip) {
    for (std::size_t i = 0; i < texts.size(); ++i) {
        const ParsedClipPlane parsed = parseClipPlane(option, texts[i]);
        if (i > 0 && parsed.space != clip.planeSpace)
            throw UsageError(option + ": give every plane in one form, NX,NY,NZ,D (data) or PX,PY,PZ,NX,NY,NZ (world); "
                                      "\"" + texts[i] + "\" differs from \"" + texts[0] + "\"");
        clip.planeSpace = parsed.space;
        clip.planes.push_back(parsed.plane);
    }
}

std::pair<glm::vec3, glm::vec3> parseCrop(const std::string& option, const std::string& text, sss::CropSpace space) {
    const bool data = space == sss::CropSpace::Data;
    const std::vector<float> v =
        parseSix(option, text, data ? "X0,Y0,Z0,X1,Y1,Z1 (normalised data coordinates)" : "X0,Y0,Z0,X1,Y1,Z1 (world)");
    const glm::vec3 lo(v[0], v[1], v[2]), hi(v[3], v[4], v[5]);
    for (int a = 0; a < 3; ++a)
        if (!((!data || (lo[a] >= 0.0f && hi[a] <= 1.0f)) && lo[a] < hi[a]))
            throw UsageError(option + ": each axis needs " + (data ? "0 <= min < max <= 1" : "min < max") + ", got \"" +
                             text + "\"");
    return {lo, hi};
}

glm::ivec3 parseDims(const std::string& option, const std::string& text) {
    const auto parts = split(text, 'x');
    if (parts.size() != 3) throw UsageError(option + ": expected XxYxZ, got \"" + text + "\"");
    return {parseInt(option, parts[0]), parseInt(option, parts[1]), parseInt(option, parts[2])};
}

fs::path dataDirectory(const std::string& dataDirOption) {
    if (!dataDirOption.empty()) return dataDirOption;
    if (const char* env = std::getenv("SSS_DATA_DIR"); env && *env) return env;
    if (fs::is_directory("../shared/data")) return "../shared/data";
    return {};
}

sss::Mesh loadSceneMesh(const std::string& path, const fs::path& dataDir) {
    const fs::path dirs[] = {dataDir};
    return sss::loadMeshSource(path, dirs);
}

sss::Volume loadSceneVolume(const std::string& path, const fs::path& dataDir, const sss::RawLoadOptions& options) {
    const fs::path dirs[] = {dataDir};
    return sss::loadVolumeSource(path, options, dirs);
}

std::optional<std::pair<double, double>> parseRange(const std::string& option, const std::string& text) {
    const auto parts = split(text, ',');
    if (parts.size() != 2) throw UsageError(option + ": expected LO,HI, got \"" + text + "\"");
    const double lo = parseFloat(option, parts[0]), hi = parseFloat(option, parts[1]);
    if (!(lo < hi)) throw UsageError(option + ": LO must be less than HI, got \"" + text + "\"");
    return std::pair<double, double>(lo, hi);
}

int runReportingErrors(const char* program, const std::function<int()>& body) {
    try {
        return body();
    } catch (const UsageError& e) {
        std::fprintf(stderr, "%s: %s\n", program, e.what());
        return 2;
    } catch (const sss::Error& e) {
        std::fprintf(stderr, "%s: %s\n", program, e.what());
        return e.kind() == sss::ErrorKind::InvalidArgument ? 2 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", program, e.what());
        return 1;
    }
}

}  // namespace examples
