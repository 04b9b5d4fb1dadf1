#include "lighting/light_uniforms.h"

#include "sss/error.h"

#include <glm/geometric.hpp>

#include <string>

namespace sss::detail {

void validateLights(const std::vector<Light>& lights, std::string_view owner) {
    if (lights.size() > static_cast<size_t>(kMaxLights))
        throw Error(ErrorKind::InvalidArgument, std::string(owner) + ": at most " + std::to_string(kMaxLights) +
                                                    " lights are supported, got " + std::to_string(lights.size()));
    for (size_t i = 0; i < lights.size(); ++i)
        validateLight(lights[i], std::string(owner) + " light " + std::to_string(i));
}

void setLightUniforms(const gl::Program& program, const std::vector<Light>& lights) {
    program.set("lightCount", static_cast<int>(lights.size()));
    for (size_t i = 0; i < lights.size(); ++i) {
        const std::string index = "[" + std::to_string(i) + "]";
        if (const auto* d = std::get_if<DirectionalLight>(&lights[i])) {
            program.set("lightVector" + index, glm::vec4(-glm::normalize(d->direction), 0.0f));
            program.set("lightRadiance" + index, d->color * d->intensity);
        } else {
            const auto& p = std::get<PointLight>(lights[i]);
            program.set("lightVector" + index, glm::vec4(p.position, 1.0f));
            program.set("lightRadiance" + index, p.color * p.intensity);
        }
    }
}

}  // namespace sss::detail
