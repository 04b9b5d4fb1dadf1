// GlStateGuard (sss/host_frame.h): the host's GL state saved, libsss's contract state set
// (src/lighting/gl_state.h), and the host's state restored.
#include "sss/host_frame.h"

#include "gl/gl.h"

#include <array>

namespace sss {
namespace {

constexpr int kUnits = 32;          // every texture unit libsss binds (src/lighting/texture_units.h)
constexpr int kStorageBuffers = 3;  // shader-storage bindings 0-2
constexpr std::array<GLenum, 5> kTextureTargets{GL_TEXTURE_1D, GL_TEXTURE_2D, GL_TEXTURE_3D, GL_TEXTURE_2D_ARRAY,
                                                GL_TEXTURE_CUBE_MAP};
constexpr std::array<GLenum, 5> kTextureBindings{GL_TEXTURE_BINDING_1D, GL_TEXTURE_BINDING_2D,
                                                 GL_TEXTURE_BINDING_3D, GL_TEXTURE_BINDING_2D_ARRAY,
                                                 GL_TEXTURE_BINDING_CUBE_MAP};
// Capabilities saved and restored as they are; the value is what libsss's passes assume.
constexpr std::array<std::pair<GLenum, bool>, 10> kCapabilities{{{GL_BLEND, false},
                                                                 {GL_CULL_FACE, false},
                                                                 {GL_DEPTH_TEST, false},
                                                                 {GL_SCISSOR_TEST, false},
                                                                 {GL_STENCIL_TEST, false},
                                                                 {GL_FRAMEBUFFER_SRGB, false},
                                                                 {GL_PRIMITIVE_RESTART, false},
                                                                 {GL_RASTERIZER_DISCARD, false},
                                                                 {GL_POLYGON_OFFSET_FILL, false},
                                                                 {GL_PROGRAM_POINT_SIZE, false}}};

GLint integer(GLenum name) {
    GLint value = 0;
    glGetIntegerv(name, &value);
    return value;
}

GLint indexedInteger(GLenum name, GLuint index) {
    GLint value = 0;
    glGetIntegeri_v(name, index, &value);
    return value;
}

void setCapability(GLenum capability, bool on) {
    if (on)
        glEnable(capability);
    else
        glDisable(capability);
}

struct ImageBinding {
    GLint name = 0, level = 0, layered = 0, layer = 0, access = GL_READ_ONLY, format = GL_R8;
};

}  // namespace

struct GlStateGuard::Saved {
    GLint program = 0, vertexArray = 0, drawFramebuffer = 0, readFramebuffer = 0, activeTexture = GL_TEXTURE0;
    std::array<GLint, 4> viewport{}, scissor{};
    std::array<GLboolean, kCapabilities.size()> capabilities{};
    GLint blendSrcRgb = GL_ONE, blendDstRgb = GL_ZERO, blendSrcAlpha = GL_ONE, blendDstAlpha = GL_ZERO;
    GLint blendEquationRgb = GL_FUNC_ADD, blendEquationAlpha = GL_FUNC_ADD;
    std::array<GLfloat, 4> blendColor{};
    GLint cullFace = GL_BACK, frontFace = GL_CCW, depthFunc = GL_LESS, polygonMode = GL_FILL;
    GLboolean depthMask = GL_TRUE;
    std::array<GLdouble, 2> depthRange{0.0, 1.0};
    std::array<GLboolean, 4> colorMask{GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE};
    GLint packAlignment = 4, unpackAlignment = 4, packBuffer = 0, unpackBuffer = 0;
    std::array<std::array<GLint, kTextureTargets.size()>, kUnits> textures{};
    std::array<GLint, kUnits> samplers{};
    std::array<GLint, kStorageBuffers> storageBuffers{};
    std::array<GLint64, kStorageBuffers> storageOffsets{}, storageSizes{};
    ImageBinding image0;

    void save();
    void restore() const;
};

void GlStateGuard::Saved::save() {
    program = integer(GL_CURRENT_PROGRAM);
    vertexArray = integer(GL_VERTEX_ARRAY_BINDING);
    drawFramebuffer = integer(GL_DRAW_FRAMEBUFFER_BINDING);
    readFramebuffer = integer(GL_READ_FRAMEBUFFER_BINDING);
    glGetIntegerv(GL_VIEWPORT, viewport.data());
    glGetIntegerv(GL_SCISSOR_BOX, scissor.data());
    for (std::size_t i = 0; i < kCapabilities.size(); ++i) capabilities[i] = glIsEnabled(kCapabilities[i].first);
    blendSrcRgb = integer(GL_BLEND_SRC_RGB);
    blendDstRgb = integer(GL_BLEND_DST_RGB);
    blendSrcAlpha = integer(GL_BLEND_SRC_ALPHA);
    blendDstAlpha = integer(GL_BLEND_DST_ALPHA);
    blendEquationRgb = integer(GL_BLEND_EQUATION_RGB);
    blendEquationAlpha = integer(GL_BLEND_EQUATION_ALPHA);
    glGetFloatv(GL_BLEND_COLOR, blendColor.data());
    cullFace = integer(GL_CULL_FACE_MODE);
    frontFace = integer(GL_FRONT_FACE);
    depthFunc = integer(GL_DEPTH_FUNC);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &depthMask);
    glGetDoublev(GL_DEPTH_RANGE, depthRange.data());
    glGetBooleanv(GL_COLOR_WRITEMASK, colorMask.data());
    std::array<GLint, 2> polygonModes{};
    glGetIntegerv(GL_POLYGON_MODE, polygonModes.data());
    polygonMode = polygonModes[0];
    packAlignment = integer(GL_PACK_ALIGNMENT);
    unpackAlignment = integer(GL_UNPACK_ALIGNMENT);
    packBuffer = integer(GL_PIXEL_PACK_BUFFER_BINDING);
    unpackBuffer = integer(GL_PIXEL_UNPACK_BUFFER_BINDING);
    activeTexture = integer(GL_ACTIVE_TEXTURE);
    for (int unit = 0; unit < kUnits; ++unit) {
        glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
        for (std::size_t t = 0; t < kTextureTargets.size(); ++t) textures[unit][t] = integer(kTextureBindings[t]);
        samplers[unit] = integer(GL_SAMPLER_BINDING);
    }
    for (GLuint b = 0; b < kStorageBuffers; ++b) {
        storageBuffers[b] = indexedInteger(GL_SHADER_STORAGE_BUFFER_BINDING, b);
        glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, b, &storageOffsets[b]);
        glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, b, &storageSizes[b]);
    }
    image0 = {indexedInteger(GL_IMAGE_BINDING_NAME, 0), indexedInteger(GL_IMAGE_BINDING_LEVEL, 0),
              indexedInteger(GL_IMAGE_BINDING_LAYERED, 0), indexedInteger(GL_IMAGE_BINDING_LAYER, 0),
              indexedInteger(GL_IMAGE_BINDING_ACCESS, 0), indexedInteger(GL_IMAGE_BINDING_FORMAT, 0)};
}

void GlStateGuard::Saved::restore() const {
    glUseProgram(static_cast<GLuint>(program));
    glBindVertexArray(static_cast<GLuint>(vertexArray));
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(drawFramebuffer));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(readFramebuffer));
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    glScissor(scissor[0], scissor[1], scissor[2], scissor[3]);
    for (std::size_t i = 0; i < kCapabilities.size(); ++i) setCapability(kCapabilities[i].first, capabilities[i]);
    glBlendFuncSeparate(static_cast<GLenum>(blendSrcRgb), static_cast<GLenum>(blendDstRgb),
                        static_cast<GLenum>(blendSrcAlpha), static_cast<GLenum>(blendDstAlpha));
    glBlendEquationSeparate(static_cast<GLenum>(blendEquationRgb), static_cast<GLenum>(blendEquationAlpha));
    glBlendColor(blendColor[0], blendColor[1], blendColor[2], blendColor[3]);
    glCullFace(static_cast<GLenum>(cullFace));
    glFrontFace(static_cast<GLenum>(frontFace));
    glDepthFunc(static_cast<GLenum>(depthFunc));
    glDepthMask(depthMask);
    glDepthRange(depthRange[0], depthRange[1]);
    glColorMask(colorMask[0], colorMask[1], colorMask[2], colorMask[3]);
    glPolygonMode(GL_FRONT_AND_BACK, static_cast<GLenum>(polygonMode));
    glPixelStorei(GL_PACK_ALIGNMENT, packAlignment);
    glPixelStorei(GL_UNPACK_ALIGNMENT, unpackAlignment);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, static_cast<GLuint>(packBuffer));
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, static_cast<GLuint>(unpackBuffer));
    for (int unit = 0; unit < kUnits; ++unit) {
        glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
        for (std::size_t t = 0; t < kTextureTargets.size(); ++t)
            glBindTexture(kTextureTargets[t], static_cast<GLuint>(textures[unit][t]));
        glBindSampler(static_cast<GLuint>(unit), static_cast<GLuint>(samplers[unit]));
    }
    glActiveTexture(static_cast<GLenum>(activeTexture));
    for (GLuint b = 0; b < kStorageBuffers; ++b) {
        const auto name = static_cast<GLuint>(storageBuffers[b]);
        if (name != 0 && storageSizes[b] > 0)
            glBindBufferRange(GL_SHADER_STORAGE_BUFFER, b, name, storageOffsets[b], storageSizes[b]);
        else
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, name);
    }
    glBindImageTexture(0, static_cast<GLuint>(image0.name), image0.level, static_cast<GLboolean>(image0.layered),
                       image0.layer, static_cast<GLenum>(image0.access), static_cast<GLenum>(image0.format));
}

namespace {

// What every libsss pass assumes on entry (src/lighting/gl_state.h), from any host state.
void setLibraryState() {
    glUseProgram(0);
    glBindVertexArray(0);
    for (const auto& [capability, on] : kCapabilities) setCapability(capability, on);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDepthRange(0.0, 1.0);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glFrontFace(GL_CCW);
    glCullFace(GL_BACK);
    glBlendEquation(GL_FUNC_ADD);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    for (GLuint unit = 0; unit < kUnits; ++unit) glBindSampler(unit, 0);
    glActiveTexture(GL_TEXTURE0);
}

}  // namespace

GlStateGuard::GlStateGuard() : m_saved(std::make_unique<Saved>()) {
    m_saved->save();
    setLibraryState();
}

GlStateGuard::~GlStateGuard() { m_saved->restore(); }

}  // namespace sss
