#pragma once
/// @file
/// CPU images: RGBA float (Image) and RGBA 8-bit (Image8), row 0 at the top, PNG I/O.

#include "sss/api.h"
#include <glm/ext/vector_uint4_sized.hpp>
#include <glm/vec4.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <vector>

SSS_BEGIN_API

namespace sss {

class Image8;

/// Largest accepted width or height.
inline constexpr int kMaxImageSide = 16384;

/// RGBA float image, row-major, row 0 at the top, 4 floats per pixel. Values are not clamped.
class Image {
public:
    /// width x height pixels, all set to fill (default transparent black).
    /// @throws Error InvalidArgument unless 0 < width, height <= 16384.
    Image(int width, int height, glm::vec4 fill = glm::vec4(0.0f));

    int width() const { return m_width; }    ///< pixels per row
    int height() const { return m_height; }  ///< rows
    /// Pixel (x, y), y = 0 is the top row. @throws Error InvalidArgument if outside the image.
    glm::vec4& at(int x, int y);
    /// Pixel (x, y), y = 0 is the top row. @throws Error InvalidArgument if outside the image.
    const glm::vec4& at(int x, int y) const;
    /// width*height*4 floats, RGBA, rows top to bottom. Do not resize.
    std::vector<float>& data() { return m_data; }
    /// width*height*4 floats, RGBA, rows top to bottom.
    const std::vector<float>& data() const { return m_data; }

    /// Each channel clamped to [0,1] and rounded to the nearest of 0..255; no gamma. NaN -> 0.
    Image8 toRgba8() const;
    /// Copy with the rows in reverse order (GL reads back bottom row first).
    Image flippedVertically() const;
    /// Writes toRgba8() as an 8-bit RGBA PNG: values are clamped, not display-transformed (for
    /// a picture of linear radiance use toDisplay(), include/sss/display.h).
    /// @throws Error Io naming the file if it cannot be written.
    void savePng(const std::filesystem::path& path) const;
    /// Writes an OpenEXR file with 32-bit float R, G, B, A channels: the values exactly, linear.
    /// @throws Error Io naming the file if it cannot be written.
    void saveExr(const std::filesystem::path& path) const;
    /// Reads an OpenEXR file's R, G, B (and A, else 1) channels as 32-bit floats; a missing
    /// colour channel reads as 0. @throws Error Io if missing, Parse if OpenEXR cannot read it,
    /// InvalidArgument if it is larger than 16384 on a side.
    static Image loadExr(const std::filesystem::path& path);

private:
    int m_width = 0, m_height = 0;
    std::vector<float> m_data;
};

/// RGBA 8-bit image, row-major, row 0 at the top, 4 bytes per pixel.
class Image8 {
public:
    /// width x height pixels, all set to fill (default transparent black).
    /// @throws Error InvalidArgument unless 0 < width, height <= 16384.
    Image8(int width, int height, glm::u8vec4 fill = glm::u8vec4(0));

    int width() const { return m_width; }    ///< pixels per row
    int height() const { return m_height; }  ///< rows
    /// Pixel (x, y), y = 0 is the top row. @throws Error InvalidArgument if outside the image.
    glm::u8vec4& at(int x, int y);
    /// Pixel (x, y), y = 0 is the top row. @throws Error InvalidArgument if outside the image.
    const glm::u8vec4& at(int x, int y) const;
    /// width*height*4 bytes, RGBA, rows top to bottom. Do not resize.
    std::vector<uint8_t>& data() { return m_data; }
    /// width*height*4 bytes, RGBA, rows top to bottom.
    const std::vector<uint8_t>& data() const { return m_data; }

    /// Each channel divided by 255.
    Image toFloat() const;
    /// Copy with the rows in reverse order (GL reads back bottom row first).
    Image8 flippedVertically() const;
    /// Writes an 8-bit RGBA PNG. @throws Error Io naming the file if it cannot be written.
    void savePng(const std::filesystem::path& path) const;
    /// Reads a PNG (any format stb_image reads), converted to 8-bit RGBA.
    /// @throws Error Io if the file is missing; Parse with stb_image's reason if it cannot be
    ///         decoded; InvalidArgument if it is larger than 16384 on a side.
    static Image8 loadPng(const std::filesystem::path& path);

private:
    int m_width = 0, m_height = 0;
    std::vector<uint8_t> m_data;
};

}  // namespace sss

SSS_END_API
