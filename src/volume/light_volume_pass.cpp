#include "volume/light_volume_pass.h"

#include "light_geometry.h"
#include "lighting/texture_units.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace sss::detail {
namespace {

constexpr float kPi = 3.14159265358979f;

float henyeyGreenstein(float cosine, float g) {
    const float denominator = 1.0f + g * g - 2.0f * g * cosine;
    return (1.0f - g * g) / (4.0f * kPi * denominator * std::sqrt(denominator));
}

// Sorted component magnitudes with their axes, largest first.
std::array<std::pair<float, int>, 3> rankAxes(glm::vec3 magnitude) {
    std::array<std::pair<float, int>, 3> ranked{{{magnitude.x, 0}, {magnitude.y, 1}, {magnitude.z, 2}}};
    std::sort(ranked.begin(), ranked.end(), [](auto a, auto b) { return a.first > b.first; });
    return ranked;
}

}  // namespace

float chromaticityConeAngle(float g) {
    constexpr float maxAngle = 60.0f * kPi / 180.0f;
    if (g <= 1e-3f) return maxAngle;  // isotropic or backward: widest blur
    // Inverting the HG sampling formula at xi = 1/2 gives the cone holding half the energy.
    const float k = (1.0f - g * g);
    const float cosine = (1.0f + g * g - k * k) / (2.0f * g);
    return std::min(std::acos(std::clamp(cosine, -1.0f, 1.0f)), maxAngle);
}

std::vector<LightSweep> planLightSweeps(const Light& light, const GpuVolume& volume, glm::ivec3 dims) {
    const glm::vec3 voxelSize = volume.box.size() / glm::vec3(dims);
    if (const auto* directional = std::get_if<DirectionalLight>(&light)) {
        // Rank axes by how far the light moves per slice, in voxels, so the previous-slice lookup
        // on the main axis stays within one texel even for anisotropic voxels.
        const glm::vec3 d = glm::normalize(directional->direction) / voxelSize;
        const auto ranked = rankAxes(glm::abs(d) / glm::length(d));
        const float w1 = ranked[0].first - ranked[2].first, w2 = ranked[1].first - ranked[2].first;
        const float sum = w1 + w2;
        std::vector<LightSweep> sweeps{{ranked[0].second, d[ranked[0].second] < 0, sum > 0 ? w1 / sum : 0.5f}};
        if (sum <= 0 || w2 > 0)
            sweeps.push_back({ranked[1].second, d[ranked[1].second] < 0, sum > 0 ? w2 / sum : 0.5f});
        return sweeps;
    }
    // Point or spot light: how far outside the box it is along each axis, in half-extents.
    const glm::vec3 position = *lightPosition(light);
    const glm::vec3 offset = position - volume.box.center();
    const glm::vec3 ratio = glm::abs(offset) / (0.5f * volume.box.size());
    const auto ranked = rankAxes(ratio);
    if (ranked[0].first <= 1.0f) {
        // Inside the box or on its boundary: sweep outward from the light in all six directions.
        std::vector<LightSweep> sweeps;
        for (int axis = 0; axis < 3; ++axis) {
            const float slice = (position[axis] - volume.box.min[axis]) / voxelSize[axis] - 0.5f;
            // Each sweep starts at the first slice beyond the light, so nothing it passes through
            // lies behind the light.
            const int forward = std::clamp(static_cast<int>(std::ceil(slice)), 0, dims[axis] - 1);
            const int backward = std::clamp(static_cast<int>(std::ceil(static_cast<float>(dims[axis] - 1) - slice)), 0, dims[axis] - 1);
            sweeps.push_back({axis, false, 1.0f, forward, true});
            sweeps.push_back({axis, true, 1.0f, backward, true});
        }
        return sweeps;
    }
    // Outside: the light travels into the box through the face(s) it is beyond. A second axis
    // is valid only while the light is beyond that face too; its weight reaches 0 as it stops.
    const float floor3 = std::max(1.0f, ranked[2].first);
    const float w1 = ranked[0].first - floor3, w2 = std::max(0.0f, ranked[1].first - floor3);
    const float sum = w1 + w2;
    std::vector<LightSweep> sweeps{{ranked[0].second, offset[ranked[0].second] > 0, sum > 0 ? w1 / sum : 1.0f}};
    if (w2 > 0) sweeps.push_back({ranked[1].second, offset[ranked[1].second] > 0, w2 / sum});
    return sweeps;
}

glm::ivec3 lightVolumeDims(glm::ivec3 volumeDims, float scale) {
    return glm::max(glm::ivec3(1), glm::ivec3(glm::round(glm::vec3(volumeDims) * scale)));
}

LightVolumePass::LightVolumePass(bool eyePass)
    : m_program(gl::Program::link({{GL_COMPUTE_SHADER, "volume/light_propagation.comp"}},
                                  {{"EYE_PASS", eyePass ? "1" : "0"}})),
      m_eyePass(eyePass) {}

void LightVolumePass::run(const GpuVolume& volume, const gl::Texture& transferFunction, const Light& light,
                          const glm::mat4& model, const LightVolumeSettings& settings, gl::Texture& output) {
    sweep(volume, transferFunction, light, model, settings, output, glm::vec4(1.0f));
}

void LightVolumePass::runEyePass(const GpuVolume& volume, const gl::Texture& transferFunction,
                                 const gl::Texture& litColour, glm::vec3 viewDirection, const glm::mat4& model,
                                 const LightVolumeSettings& settings, gl::Texture& output) {
    m_program.set("litColour", units::kLitColour);
    litColour.bind(units::kLitColour);
    // Light travelling towards the viewer; nothing enters from behind the volume.
    sweep(volume, transferFunction, DirectionalLight{.direction = -viewDirection}, model, settings, output,
          glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
}

void LightVolumePass::sweep(const GpuVolume& volume, const gl::Texture& transferFunction, const Light& worldLight,
                            const glm::mat4& model, const LightVolumeSettings& settings, gl::Texture& output,
                            glm::vec4 outside) {
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

    const std::vector<LightSweep> sweeps = planLightSweeps(light, volume, dims);
    const float cone = chromaticityConeAngle(settings.anisotropy);
    const float centreWeight = henyeyGreenstein(1.0f, settings.anisotropy);
    const float ringWeight = henyeyGreenstein(std::cos(cone), settings.anisotropy);
    const float norm = centreWeight + 8.0f * ringWeight;

    const gl::Program& p = m_program;
    p.set("volumeTexture", 0);
    p.set("transferFunction", 1);
    p.set("previousSlice", 2);
    p.set("lightVolume", 0);   // image units
    p.set("currentSlice", 1);
    p.set("transferFunctionEntries", static_cast<float>(transferFunction.size().x));
    p.set("valueScaleOffset", volume.valueScaleOffset);
    p.set("lightVolumeDims", dims);
    p.set("voxelSize", volume.box.size() / glm::vec3(dims));
    p.set("boxMin", volume.box.min);
    p.set("referenceLength", volume.voxelLength);
    if (const auto* d = std::get_if<DirectionalLight>(&light)) {
        p.set("isPointLight", 0);
        p.set("lightDirection", d->direction);
    } else {
        p.set("isPointLight", 1);
        p.set("lightPosition", *lightPosition(light));
    }
    p.set("coneTangent", std::tan(cone));
    p.set("coneWeights", glm::vec2(centreWeight, ringWeight) / norm);


    volume.texture.bind(0);
    transferFunction.bind(1);
    output.bindImage(0, GL_READ_WRITE);
    m_program.use();
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
        p.set("sweepAxes", glm::ivec3(u, v, sweep.axis));
        p.set("sweepFlip", glm::ivec3(0, 0, sweep.reversed ? 1 : 0));
        p.set("sweepWeight", sweep.weight);
        p.set("accumulate", (!sweep.pyramid && s > 0) ? 1 : 0);
        p.set("pyramidMask", sweep.pyramid ? 1 : 0);
        glClearTexImage(m_slices[0].id(), 0, GL_RGBA, GL_FLOAT, unlit);
        const GLuint groupsX = static_cast<GLuint>((sliceSize.x + 7) / 8), groupsY = static_cast<GLuint>((sliceSize.y + 7) / 8);
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
