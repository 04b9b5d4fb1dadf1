#include "volume/ray_cast_pass.h"

#include "volume/clip_uniforms.h"
#include "volume/composite_over.h"
#include "core/light_geometry.h"
#include "volume/fluence_cache.h"
#include "volume/gradient_volume_pass.h"
#include "lighting/texture_units.h"
#include "sss/error.h"

#include "lighting/camera_uniforms.h"
#include "lighting/light_uniforms.h"

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <limits>
#include <cmath>
#include <string>
#include <variant>

namespace sss::detail {

bool usesGradient(VolumeShading s) { return s == VolumeShading::Gradient || s == VolumeShading::ScatteringGradient; }

bool usesLightVolume(VolumeShading s) {
    return s == VolumeShading::Scattering || s == VolumeShading::ScatteringGradient;
}

bool usesComputeRayCaster(RayCaster caster, bool softwareDevice) {
    if (caster != RayCaster::Auto) return caster == RayCaster::Compute;
    // Measured (benchmarks/README.md, "Fragment or compute"): on an H200 compute is 7-17 times
    // faster; on llvmpipe the fragment path is as fast or faster.
    return !softwareDevice;
}

PixelRect screenRectangle(const glm::mat4& modelViewProjection, const Bounds& box, glm::ivec2 viewport) {
    const PixelRect whole{{0, 0}, viewport};
    glm::vec2 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
    for (int i = 0; i < 8; ++i) {
        const glm::vec4 corner((i & 1) ? box.max.x : box.min.x, (i & 2) ? box.max.y : box.min.y,
                               (i & 4) ? box.max.z : box.min.z, 1.0f);
        const glm::vec4 clip = modelViewProjection * corner;
        if (clip.w <= 1e-6f * std::abs(clip.z)) return whole;  // behind (or level with) the eye
        const glm::vec2 window = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(viewport);
        lo = glm::min(lo, window);
        hi = glm::max(hi, window);
    }
    const glm::ivec2 first = glm::max(glm::ivec2(glm::floor(lo)) - 1, glm::ivec2(0));
    const glm::ivec2 last = glm::min(glm::ivec2(glm::ceil(hi)) + 1, viewport);
    return {first, glm::max(last - first, glm::ivec2(0))};
}

bool usesEyePass(const VolumeRenderOptions& o) {
    return o.eyePass && usesLightVolume(o.shading) && o.model == VolumeModel::Paper;
}

bool usesScatteringCache(const VolumeRenderOptions& o) {
    return o.multipleScatteringCache && usesLightVolume(o.shading) && o.model == VolumeModel::Physical;
}

bool cacheEvaluatedPerSample(CacheViewEvaluation evaluation, bool softwareDevice, double cells, double pixels) {
    if (evaluation != CacheViewEvaluation::Auto) return evaluation == CacheViewEvaluation::PerSample;
    return softwareDevice && cells > kCacheCellsPerPixel * pixels;
}

namespace {

glm::mat3 normalMatrix(const glm::mat4& model) { return glm::transpose(glm::inverse(glm::mat3(model))); }

// N^T N for the model's normal matrix N: diagonal (to float rounding) when the model scales
// along the volume's own axes, then turns (a uniform scale included).
bool diagonalMetric(const glm::mat4& model) {
    const glm::mat3 n = normalMatrix(model);
    const glm::mat3 metric = glm::transpose(n) * n;
    const float largest = std::max({metric[0][0], metric[1][1], metric[2][2]});
    for (int column = 0; column < 3; ++column)
        for (int row = 0; row < 3; ++row)
            if (row != column && std::abs(metric[column][row]) > 1e-6f * largest) return false;
    return true;
}

}  // namespace

RayCastVariant RayCastVariant::of(const VolumeRenderOptions& options, const RayCastScene& scene) {
    const std::vector<Light>& lights = scene.lights;
    RayCastVariant v;
    v.shading = options.shading;
    v.emptySpaceSkipping = options.emptySpaceSkipping;
    v.lightCount = lights.size();
    v.eyePass = usesEyePass(options);
    v.gradients = scene.gradients;
    v.preintegration = scene.preintegration;
    v.directionalLightsOnly = std::all_of(lights.begin(), lights.end(), [](const Light& light) {
        return std::holds_alternative<DirectionalLight>(light);
    });
    const float shininess = options.shininess;
    if (usesGradient(options.shading) && shininess >= 1.0f && shininess <= 256.0f && shininess == std::floor(shininess))
        v.integerShininess = static_cast<int>(shininess);
    // Only where gradients shade: elsewhere a model change would recompile the caster for nothing.
    v.diagonalGradientMetric = !usesGradient(options.shading) || diagonalMetric(scene.model);
    v.clipped = scene.clip != nullptr;
    v.meshShadows = usesLightVolume(options.shading) && castsMeshShadows(scene.meshShadows, lights.size());
    v.physicalModel = usesLightVolume(options.shading) && options.model == VolumeModel::Physical;
    v.compute = usesComputeRayCaster(options.rayCaster, scene.softwareDevice);
    v.scatteringCache = usesScatteringCache(options);
    v.cachePerSample = v.scatteringCache && scene.cachePerSample;
    v.reconstruction = options.reconstruction;
    return v;
}

RayCastPass::RayCastPass(const RayCastVariant& variant)
    : m_variant(variant),
      m_program(gl::Program::link(variant.compute ? std::initializer_list<gl::ShaderStage>{{GL_COMPUTE_SHADER,
                                                                                         "volume/ray_cast.comp"}}
                                                  : std::initializer_list<gl::ShaderStage>{
                                                        {GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                                        {GL_FRAGMENT_SHADER, "volume/ray_cast.frag"}},
                                  {{"SHADING_GRADIENT", usesGradient(variant.shading) ? "1" : "0"},
                                   {"SHADING_SCATTERING", usesLightVolume(variant.shading) ? "1" : "0"},
                                   {"EMPTY_SPACE_SKIPPING", variant.emptySpaceSkipping ? "1" : "0"},
                                   {"LIGHT_COUNT", std::to_string(variant.lightCount)},
                                   {"EYE_PASS", variant.eyePass ? "1" : "0"},
                                   {"GRADIENT_VOLUME", variant.gradients != GradientSource::OnTheFly ? "1" : "0"},
                                   {"VALUES_IN_GRADIENTS", variant.gradients == GradientSource::VolumeWithValues ? "1" : "0"},
                                   {"PREINTEGRATED", variant.preintegration ? "1" : "0"},
                                   {"DIRECTIONAL_LIGHTS_ONLY", variant.directionalLightsOnly ? "1" : "0"},
                                   {"INTEGER_SHININESS", std::to_string(variant.integerShininess)},
                                   {"DIAGONAL_GRADIENT_METRIC", variant.diagonalGradientMetric ? "1" : "0"},
                                   {"CLIP", variant.clipped ? "1" : "0"},
                                   {"MESH_SHADOWS", variant.meshShadows ? "1" : "0"},
                                   {"PHYSICAL_MODEL", variant.physicalModel ? "1" : "0"},
                                   {"SCATTERING_CACHE", variant.scatteringCache ? "1" : "0"},
                                   {"CACHE_PER_SAMPLE", variant.cachePerSample ? "1" : "0"},
                                   {"CUBIC_RECONSTRUCTION", cubicReconstructionDefine(variant.reconstruction)}})),
      m_emptyVertexArray(gl::VertexArray::create()) {}

void RayCastPass::run(const RayCastInputs& in) const {
    bindInputs(in);
    if (m_variant.compute) {
        dispatchOverRectangle(in);
        return;
    }
    // Premultiplied "over": the volume's colour in front of what the target already holds.
    drawPremultipliedOver(m_program, m_emptyVertexArray);
}

void RayCastPass::dispatchOverRectangle(const RayCastInputs& in) const {
    const glm::ivec2 viewport(in.target.width(), in.target.height());
    const glm::mat4 modelViewProjection = in.camera.projection(in.aspect) * in.camera.view() * in.model;
    const PixelRect rect = screenRectangle(modelViewProjection, in.volume.box, viewport);
    if (rect.empty()) return;
    const gl::Program& p = m_program;
    p.set("rectOrigin", rect.origin);
    p.set("rectSize", rect.size);
    p.set("viewportSize", glm::vec2(viewport));
    p.set("target", 0);
    glBindImageTexture(0, in.target.colorTextureId(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    p.use();
    const glm::ivec3 group = p.workGroupSize();
    glDispatchCompute(static_cast<GLuint>((rect.size.x + group.x - 1) / group.x),
                      static_cast<GLuint>((rect.size.y + group.y - 1) / group.y), 1);
    // Later passes read the colour as a framebuffer attachment, a texture or a read-back.
    glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                    GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glUseProgram(0);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
}

void RayCastPass::bindInputs(const RayCastInputs& in) const {
    const GpuVolume& volume = in.volume;
    const glm::mat4& model = in.model;
    const std::vector<Light>& lights = in.lights;
    const VolumeRenderOptions& options = in.options;
    const MeshShadowMaps* meshShadows = in.meshShadows;
    const glm::mat4 viewProjection = in.camera.projection(in.aspect) * in.camera.view();
    const float stepLength = options.stepSize * volume.voxelLength;
    const glm::vec3 size = volume.box.size();
    // Enough steps to cross the box diagonally, plus one for the jittered start.
    const float diagonal = std::sqrt(glm::dot(size, size));
    const int maxSteps = static_cast<int>(std::ceil(diagonal / stepLength)) + 2;

    const gl::Program& p = m_program;
    p.set("inverseViewProjection", glm::inverse(viewProjection));
    p.set("worldToModel", glm::inverse(model));
    p.set("volumeTexture", 0);
    p.set("transferFunction", 1);
    p.set("sceneDepth", 2);
    p.set("occupancy", 3);
    p.set("brickVoxels", kBrickVoxels);
    p.set("textureToBrick", textureToBrick(volume.dims));
    p.set("transferFunctionEntries", static_cast<float>(in.transferFunction.size().x));
    p.set("valueScaleOffset", volume.valueScaleOffset);
    p.set("boxMin", volume.box.min);
    p.set("boxMax", volume.box.max);
    setClipUniforms(p, in.clip, model, volume.box);
    p.set("volumeDims", volume.dims);
    p.set("stepLength", stepLength);
    p.set("opacityExponent", options.stepSize);
    p.set("earlyTermination", options.earlyTermination);
    p.set("jitterEnabled", options.jitter ? 1 : 0);
    // Frames anti-aliased with sub-pixel offsets (FrameAccumulator) also get different ray starts,
    // so their mean averages the step's wood grain out as well as the edges; without an offset
    // the jitter is the same every frame (no flicker). The shift is a fixed scramble of the offset.
    const glm::vec2 subpixel = in.camera.subpixelOffset();
    const double scramble = 7548.776662 * std::abs(subpixel.x) + 5698.402910 * std::abs(subpixel.y) +
                            (subpixel.x < 0.0f ? 0.5 : 0.0) + (subpixel.y < 0.0f ? 0.25 : 0.0);
    p.set("jitterShift", static_cast<float>(scramble - std::floor(scramble)));
    p.set("maxSteps", maxSteps);
    if (m_variant.shading != VolumeShading::EmissionAbsorption) {
        p.set("modelToWorld", model);
        // Emission adds to the ambient term: both are light-independent fractions of the TF colour.
        // The physical model has neither (single scattering only).
        p.set("ambientStrength", m_variant.physicalModel ? 0.0f : options.ambient + options.emission);
        p.set("diffuseStrength", options.diffuse);
        p.set("phaseG", options.anisotropy);
        setCameraUniforms(p, in.camera);
        setLightUniforms(p, lights);
    }
    if (usesGradient(m_variant.shading)) {
        // The shader's gradient is in value units per voxel along the model axes: scale it to
        // model units (voxels per unit on each axis, so anisotropic boxes get correct normals),
        // point it from high to low values, then take it to world space as a normal.
        const glm::vec3 voxelsPerUnit = glm::vec3(volume.dims) / size;
        const glm::mat3 normalToWorld = normalMatrix(model);
        const glm::mat3 highToLow(-voxelsPerUnit.x, 0.0f, 0.0f, 0.0f, -voxelsPerUnit.y, 0.0f, 0.0f, 0.0f, -voxelsPerUnit.z);
        const glm::mat3 gradientToOutward = normalToWorld * highToLow;
        p.set("gradientToOutward", gradientToOutward);
        p.set("gradientMetric", glm::transpose(gradientToOutward) * gradientToOutward);
        p.set("specularColor", options.specular);
        p.set("shininess", options.shininess);
        p.set("gradientThreshold", options.gradientThreshold);
        if (m_variant.gradients != GradientSource::OnTheFly && in.gradientVolume) {
            p.set("gradientVolume", units::kGradientVolume);
            const GradientEncoding encoding = gradientEncoding(in.gradientVolume->internalFormat());
            p.set("gradientDecode", glm::vec2(encoding.decodeScale(), encoding.decodeOffset()));
            in.gradientVolume->bind(units::kGradientVolume);
        }
    }
    if (usesLightVolume(m_variant.shading)) {
        if (m_variant.meshShadows) setMeshVisibilityUniforms(p, *meshShadows, lights);
        if (m_variant.eyePass && in.eyeVolume) {
            p.set("eyeVolume", units::kEyeVolume);
            p.set("eyePassStrength", options.eyePassStrength);
            in.eyeVolume->bind(units::kEyeVolume);
        }
        p.set("worldToModelDirection", glm::inverse(glm::mat3(model)));
        if (m_variant.scatteringCache && in.cache) {
            if (m_variant.cachePerSample) {
                in.cache->bindSources(p, units::kCacheSources);
                p.set("cacheViewer", modelSpaceViewer(in.camera, model));
            } else {
                p.set("cacheTowardsViewer", units::kCacheTowardsViewer);
                p.set("cacheTowardsViewerSlope", units::kCacheTowardsViewerSlope);
                p.set("cacheTowardsViewerCap", units::kCacheTowardsViewerCap);
                in.cache->towardsViewer().bind(units::kCacheTowardsViewer);
                in.cache->towardsViewerSlope().bind(units::kCacheTowardsViewerSlope);
                in.cache->towardsViewerCap().bind(units::kCacheTowardsViewerCap);
            }
            // The direct light the cache regresses on is weighted as its photons were, and a
            // change of radiance alone that the cache kept scales what it holds.
            const std::vector<float> weights = directLightWeights(in.cache->lights(), model, in.volume.box);
            for (size_t i = 0; i < weights.size(); ++i) p.set("cacheDirectWeight[" + std::to_string(i) + "]", weights[i]);
            p.set("cacheRadianceScale", commonRadianceScale(in.cache->lights(), in.lights).value_or(glm::vec3(1.0f)));
        }
        // Reads the light volume this many texels towards the light and carries the light back
        // through the data (shaders/volume/ray_cast.glsl, shade()).
        p.set("lightVolumeReach", in.lightVolumeReach);
        for (size_t i = 0; i < in.lightVolumes.size(); ++i) {
            const int unit = units::kLightVolumes + static_cast<int>(i);
            p.set("lightVolumes[" + std::to_string(i) + "]", unit);
            in.lightVolumes[i].bind(static_cast<GLuint>(unit));
        }
    }

    volume.texture.bind(0);
    in.transferFunction.bind(1);
    if (in.sceneDepth) in.sceneDepth->bind(2);
    else glBindTextureUnit(2, in.target.depthTextureId());
    if (m_variant.emptySpaceSkipping) in.occupancy.bind(3);
    if (m_variant.preintegration && in.preintegration) {
        p.set("preintegrationTable", units::kPreintegration);
        p.set("preintegrationSize", static_cast<float>(in.preintegration->size().x));
        in.preintegration->bind(units::kPreintegration);
    }
    if (!m_variant.preintegration) {
        if (!in.stepTransferFunction) throw Error(ErrorKind::InvalidArgument, "RayCastPass: no step transfer function");
        p.set("stepTransferFunction", units::kStepTransferFunction);
        p.set("stepTransferFunctionEntries", static_cast<float>(in.stepTransferFunction->size().x));
        in.stepTransferFunction->bind(units::kStepTransferFunction);
    }
    if (in.opacityTable) {
        p.set("opacityTable", units::kOpacityTable);
        in.opacityTable->bind(units::kOpacityTable);
    }
}

}  // namespace sss::detail
