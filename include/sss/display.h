#pragma once
/// @file
/// The colour pipeline. Every renderer writes linear radiance (scene-referred, unbounded) into
/// RenderTarget's RGBA32F colour; nothing is gamma-encoded on the way. A DisplayTransform turns
/// linear values into display values once, at output: toDisplay() for PNG files and the
/// benchmark's images, DisplayEncoder for a window. Image::saveExr keeps the linear values.
///
///   display = encode(toneMap(linear * 2^exposure)), with encode = sRGB transfer function
///
/// Alpha is passed through, clamped to [0,1]. The transform lives in one text shared by C++ and
/// GLSL (shaders/common/display_transform.glsl), so CPU and GPU output agree.

#include "sss/api.h"
#include "sss/image.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <memory>
#include <string_view>

SSS_BEGIN_API

namespace sss {

class RenderTarget;

enum class ToneMap {
    None,    ///< clip at 1
    Filmic,  ///< the ACES filmic curve fit of Narkowicz (2015): highlights roll off instead of clipping
};

struct DisplayTransform {
    float exposure = 0.0f;           ///< stops: linear values are scaled by 2^exposure (default: 0)
    ToneMap toneMap = ToneMap::None;  ///< default: None (values above 1 clip)
    bool srgb = true;                ///< encode with the sRGB transfer function (default: on)
};

/// Throws Error(InvalidArgument) unless exposure is finite and within [-64, 64] stops.
void validate(const DisplayTransform& transform);

/// Display values in [0,1] of one linear colour.
glm::vec3 applyDisplayTransform(glm::vec3 linear, const DisplayTransform& transform = {});

/// The display image of a linear one, rounded to 8 bits (NaN -> 0).
Image8 toDisplay(const Image& linear, const DisplayTransform& transform = {});

/// "none" | "filmic" (Error InvalidArgument otherwise), and back.
ToneMap parseToneMap(std::string_view name);
const char* toneMapName(ToneMap toneMap);

/// Applies a DisplayTransform on the GPU: encodes a RenderTarget's linear colour into an RGBA8
/// framebuffer, for applications that present the result in a window (glBlitNamedFramebuffer
/// from framebufferId()). Needs a current GlContext for its whole lifetime.
class DisplayEncoder {
public:
    DisplayEncoder();
    ~DisplayEncoder();
    DisplayEncoder(DisplayEncoder&&) noexcept;
    DisplayEncoder& operator=(DisplayEncoder&&) noexcept;

    /// Encodes `linear`'s colour; the output has its size.
    void encode(const RenderTarget& linear, const DisplayTransform& transform = {});
    /// The RGBA8 framebuffer holding the last encode() (0 before the first).
    std::uint32_t framebufferId() const;
    /// Reads the encoded image back, top row first.
    Image8 read() const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

}  // namespace sss

SSS_END_API
