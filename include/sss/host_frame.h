#pragma once
/// @file
/// Drawing libsss into a host application's own framebuffer, with its depth honoured both ways:
/// the host's geometry stops volume rays and hides libsss meshes, and libsss meshes hide what
/// the host draws afterwards.
///
///     auto context = sss::HostContext::adopt({.getProcAddress = glfwGetProcAddress});
///     sss::HybridCompositor scene({.clearTarget = false});  // draws over the host's depth
///     sss::HostTarget host;
///     // each frame: the host draws its opaque geometry with camera.view() and
///     // camera.projection(aspect), then
///     {
///         sss::HostTarget::Frame frame = host.begin({.framebuffer = 0, .width = w, .height = h});
///         scene.render(camera, frame.target());
///         frame.present();
///     }   // the host's GL state is back; what it draws now is depth-tested against libsss's
///
/// The host's depth must come from the same camera: libsss's view and projection matrices, the
/// default depth range [0, 1] and clip control (lower left, negative one to one).
///
/// GL STATE CONTRACT. Between begin() and the end of the Frame, libsss owns the GL state; when the
/// Frame ends, everything listed in GlStateGuard is as the host left it. libsss objects keep
/// their own GL objects alive: the host must not delete names it did not create.
#include "sss/api.h"
#include "sss/display.h"
#include "sss/render_target.h"

#include <cstdint>
#include <memory>

SSS_BEGIN_API

namespace sss {

/// A rectangle of one of the host's framebuffers. A host that renders into its own colour and
/// depth textures attaches them to a framebuffer object (glNamedFramebufferTexture) and names it.
struct HostFramebuffer {
    std::uint32_t framebuffer = 0;  ///< GL name; 0 is the default framebuffer (the window)
    int x = 0;                      ///< lower-left corner, in pixels
    int y = 0;
    int width = 0;                  ///< size in pixels, in [1, 16384]: the size libsss renders at
    int height = 0;
    /// Write linear radiance (for a floating-point framebuffer or one with GL_FRAMEBUFFER_SRGB
    /// that the host tone maps itself) instead of display values through `display`.
    bool linear = false;
    DisplayTransform display{};     ///< the display transform of the written colour (not linear)
    /// Honour the host's depth both ways (default). Off: libsss draws as an overlay; its rays
    /// run through the host's geometry, and what the host draws afterwards covers libsss.
    bool depth = true;
};

/// Saves the GL state a host may rely on when constructed and restores it when destroyed:
/// program, vertex array, draw and read framebuffers, viewport, scissor, blending (enable,
/// functions, equations, colour), face culling (enable, mode, front face), depth test (enable,
/// function, mask, range), stencil test, colour mask, GL_FRAMEBUFFER_SRGB, polygon mode,
/// primitive restart, rasterizer discard, pixel pack and unpack (alignment, buffers), the
/// active texture unit and, on every unit libsss uses (0-31), the 1D, 2D, 3D, 2D-array and
/// cube-map textures and the sampler, shader-storage buffers 0-2 and image unit 0.
/// Then it sets the state libsss's passes assume (src/lighting/gl_state.h in the source).
class GlStateGuard {
public:
    GlStateGuard();
    ~GlStateGuard();
    GlStateGuard(const GlStateGuard&) = delete;
    GlStateGuard& operator=(const GlStateGuard&) = delete;

private:
    struct Saved;
    std::unique_ptr<Saved> m_saved;
};

/// Renders libsss into host framebuffers. Owns the RenderTarget libsss draws into (RGBA32F
/// linear colour, 32-bit depth) and the passes that move depth in and colour and depth out.
/// Needs a current GlContext (a HostContext) for its whole lifetime.
class HostTarget {
public:
    HostTarget();
    ~HostTarget();
    HostTarget(HostTarget&&) noexcept;
    HostTarget& operator=(HostTarget&&) noexcept;

    /// One frame into one host framebuffer: a GlStateGuard for its lifetime.
    class Frame {
    public:
        ~Frame();
        Frame(Frame&&) noexcept;
        Frame& operator=(Frame&&) = delete;

        /// The target to render into: transparent colour, the host's depth.
        RenderTarget& target();
        /// Composites the target over the host's colour (premultiplied "over") and writes its
        /// depth where libsss drew. Call once, after rendering.
        void present();

    private:
        friend class HostTarget;
        Frame(HostTarget& owner, const HostFramebuffer& framebuffer);
        struct State;
        std::unique_ptr<State> m_state;
    };

    /// Saves the host's GL state, resizes the target to the rectangle, clears its colour to
    /// transparent black and copies the host's depth into it (far everywhere when the host's
    /// framebuffer has no depth buffer).
    /// @throws Error InvalidArgument for a size outside [1, 16384], a framebuffer name that is
    ///         not a framebuffer, or an incomplete framebuffer.
    Frame begin(const HostFramebuffer& framebuffer);

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

}  // namespace sss

SSS_END_API
