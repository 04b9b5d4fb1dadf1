#include "sss/light.h"

#include "format.h"

#include "sss/error.h"

#include <glm/geometric.hpp>

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
    } else {
        const auto& p = std::get<PointLight>(light);
        if (!isFinite(p.position))
            throw Error(ErrorKind::InvalidArgument,
                        std::string(what) + ": PointLight::position must be finite, got " + str(p.position));
        checkColor(what, "PointLight", p.color, p.intensity);
    }
}

}  // namespace sss
