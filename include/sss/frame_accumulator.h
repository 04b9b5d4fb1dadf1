#pragma once
/// @file
/// Progressive anti-aliasing for static scenes: render the scene several times, each with the
/// camera shifted by a different sub-pixel offset (Camera::setSubpixelOffset), and average the
/// frames. Every frame is a complete, depth-correct image (meshes, volumes and their
/// compositing all see the same shifted camera), so the mean is a supersampled picture of the
/// whole scene, hybrid scenes included. The offsets follow the Halton (2, 3) sequence over the
/// pixel, with frame 0 at the pixel centre.
///
///     sss::FrameAccumulator aa(width, height);
///     for (int i = 0; i < 8; ++i) {
///         camera.setSubpixelOffset(sss::FrameAccumulator::subpixelOffset(i, width, height));
///         scene.render(camera, frame);
///         aa.add(frame);
///     }
///     camera.setSubpixelOffset({0, 0});
///     sss::Image picture = aa.result().readColor();

#include "sss/api.h"
#include "sss/render_target.h"

#include <glm/vec2.hpp>

#include <memory>

SSS_BEGIN_API

namespace sss {

class FrameAccumulator {
public:
    /// Needs a current GlContext. @throws Error InvalidArgument as RenderTarget.
    FrameAccumulator(int width, int height);
    ~FrameAccumulator();
    FrameAccumulator(FrameAccumulator&&) noexcept;
    FrameAccumulator& operator=(FrameAccumulator&&) noexcept;

    /// The NDC offset of frame `index` (>= 0) for a width x height target: Halton (2, 3) point
    /// index over the pixel, minus the pixel centre; (0, 0) for index 0.
    static glm::vec2 subpixelOffset(int index, int width, int height);

    /// Adds a frame to the running mean (colour; the depth kept is the first frame's).
    /// @throws Error InvalidArgument if the frame's size differs from the accumulator's.
    void add(const RenderTarget& frame);
    /// Forgets every frame (call when the scene or the camera changes).
    void reset();
    int frames() const;
    /// The mean of the frames added since the last reset (cleared to 0 before the first).
    const RenderTarget& result() const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

}  // namespace sss

SSS_END_API
