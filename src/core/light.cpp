#include "sss/light.h"

#include "util/format.h"
#include "core/light_geometry.h"

#include "sss/error.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <cmath>
#include <sstream>
#include <string>

namespace sss {
namespace {

std::string str(glm::vec3 v) { return detail::formatVec(v); }

bool isFinite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void checkColor(std::string_view what, const char* type, glm::vec3 color, float intensity) {
    if (!isFinite(color) || color.x < 0.0f || color.y < 0.0f || color.z < 0.0f)
        throw Error(ErrorKind::InvalidArgument, std::string(what) + ": " + type +
                                                    "::color must be finite and >= 0, got " + str(color));
    if (!std::isfinite(intensity) || intensity < 0.0f) {
        std::ostringstream s;
        s << what << ": " << type << "::intensity must be finite and >= 0, got " << intensity;
        throw Error(ErrorKind::InvalidArgument, s.str());
    }
}

}  // namespace

void validateLight(const Light& light, std::string_view what) {
    if (const auto* d = std::get_if<DirectionalLight>(&light)) {
        const float len = glm::length(d->direction);
        if (!isFinite(d->direction) || !std::isfinite(len) || len <= 0.0f)
            throw Error(ErrorKind::InvalidArgument, std::string(what) +
                                                        ": DirectionalLight::direction must be finite and non-zero, got " +
                                                        str(d->direction));
        checkColor(what, "DirectionalLight", d->color, d->intensity);
    } else if (const auto* p = std::get_if<PointLight>(&light)) {
        if (!isFinite(p->position))
            throw Error(ErrorKind::InvalidArgument,
                        std::string(what) + ": PointLight::position must be finite, got " + str(p->position));
        checkColor(what, "PointLight", p->color, p->intensity);
    } else {
        const auto& s = std::get<SpotLight>(light);
        if (!isFinite(s.position))
            throw Error(ErrorKind::InvalidArgument,
                        std::string(what) + ": SpotLight::position must be finite, got " + str(s.position));
        const float len = glm::length(s.direction);
        if (!isFinite(s.direction) || !std::isfinite(len) || len <= 0.0f)
            throw Error(ErrorKind::InvalidArgument, std::string(what) +
                                                        ": SpotLight::direction must be finite and non-zero, got " +
                                                        str(s.direction));
        if (!(s.coneAngle > 0.0f && s.coneAngle <= 90.0f)) {
            std::ostringstream m;
            m << what << ": SpotLight::coneAngle must be in (0, 90] degrees, got " << s.coneAngle;
            throw Error(ErrorKind::InvalidArgument, m.str());
        }
        if (!(s.falloff >= 0.0f && s.falloff <= 1.0f)) {
            std::ostringstream m;
            m << what << ": SpotLight::falloff must be in [0, 1], got " << s.falloff;
            throw Error(ErrorKind::InvalidArgument, m.str());
        }
        checkColor(what, "SpotLight", s.color, s.intensity);
    }
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
