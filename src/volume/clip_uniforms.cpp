#include "volume/clip_uniforms.h"

#include "core/volume_clip_space.h"

#include <glm/common.hpp>

#include <string>

namespace sss::detail {

void setClipUniforms(const gl::Program& p, const VolumeClip* clip, const glm::mat4& model, const Bounds& box) {
    const TextureClip t = clip ? textureClip(*clip, model, box) : TextureClip{};
    p.set("clipActive", t.active ? 1 : 0);
    p.set("clipLight", t.active && !clip->clippedMatterCastsShadows ? 1 : 0);
    p.set("clipPlaneCount", static_cast<int>(t.planes.size()));
    for (size_t i = 0; i < t.planes.size(); ++i) p.set("clipPlanes[" + std::to_string(i) + "]", glm::vec4(t.planes[i]));
    // Open faces (infinite in TextureClip) as large finite values: GLSL has no infinity literal.
    constexpr double far = 1e30;
    p.set("cropMin", glm::vec3(glm::clamp(t.cropMin, -far, far)));
    p.set("cropMax", glm::vec3(glm::clamp(t.cropMax, -far, far)));
}

}  // namespace sss::detail
