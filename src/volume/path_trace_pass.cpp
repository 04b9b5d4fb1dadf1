#include "volume/path_trace_pass.h"

#include "volume/clip_uniforms.h"
#include "volume/composite_over.h"
#include "gl/device.h"
#include "core/light_geometry.h"
#include "lighting/light_uniforms.h"
#include "sss/error.h"
#include "sss/log.h"
#include "sss/volume_reference.h"

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <variant>

namespace sss::detail {

namespace {
// The GPU's filtered classification may round a little above the table's largest opacity; a
// majorant below sigma_t would bias the estimate, one a little above only costs lookups (the
// shader also clamps sigma_t to it).
constexpr float kMajorantSlack = 1.001f;
// sizeof(PathState) in path_trace.comp (std430: seven 16-byte vectors).
constexpr std::size_t kPathStateBytes = 112;
}  // namespace

gl::Texture brickMajorants(const OccupancyGrid& grid, float voxelLength) {
    std::vector<float> sigma;
    sigma.reserve(grid.maxOpacity().size());
    for (const float alpha : grid.maxOpacity()) {
        const double a = alpha;
        const double depth = !(a > 0.0) ? 0.0 : a >= 1.0 ? kMaxOpticalDepthPerVoxel
                                                         : std::min(-std::log1p(-a), kMaxOpticalDepthPerVoxel);
        sigma.push_back(static_cast<float>(depth / voxelLength) * kMajorantSlack);
    }
    gl::Texture texture = gl::Texture::create3D(GL_R32F, grid.brickCount(), "path-tracer majorants");
    texture.setFilter(GL_NEAREST, GL_NEAREST);
    texture.upload(GL_RED, GL_FLOAT, sigma.data());
    return texture;
}

PathTracePass::PathTracePass(PathTraceBounds bounds, VolumeReconstruction reconstruction)
    : m_resolve(gl::Program::link({{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                   {GL_FRAGMENT_SHADER, "volume/path_trace_resolve.frag"}})),
      m_emptyVertexArray(gl::VertexArray::create()),
      m_bounds(bounds),
      m_reconstruction(reconstruction) {
    if (bounds.stepsPerDispatch < 1 || bounds.stepsPerDispatch > kPathTraceMaxStepsPerDispatch)
        throw Error(ErrorKind::InvalidArgument, "PathTracePass: stepsPerDispatch must be in [1, " +
                                                    std::to_string(kPathTraceMaxStepsPerDispatch) + "], got " +
                                                    std::to_string(bounds.stepsPerDispatch));
    if (bounds.maxPathStates < 1)
        throw Error(ErrorKind::InvalidArgument,
                    "PathTracePass: maxPathStates must be >= 1, got " + std::to_string(bounds.maxPathStates));
    const std::uint32_t zero[2] = {0, 0};
    m_status = gl::Buffer::create(sizeof(zero), zero, GL_DYNAMIC_STORAGE_BIT, "path-tracer status");
    m_resumable = bounds.resumable.value_or(gl::currentDeviceIsSoftware());
    if (!m_resumable) {
        const GLbitfield mapping = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
        m_statusCopy = gl::Buffer::create(sizeof(zero), zero, mapping, "path-tracer status (read a frame later)");
        m_statusMapped =
            static_cast<const std::uint32_t*>(glMapNamedBufferRange(m_statusCopy.id(), 0, sizeof(zero), mapping));
    }
}

PathTracePass::~PathTracePass() {
    if (m_statusFence) glDeleteSync(m_statusFence);
    if (m_statusMapped) glUnmapNamedBuffer(m_statusCopy.id());
}

void PathTracePass::reportAbandoned(std::uint32_t abandoned) {
    if (abandoned == 0) return;
    m_abandoned += abandoned;
    log(LogLevel::Warning, "PathTracePass: " + std::to_string(abandoned) +
                               " paths were given up after 2^24 steps each (degenerate rays); the image is biased there");
}

void PathTracePass::collectStatus() {
    if (!m_statusFence) return;
    GLint signalled = GL_UNSIGNALED;
    glGetSynciv(m_statusFence, GL_SYNC_STATUS, 1, nullptr, &signalled);
    if (signalled != GL_SIGNALED) return;  // still on the GPU: next frame
    glDeleteSync(m_statusFence);
    m_statusFence = nullptr;
    reportAbandoned(m_statusMapped[1]);
}

const gl::Program& PathTracePass::traceProgram(bool meshShadows) {
    return gl::linkedOnce(m_tracePrograms, meshShadows, "volume/path_trace.comp", [&]() -> ShaderDefines {
        return {{"MAX_LIGHTS", std::to_string(kMaxLights)},
                {"CUBIC_RECONSTRUCTION", cubicReconstructionDefine(m_reconstruction)},
                {"MESH_SHADOWS", meshShadows ? "1" : "0"}};
    });
}

void PathTracePass::accumulate(const PathTraceInputs& in, const gl::Texture& sums) {
    const GpuVolume& volume = in.volume;
    const glm::mat4 viewProjection = in.camera.projection(in.aspect) * in.camera.view();
    const glm::mat4 worldToModel = glm::inverse(in.model);
    const bool meshShadows = castsMeshShadows(in.meshShadows, in.lights.size());
    const gl::Program& p = traceProgram(meshShadows);
    if (meshShadows) setMeshVisibilityUniforms(p, *in.meshShadows, in.lights);
    p.set("inverseViewProjection", glm::inverse(viewProjection));
    p.set("worldToModel", worldToModel);
    p.set("modelToWorld", in.model);
    p.set("volumeTexture", 0);
    p.set("transferFunction", 1);
    p.set("sceneDepth", 2);
    p.set("majorants", 3);
    p.set("transferFunctionEntries", static_cast<float>(in.transferFunction.size().x));
    p.set("valueScaleOffset", volume.valueScaleOffset);
    p.set("boxMin", volume.box.min);
    p.set("boxMax", volume.box.max);
    setClipUniforms(p, in.clip, in.model, volume.box);
    p.set("cellSize", volume.box.size() * static_cast<float>(kBrickVoxels) / glm::vec3(volume.dims));
    p.set("voxelLength", volume.voxelLength);
    p.set("phaseG", in.options.anisotropy);
    p.set("maxBounces", in.options.maxBounces);
    const glm::ivec3 size = sums.size();
    glProgramUniform2i(p.id(), p.uniformLocation("imageSize"), size.x, size.y);
    // Lights as the CPU path tracer prepares them: directions and positions in model space,
    // point-light falloff and spot cones from world-space vectors; black lights are left out.
    const glm::mat3 worldToModelLinear(worldToModel);
    int count = 0;
    for (const Light& light : in.lights) {
        glm::vec4 modelVector;
        glm::vec3 worldPosition(0.0f);
        const glm::vec3 radiance = lightRadiance(light);
        if (const auto* d = std::get_if<DirectionalLight>(&light)) {
            modelVector = glm::vec4(glm::normalize(worldToModelLinear * -glm::normalize(d->direction)), 0.0f);
        } else {
            worldPosition = *lightPosition(light);
            modelVector = glm::vec4(glm::vec3(worldToModel * glm::vec4(worldPosition, 1.0f)), 1.0f);
        }
        if (!(std::max({radiance.x, radiance.y, radiance.z}) > 0.0f)) continue;
        const std::string i = "[" + std::to_string(count) + "]";
        p.set("lightModel" + i, modelVector);
        p.set("lightWorldPosition" + i, worldPosition);
        p.set("lightRadiance" + i, radiance);
        p.set("lightShadowLayer" + i, static_cast<int>(&light - in.lights.data()));
        setSpotConeUniforms(p, count++, light);
    }
    p.set("lightCount", count);

    // Bands of whole rows, as many as the path-state budget holds (at least one row).
    const int bandRows = std::clamp(m_bounds.maxPathStates / size.x, 1, size.y);
    const std::size_t states = static_cast<std::size_t>(size.x) * static_cast<std::size_t>(bandRows);
    if (!m_paths || m_paths.size() != states * kPathStateBytes)
        m_paths = gl::Buffer::create(states * kPathStateBytes, nullptr, 0, "path-tracer path states");
    p.set("firstSample", in.firstSample);
    p.set("pathsPerPixel", static_cast<unsigned>(in.options.samplesPerFrame));
    // Without resuming, one dispatch takes every path to its end (or to its 2^24-step cap).
    p.set("stepsPerDispatch", m_resumable ? m_bounds.stepsPerDispatch : std::numeric_limits<int>::max());

    volume.texture.bind(0);
    in.transferFunction.bind(1);
    in.sceneDepth.bind(2);
    in.majorants.bind(3);
    sums.bindImage(0, GL_READ_WRITE);
    m_paths.bindStorage(0);
    m_status.bindStorage(1);
    p.use();
    collectStatus();
    const std::uint32_t zero[2] = {0, 0};
    m_status.upload(0, sizeof(zero), zero);
    dispatchBands(p, glm::ivec2(size), bandRows);
    if (!m_resumable && !m_statusFence) {
        glCopyNamedBufferSubData(m_status.id(), m_statusCopy.id(), 0, 0, sizeof(zero));
        glMemoryBarrier(GL_CLIENT_MAPPED_BUFFER_BARRIER_BIT);
        m_statusFence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    glUseProgram(0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, 0);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
}

void PathTracePass::dispatchBands(const gl::Program& p, glm::ivec2 size, int bandRows) {
    // llvmpipe gives each invocation 65535 loop iterations in all, over all its loops (measured:
    // two loops of 40000 ran 40000 and 25534), then leaves every loop early; many paths in one
    // invocation were cut short that way (512 paths lost 28 % of the light). So there no
    // dispatch runs a path to its end regardless of length: each spends at most
    // stepsPerDispatch steps per pixel, and the paths' state carries over to the next dispatch
    // until every pixel has finished its paths. The shader counts the invocations with work
    // left, read back after each dispatch.
    const std::uint32_t zero = 0;
    std::uint32_t status[2] = {0, 0};
    m_lastDispatches = 0;
    for (int firstRow = 0; firstRow < size.y; firstRow += bandRows) {
        const int rows = std::min(bandRows, size.y - firstRow);
        p.set("bandFirstRow", firstRow);
        p.set("bandRows", rows);
        for (bool restart = true;; restart = false) {
            p.set("restart", restart ? 1 : 0);
            glDispatchCompute(static_cast<GLuint>((size.x + 7) / 8), static_cast<GLuint>((rows + 7) / 8), 1);
            ++m_lastDispatches;
            glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                            GL_BUFFER_UPDATE_BARRIER_BIT);
            if (!m_resumable) break;
            glGetNamedBufferSubData(m_status.id(), 0, sizeof(status), status);
            if (status[0] == 0) break;
            m_status.upload(0, sizeof(zero), &zero);  // the unfinished count; the abandoned one runs on
        }
    }
    if (m_resumable) reportAbandoned(status[1]);
}

void PathTracePass::composite(const gl::Texture& sums, int samples, glm::vec3 radianceScale) const {
    m_resolve.set("accumulation", 0);
    m_resolve.set("radianceScale", radianceScale);
    m_resolve.set("inverseSamples", samples > 0 ? 1.0f / static_cast<float>(samples) : 0.0f);
    sums.bind(0);
    // Premultiplied "over": the volume's colour in front of what the target already holds.
    drawPremultipliedOver(m_resolve, m_emptyVertexArray);
}

}  // namespace sss::detail
