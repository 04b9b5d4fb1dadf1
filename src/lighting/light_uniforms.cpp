#include "lighting/light_uniforms.h"

#include "core/light_geometry.h"

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
        if (const auto* d = std::get_if<DirectionalLight>(&lights[i]))
            program.set("lightVector" + index, glm::vec4(-glm::normalize(d->direction), 0.0f));
        else
            program.set("lightVector" + index, glm::vec4(*lightPosition(lights[i]), 1.0f));
        program.set("lightRadiance" + index, lightRadiance(lights[i]));
        setSpotConeUniforms(program, static_cast<int>(i), lights[i]);
    }
}

void setSpotConeUniforms(const gl::Program& program, int index, const Light& light) {
    const std::string i = "[" + std::to_string(index) + "]";
    const auto* s = std::get_if<SpotLight>(&light);
    // Cosines below -1: every direction is inside the "inner cone", so the factor is exactly 1.
    program.set("lightSpotAxis" + i, s ? glm::normalize(s->direction) : glm::vec3(0.0f));
    program.set("lightSpotCosines" + i, s ? spotConeCosines(*s) : glm::vec2(-2.0f));
}

}  // namespace sss::detail
