#include "lighting/shadows.h"

#include "lighting/texture_units.h"

#include "lighting/light_uniforms.h"

#include <string>

namespace sss::detail {

void setVolumeShadowUniforms(const gl::Program& program, const VolumeShadows* shadows, std::size_t lightCount) {
    const bool enabled = shadows && shadows->lightVolumes && shadows->lightVolumes->size() >= lightCount;
    program.set("volumeShadowEnabled", enabled ? 1 : 0);
    // Samplers keep their own units even when unused: two samplers of different types on one
    // unit (these default to unit 0) make every draw fail validation.
    for (int i = 0; i < kMaxLights; ++i)
        program.set("volumeShadowLight[" + std::to_string(i) + "]", units::kVolumeShadows + i);
    if (!enabled) return;
    program.set("volumeShadowWorldToTexture", shadows->worldToTexture);
    for (std::size_t i = 0; i < lightCount; ++i) {
        (*shadows->lightVolumes)[i].bind(static_cast<GLuint>(units::kVolumeShadows + static_cast<int>(i)));
    }
}

}  // namespace sss::detail
