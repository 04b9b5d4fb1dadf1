#include "volume/light_volume_pass.h"

#include "core/light_geometry.h"
#include "lighting/texture_units.h"
#include "volume/empty_space.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>

namespace sss::detail {

LightVolumePass::LightVolumePass(bool eyePass) : m_eyePass(eyePass) { program(true); }

const gl::Program& LightVolumePass::program(bool chromaticity) {
    std::optional<gl::Program>& p = m_programs[chromaticity ? 1 : 0];
    if (!p)
        p = gl::Program::link({{GL_COMPUTE_SHADER, "volume/light_propagation.comp"}},
                              {{"EYE_PASS", m_eyePass ? "1" : "0"}, {"CHROMATICITY", chromaticity ? "1" : "0"}});
    return *p;
}

void LightVolumePass::run(const LightVolumeMedium& medium, const Light& light, const glm::mat4& model,
                          const LightVolumeSettings& settings, gl::Texture& output) {
    sweep(medium, light, model, settings, output, glm::vec4(1.0f));
}

void LightVolumePass::runEyePass(const LightVolumeMedium& medium, const gl::Texture& litColour,
                                 glm::vec3 viewDirection, const glm::mat4& model, const LightVolumeSettings& settings,
                                 gl::Texture& output) {
    program(true).set("litColour", units::kLitColour);
    litColour.bind(units::kLitColour);
    // Light travelling towards the viewer; nothing enters from behind the volume.
    sweep(medium, DirectionalLight{.direction = -viewDirection}, model, settings, output,
          glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
}

void LightVolumePass::sweep(const LightVolumeMedium& medium, const Light& worldLight, const glm::mat4& model,
                            const LightVolumeSettings& settings, gl::Texture& output, glm::vec4 outside) {
    const GpuVolume& volume = medium.volume;
    const glm::ivec3 dims = lightVolumeDims(volume.dims, settings.resolutionScale);
    if (!output || output.size() != dims) {
        output = gl::Texture::create3D(GL_RGBA16F, dims, m_eyePass ? "eye-pass volume" : "light volume");
    }
    // The light in the volume's model space, where the propagation works. The volume holds what
    // the medium lets through from the light's position; a spot light's cone scales the light
    // where it is shaded (lights.glsl), so here it propagates like a point light.
    const glm::mat4 toModel = glm::inverse(model);
    Light light = worldLight;
    if (auto* d = std::get_if<DirectionalLight>(&light))
        d->direction = glm::normalize(glm::mat3(toModel) * glm::normalize(d->direction));
    else
        light = PointLight{.position = glm::vec3(toModel * glm::vec4(*lightPosition(worldLight), 1.0f))};

    const std::vector<LightSweep> sweeps = planLightSweeps(light, volume.box, dims);
    const ChromaticityCone cone = chromaticityCone(settings.anisotropy);

    // The eye pass carries colour whatever the settings say.
    const gl::Program& p = program(settings.chromaticity || m_eyePass);
    p.set("volumeTexture", 0);
    p.set("transferFunction", 1);
    p.set("previousSlice", 2);
    p.set("lightVolume", 0);   // image units
    p.set("currentSlice", 1);
    p.set("occupiedNeighbourhoods", 3);
    p.set("transferFunctionEntries", static_cast<float>(medium.transferFunction.size().x));
    p.set("valueScaleOffset", volume.valueScaleOffset);
    p.set("lightVolumeDims", dims);
    const glm::vec3 voxelSize = volume.box.size() / glm::vec3(dims);
    p.set("voxelSize", voxelSize);
    p.set("boxMin", volume.box.min);
    p.set("referenceLength", volume.voxelLength);
    if (const auto* d = std::get_if<DirectionalLight>(&light)) {
        p.set("isPointLight", 0);
        p.set("lightDirection", d->direction);
    } else {
        p.set("isPointLight", 1);
        p.set("lightPosition", *lightPosition(light));
    }
    p.set("coneTangent", cone.tangent);
    p.set("coneWeights", glm::vec2(cone.centreWeight, cone.ringWeight));
    p.set("skipEmpty", medium.occupiedNeighbourhoods ? 1 : 0);
    p.set("dataDims", volume.dims);
    p.set("brickVoxels", kBrickVoxels);
    p.set("textureToBrick", textureToBrick(volume.dims));

    volume.texture.bind(0);
    medium.transferFunction.bind(1);
    // Unit 3 always holds a 3D texture, so the sampler validates with skipping off as well.
    (medium.occupiedNeighbourhoods ? *medium.occupiedNeighbourhoods : volume.texture).bind(3);
    output.bindImage(0, GL_READ_WRITE);
    p.use();
    const float unlit[4] = {outside.r, outside.g, outside.b, outside.a};
    for (size_t s = 0; s < sweeps.size(); ++s) {
        const LightSweep& sweep = sweeps[s];
        const int u = (sweep.axis + 1) % 3, v = (sweep.axis + 2) % 3;
        const glm::ivec2 sliceSize(dims[u], dims[v]);
        for (gl::Texture& slice : m_slices) {
            if (!slice || glm::ivec2(slice.size()) != sliceSize) {
                slice = gl::Texture::create2D(GL_RGBA16F, sliceSize.x, sliceSize.y, "light volume slice");
                slice.setWrap(GL_CLAMP_TO_BORDER);  // what enters from outside the volume
            }
            slice.setBorderColor(outside);
        }
        // The sweep frame: u and v across a slice, w along the sweep (towards -axis if reversed).
        glm::ivec3 origin(0), stepU(0), stepV(0), stepW(0);
        stepU[u] = 1;
        stepV[v] = 1;
        stepW[sweep.axis] = sweep.reversed ? -1 : 1;
        origin[sweep.axis] = sweep.reversed ? dims[sweep.axis] - 1 : 0;
        glm::mat3 dataToSweep(0.0f);  // column = data axis, row = sweep axis
        dataToSweep[u][0] = 1.0f;
        dataToSweep[v][1] = 1.0f;
        dataToSweep[sweep.axis][2] = sweep.reversed ? -1.0f : 1.0f;
        p.set("sliceDims", glm::ivec3(dims[u], dims[v], dims[sweep.axis]));
        p.set("voxelOrigin", origin);
        p.set("voxelStepU", stepU);
        p.set("voxelStepV", stepV);
        p.set("voxelStepW", stepW);
        p.set("dataToSweep", dataToSweep);
        p.set("sweepVoxelSize", glm::vec3(voxelSize[u], voxelSize[v], voxelSize[sweep.axis]));
        p.set("sweepWeight", sweep.weight);
        p.set("accumulate", (!sweep.pyramid && s > 0) ? 1 : 0);
        p.set("pyramidMask", sweep.pyramid ? 1 : 0);
        glClearTexImage(m_slices[0].id(), 0, GL_RGBA, GL_FLOAT, unlit);
        const glm::ivec3 group = p.workGroupSize();
        const auto groupsX = static_cast<GLuint>((sliceSize.x + group.x - 1) / group.x);
        const auto groupsY = static_cast<GLuint>((sliceSize.y + group.y - 1) / group.y);
        for (int w = sweep.firstSlice; w < dims[sweep.axis]; ++w) {
            const gl::Texture& previous = m_slices[(w - sweep.firstSlice) % 2];
            const gl::Texture& current = m_slices[(w - sweep.firstSlice + 1) % 2];
            previous.bind(2);
            current.bindImage(1, GL_WRITE_ONLY);
            p.set("sliceIndex", w);
            glDispatchCompute(groupsX, groupsY, 1);
            // The next slice samples this one; the ray caster samples the volume afterwards.
            glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
        }
    }
    glUseProgram(0);
}

}  // namespace sss::detail
