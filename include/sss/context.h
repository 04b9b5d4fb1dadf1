#pragma once
/// @file
/// OpenGL 4.5 core contexts. Renderers draw with whatever context is current on the calling
/// thread; a GlContext only creates one, makes it current and reports on it.
///
/// Contract for backends: creating a context loads the GL entry points and leaves the new
/// context current; backends never change GL state other than what context creation implies.

#include "sss/api.h"
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

SSS_BEGIN_API

namespace sss {

/// A GL entry point as context libraries return it (glfwGetProcAddress, eglGetProcAddress).
using GlProc = void (*)();
/// Looks up a GL entry point by name; a null result means the context lacks it.
using GlProcLoader = std::function<GlProc(const char* name)>;

/// What the driver says about a context.
struct ContextInfo {
    std::string vendor;        ///< GL_VENDOR
    std::string renderer;      ///< GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    std::string version;       ///< GL_VERSION
    std::string backend;       ///< how it was made, e.g. "EGL surfaceless (EGL_MESA_platform_surfaceless)"
    bool debug = false;        ///< KHR_debug output is installed and routed to the library log
    /// True for software rasterisers (llvmpipe, softpipe, SwiftShader), whose GL timer queries
    /// do not measure rendering: time them with a CPU clock around glFinish().
    bool software = false;
};

/// Counts of KHR_debug messages received since the context was created (or since reset).
struct DebugMessageCounts {
    std::uint64_t errors = 0;       ///< GL_DEBUG_TYPE_ERROR messages: always a libsss bug
    std::uint64_t warnings = 0;     ///< undefined/deprecated behaviour, high/medium severity
    std::uint64_t other = 0;
};

/// An OpenGL 4.5 core context. Not copyable; destroying it destroys the GL context, so GL
/// objects made with it (renderers, render targets) must be destroyed first.
class GlContext {
public:
    virtual ~GlContext() = default;
    GlContext(const GlContext&) = delete;
    GlContext& operator=(const GlContext&) = delete;

    /// Makes this context current on the calling thread.
    virtual void makeCurrent() = 0;
    /// Presents the default framebuffer (windowed backends); headless backends do nothing.
    virtual void swapBuffers() {}

    const ContextInfo& info() const { return m_info; }
    /// KHR_debug counters (all zero when debug output is off).
    DebugMessageCounts debugMessages() const;
    void resetDebugMessages();
    /// The last GL error message received through KHR_debug, empty if none.
    std::string lastDebugError() const;

protected:
    GlContext() = default;
    /// Called by backends once the context is current: loads GL, checks for 4.5 core, fills
    /// info() and installs the debug callback when requested. Throws Error(Gl) on failure.
    void initializeGl(const GlProcLoader& getProcAddress, bool debug, std::string backend);

public:
    struct DebugState;  ///< @private implementation detail of the KHR_debug callback

private:
    ContextInfo m_info;
    std::shared_ptr<DebugState> m_debug;
};

/// How the headless EGL backend finds a display. Auto tries them in the listed order.
enum class EglPlatform {
    Auto,
    Surfaceless,   ///< EGL_MESA_platform_surfaceless (Mesa)
    Device,        ///< EGL_EXT_platform_device: first device (NVIDIA's headless path)
    DefaultPbuffer ///< eglGetDisplay(EGL_DEFAULT_DISPLAY) + a 1x1 pbuffer
};

struct EglContextOptions {
    EglPlatform platform = EglPlatform::Auto;
    /// Create a debug context and route KHR_debug output to the library log. Also switched on
    /// by the environment variable SSS_GL_DEBUG=1.
    bool debug = false;
    /// With EglPlatform::Device/Auto, prefer a software device (EGL_MESA_device_software), so
    /// images are reproducible on machines that also have a GPU. Also SSS_EGL_SOFTWARE=1.
    bool preferSoftware = false;
};

/// Headless OpenGL 4.5 core context through EGL; renders only into framebuffer objects.
class EglContext final : public GlContext {
public:
    /// Throws Error(ErrorKind::Gl) naming every platform tried and why it failed.
    static std::unique_ptr<EglContext> create(const EglContextOptions& options = {});
    ~EglContext() override;
    void makeCurrent() override;

private:
    EglContext() = default;
    struct Native;
    std::unique_ptr<Native> m_native;
};

/// Options of HostContext::adopt.
struct HostContextOptions {
    /// How the host's context library finds GL entry points: glfwGetProcAddress works as is;
    /// SDL_GL_GetProcAddress, eglGetProcAddress or Qt's QOpenGLContext::getProcAddress through a
    /// lambda. Required.
    GlProcLoader getProcAddress{};
    /// Makes the host's context current (for GlContext::makeCurrent); empty: makeCurrent() does
    /// nothing, and the host keeps its context current whenever it calls libsss.
    std::function<void()> makeCurrent{};
    /// Install libsss's KHR_debug callback (replacing the host's) and count messages, as the
    /// other contexts do with `debug`. Default off: the host's own callback stays.
    bool debug = false;
    /// Names the context in info().backend and in messages (default: "host context").
    std::string name = "host context";
};

/// The host application's own OpenGL 4.5 core context, adopted: libsss loads its GL entry
/// points from it and draws with it, but neither creates nor destroys it. The host's context
/// must be current when adopt() runs and whenever libsss is called; libsss objects must be
/// destroyed before the host destroys its context. To draw into the host's framebuffer with its
/// depth, see sss/host_frame.h.
class HostContext final : public GlContext {
public:
    /// Throws Error(InvalidArgument) without getProcAddress, Error(Gl) if no context is current
    /// or it is not OpenGL 4.5 core.
    static std::unique_ptr<HostContext> adopt(const HostContextOptions& options);
    ~HostContext() override;
    void makeCurrent() override;

private:
    HostContext() = default;
    std::function<void()> m_makeCurrent;
    bool m_ownsDebugCallback = false;
};

}  // namespace sss

SSS_END_API
