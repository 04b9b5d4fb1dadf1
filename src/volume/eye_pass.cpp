#include "volume/eye_pass.h"

#include "lighting/light_uniforms.h"
#include "lighting/texture_units.h"

#include <string>

namespace sss::detail {

void EyePass::run(const EyePassInputs& in) {
    const glm::ivec3 dims = in.lightVolumes.front().size();
    const bool meshShadows = castsMeshShadows(in.meshShadows, in.lights.size());
    const LitColourVariant variant{in.lights.size(), in.settings.reconstruction, meshShadows};
    const auto defines = [&]() -> ShaderDefines {
        return {{"LIGHT_COUNT", std::to_string(in.lights.size())},
                {"CUBIC_RECONSTRUCTION", cubicReconstructionDefine(in.settings.reconstruction)},
                {"MESH_SHADOWS", meshShadows ? "1" : "0"}};
    };
    const gl::Program& p = gl::linkedOnce(m_litColourPrograms, variant, "volume/lit_colour.comp", defines);
    if (!m_litColour || m_litColour.size() != dims)
        m_litColour = gl::Texture::create3D(GL_RGBA16F, dims, "eye pass: scattered light");
    p.set("volumeTexture", 0);
    p.set("transferFunction", 1);
    p.set("transferFunctionEntries", static_cast<float>(in.transferFunction.size().x));
    p.set("valueScaleOffset", in.volume.valueScaleOffset);
    p.set("litColour", 0);  // image unit
    p.set("dims", dims);
    p.set("boxMin", in.volume.box.min);
    p.set("voxelSize", in.volume.box.size() / glm::vec3(dims));
    p.set("modelToWorld", in.model);
    p.set("ambientStrength", in.ambientStrength);
    p.set("diffuseStrength", in.diffuseStrength);
    setLightUniforms(p, in.lights);
    if (meshShadows) setMeshVisibilityUniforms(p, *in.meshShadows, in.lights);
    for (size_t i = 0; i < in.lights.size(); ++i) {
        p.set("lightVolumes[" + std::to_string(i) + "]", units::kLightVolumes + static_cast<int>(i));
        in.lightVolumes[i].bind(static_cast<GLuint>(units::kLightVolumes + static_cast<int>(i)));
    }
    in.volume.texture.bind(0);
    in.transferFunction.bind(1);
    m_litColour.bindImage(0, GL_WRITE_ONLY);
    p.use();
    glDispatchCompute(static_cast<GLuint>((dims.x + 3) / 4), static_cast<GLuint>((dims.y + 3) / 4),
                      static_cast<GLuint>((dims.z + 3) / 4));
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    glUseProgram(0);
    if (!m_sweep) m_sweep.emplace(true);
    m_sweep->runEyePass({.volume = in.volume,
                         .transferFunction = in.transferFunction,
                         .occupiedNeighbourhoods = in.occupiedNeighbourhoods,
                         .clip = in.clip},
                        m_litColour, in.viewDirection, in.model, in.settings,
                        m_eyeVolume);
}

void EyePass::release() {
    m_litColour = {};
    m_eyeVolume = {};
}

}  // namespace sss::detail
