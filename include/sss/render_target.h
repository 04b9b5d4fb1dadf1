#pragma once
/// @file
/// An offscreen image the renderers draw into: RGBA32F colour + 32-bit float depth.

#include "sss/api.h"
#include "sss/image.h"

#include <glm/vec4.hpp>

#include <cstdint>
#include <memory>
#include <vector>

SSS_BEGIN_API

namespace sss {

/// Offscreen colour + depth target. Needs a current GlContext for its whole lifetime.
/// Colour is linear radiance in 32-bit float (every renderer writes linear values; the display
/// transform of include/sss/display.h turns them into a picture at output); depth is
/// window-space depth in [0,1], 1 = far plane.
class RenderTarget {
public:
    /// Throws Error(InvalidArgument) unless 0 < width, height <= 16384.
    RenderTarget(int width, int height);
    ~RenderTarget();
    RenderTarget(RenderTarget&&) noexcept;
    RenderTarget& operator=(RenderTarget&&) noexcept;

    int width() const;
    int height() const;
    float aspect() const { return static_cast<float>(width()) / static_cast<float>(height()); }

    /// Clears colour to `color` and depth to 1.
    void clear(glm::vec4 color);
    /// Reads the colour back, top row first. Waits for rendering to finish.
    Image readColor() const;
    /// Reads the depth back, top row first.
    std::vector<float> readDepth() const;

    /// GL names for applications that composite the result themselves (e.g. glBlitNamedFramebuffer).
    std::uint32_t framebufferId() const;
    std::uint32_t colorTextureId() const;
    std::uint32_t depthTextureId() const;

    /// Binds the framebuffer and sets the viewport to the whole target (used by renderers).
    void bindForDrawing() const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

}  // namespace sss

SSS_END_API
