#include "sss/light.h"

#include "util/format.h"
#include "core/light_geometry.h"

#include "sss/error.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace sss {
namespace {

std::string str(glm::vec3 v) { return detail::formatVec(v); }

bool isFinite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

[[noreturn]] void fail(std::string_view what, const char* type, const char* field, const std::string& reason) {
    throw Error(ErrorKind::InvalidArgument, type, field, reason, std::string(what));
}

template <class T>
std::string text(const T& value) {
    std::ostringstream s;
    s << value;
    return s.str();
}

void checkColor(std::string_view what, const char* type, glm::vec3 color, float intensity) {
    if (!isFinite(color) || color.x < 0.0f || color.y < 0.0f || color.z < 0.0f)
        fail(what, type, "color", "must be finite and >= 0, got " + str(color));
    if (!std::isfinite(intensity) || intensity < 0.0f)
        fail(what, type, "intensity", "must be finite and >= 0, got " + text(intensity));
}

void checkDirection(std::string_view what, const char* type, glm::vec3 direction) {
    const float len = glm::length(direction);
    if (!isFinite(direction) || !std::isfinite(len) || len <= 0.0f)
        fail(what, type, "direction", "must be finite and non-zero, got " + str(direction));
}

}  // namespace

void validateLight(const Light& light, std::string_view what) {
    if (const auto* d = std::get_if<DirectionalLight>(&light)) {
        checkDirection(what, "DirectionalLight", d->direction);
        checkColor(what, "DirectionalLight", d->color, d->intensity);
    } else if (const auto* p = std::get_if<PointLight>(&light)) {
        if (!isFinite(p->position)) fail(what, "PointLight", "position", "must be finite, got " + str(p->position));
        checkColor(what, "PointLight", p->color, p->intensity);
    } else {
        const auto& s = std::get<SpotLight>(light);
        if (!isFinite(s.position)) fail(what, "SpotLight", "position", "must be finite, got " + str(s.position));
        checkDirection(what, "SpotLight", s.direction);
        if (!(s.coneAngle > 0.0f && s.coneAngle <= 90.0f))
            fail(what, "SpotLight", "coneAngle", "must be in (0, 90] degrees, got " + text(s.coneAngle));
        if (!(s.falloff >= 0.0f && s.falloff <= 1.0f))
            fail(what, "SpotLight", "falloff", "must be in [0, 1], got " + text(s.falloff));
        checkColor(what, "SpotLight", s.color, s.intensity);
    }
}

std::vector<Light> detail::withUnitRadiance(std::vector<Light> lights) {
    for (Light& light : lights)
        std::visit(
            [](auto& l) {
                l.color = glm::vec3(1.0f);
                l.intensity = 1.0f;
            },
            light);
    return lights;
}

std::vector<Light> detail::asLightVolumeLights(std::vector<Light> lights) {
    lights = withUnitRadiance(std::move(lights));
    for (Light& light : lights)
        if (const auto* spot = std::get_if<SpotLight>(&light)) light = PointLight{.position = spot->position};
    return lights;
}

std::optional<glm::vec3> detail::commonRadianceScale(const std::vector<Light>& before, const std::vector<Light>& now) {
    if (before.size() != now.size() || withUnitRadiance(before) != withUnitRadiance(now)) return std::nullopt;
    // Each channel's factor from the light brightest in it before; every light must agree.
    glm::vec3 scale(0.0f), brightest(0.0f);
    for (size_t i = 0; i < before.size(); ++i) {
        const glm::vec3 was = lightRadiance(before[i]), is = lightRadiance(now[i]);
        for (int c = 0; c < 3; ++c)
            if (was[c] > brightest[c]) {
                brightest[c] = was[c];
                scale[c] = is[c] / was[c];
            }
    }
    constexpr float kTolerance = 1e-5f;  // relative: float noise in a colour picked again
    for (size_t i = 0; i < before.size(); ++i) {
        const glm::vec3 expected = scale * lightRadiance(before[i]), is = lightRadiance(now[i]);
        for (int c = 0; c < 3; ++c)
            if (std::abs(is[c] - expected[c]) > kTolerance * std::max(is[c], expected[c])) return std::nullopt;
    }
    return scale;
}

glm::vec2 detail::spotConeCosines(const SpotLight& light) {
    const float outerAngle = glm::radians(light.coneAngle);
    return {std::cos(outerAngle), std::cos(outerAngle * (1.0f - light.falloff))};
}

float spotConeFactor(const SpotLight& light, float cosAngle) {
    const glm::vec2 cosines = detail::spotConeCosines(light);
    const float cosOuter = cosines.x, cosInner = cosines.y;
    if (cosAngle <= cosOuter) return 0.0f;
    if (cosAngle >= cosInner) return 1.0f;  // also the hard edge, where cosInner == cosOuter
    const float t = (cosAngle - cosOuter) / (cosInner - cosOuter);
    return t * t * (3.0f - 2.0f * t);
}

}  // namespace sss
