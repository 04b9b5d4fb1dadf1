#include "volume/gradient_volume_pass.h"

namespace sss::detail {

GradientVolumePass::GradientVolumePass()
    : m_program(gl::Program::link({{GL_COMPUTE_SHADER, "volume/gradient.comp"}})) {}

gl::Texture GradientVolumePass::run(const GpuVolume& volume) const {
    const GLenum format = gradientFormatFor(volume);
    const GradientEncoding encoding = gradientEncoding(format);
    gl::Texture gradients = gl::Texture::create3D(format, volume.dims, "gradient volume");
    gradients.setFilter(GL_LINEAR, GL_LINEAR);
    gradients.setWrap(GL_CLAMP_TO_EDGE);
    const gl::Program& p = m_program;
    p.set("volumeTexture", 0);
    p.set("volumeDims", volume.dims);
    p.set("encodeScale", encoding.scale);
    p.set("encodeOffset", encoding.offset);
    p.set("storeValues", gradientVolumeHoldsValues(volume) ? 1 : 0);
    volume.texture.bind(0);
    gradients.bindImage(0, GL_WRITE_ONLY);
    p.use();
    glDispatchCompute(static_cast<GLuint>((volume.dims.x + 3) / 4), static_cast<GLuint>((volume.dims.y + 3) / 4),
                      static_cast<GLuint>((volume.dims.z + 3) / 4));
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    glUseProgram(0);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, format);
    return gradients;
}

}  // namespace sss::detail
