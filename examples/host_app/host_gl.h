#pragma once
// The host application's own GL: entry points loaded through GLFW (no libsss code), and its
// flat-shaded boxes and floor. Nothing here knows libsss.
#include <GL/glcorearb.h>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <vector>

namespace host {

// The entry points this application calls, loaded once its context is current.
struct Gl {
    PFNGLCLEARCOLORPROC ClearColor;
    PFNGLCLEARPROC Clear;
    PFNGLENABLEPROC Enable;
    PFNGLDISABLEPROC Disable;
    PFNGLVIEWPORTPROC Viewport;
    PFNGLCREATESHADERPROC CreateShader;
    PFNGLSHADERSOURCEPROC ShaderSource;
    PFNGLCOMPILESHADERPROC CompileShader;
    PFNGLGETSHADERIVPROC GetShaderiv;
    PFNGLGETSHADERINFOLOGPROC GetShaderInfoLog;
    PFNGLCREATEPROGRAMPROC CreateProgram;
    PFNGLATTACHSHADERPROC AttachShader;
    PFNGLLINKPROGRAMPROC LinkProgram;
    PFNGLGETPROGRAMIVPROC GetProgramiv;
    PFNGLDELETESHADERPROC DeleteShader;
    PFNGLDELETEPROGRAMPROC DeleteProgram;
    PFNGLUSEPROGRAMPROC UseProgram;
    PFNGLGETUNIFORMLOCATIONPROC GetUniformLocation;
    PFNGLUNIFORMMATRIX4FVPROC UniformMatrix4fv;
    PFNGLUNIFORM4FVPROC Uniform4fv;
    PFNGLUNIFORM3FVPROC Uniform3fv;
    PFNGLCREATEBUFFERSPROC CreateBuffers;
    PFNGLNAMEDBUFFERSTORAGEPROC NamedBufferStorage;
    PFNGLDELETEBUFFERSPROC DeleteBuffers;
    PFNGLCREATEVERTEXARRAYSPROC CreateVertexArrays;
    PFNGLDELETEVERTEXARRAYSPROC DeleteVertexArrays;
    PFNGLVERTEXARRAYVERTEXBUFFERPROC VertexArrayVertexBuffer;
    PFNGLENABLEVERTEXARRAYATTRIBPROC EnableVertexArrayAttrib;
    PFNGLVERTEXARRAYATTRIBFORMATPROC VertexArrayAttribFormat;
    PFNGLVERTEXARRAYATTRIBBINDINGPROC VertexArrayAttribBinding;
    PFNGLBINDVERTEXARRAYPROC BindVertexArray;
    PFNGLDRAWARRAYSPROC DrawArrays;
    PFNGLREADPIXELSPROC ReadPixels;
    PFNGLPIXELSTOREIPROC PixelStorei;
    PFNGLREADBUFFERPROC ReadBuffer;
    PFNGLBINDFRAMEBUFFERPROC BindFramebuffer;
    PFNGLBLITNAMEDFRAMEBUFFERPROC BlitNamedFramebuffer;
    PFNGLFINISHPROC Finish;

    /// Loads every entry point through glfwGetProcAddress; throws std::runtime_error naming a
    /// missing one.
    static Gl load();
};

// Flat-coloured, Lambert-lit triangles (position + normal), one draw per object.
class FlatRenderer {
public:
    explicit FlatRenderer(const Gl& gl);
    ~FlatRenderer();
    FlatRenderer(const FlatRenderer&) = delete;
    FlatRenderer& operator=(const FlatRenderer&) = delete;

    /// An axis-aligned box of half extent `half` at `centre`, or a floor square at height y.
    void drawBox(const glm::mat4& viewProjection, glm::vec3 centre, glm::vec3 half, glm::vec4 color) const;
    void drawFloor(const glm::mat4& viewProjection, float y, float half, glm::vec4 color) const;

private:
    void draw(const glm::mat4& viewProjection, const glm::mat4& model, unsigned first, int count,
              glm::vec4 color) const;
    const Gl& m_gl;
    unsigned m_program = 0, m_buffer = 0, m_vertexArray = 0;
};

}  // namespace host
