#include "sss/image.h"

#include "sss/error.h"


#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <string>

namespace sss {
namespace {

// at() views 4 consecutive floats / bytes as one glm vector.
static_assert(sizeof(glm::vec4) == 4 * sizeof(float) && alignof(glm::vec4) <= alignof(float) * 4);
static_assert(sizeof(glm::u8vec4) == 4 && alignof(glm::u8vec4) == 1);

void checkSize(const char* what, int width, int height) {
    if (width <= 0 || height <= 0 || width > kMaxImageSide || height > kMaxImageSide)
        throw Error(ErrorKind::InvalidArgument, std::string(what) + ": width and height must be in [1, " +
                                                    std::to_string(kMaxImageSide) + "], got " +
                                                    std::to_string(width) + "x" + std::to_string(height));
}

std::size_t pixelIndex(const char* what, int x, int y, int width, int height) {
    if (x < 0 || y < 0 || x >= width || y >= height)
        throw Error(ErrorKind::InvalidArgument, std::string(what) + ": pixel (" + std::to_string(x) + ", " +
                                                    std::to_string(y) + ") is outside the " +
                                                    std::to_string(width) + "x" + std::to_string(height) + " image");
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
}

template <typename T>
std::vector<T> flipRows(const std::vector<T>& data, int width, int height) {
    std::vector<T> out(data.size());
    const std::size_t row = static_cast<std::size_t>(width) * 4;
    for (int y = 0; y < height; ++y)
        std::copy_n(data.begin() + static_cast<std::ptrdiff_t>(row * static_cast<std::size_t>(y)), row,
                    out.begin() + static_cast<std::ptrdiff_t>(row * static_cast<std::size_t>(height - 1 - y)));
    return out;
}

uint8_t toByte(float v) {
    if (!(v > 0.0f)) return 0;  // also NaN
    if (v >= 1.0f) return 255;
    return static_cast<uint8_t>(std::lround(v * 255.0f));
}

}  // namespace

Image::Image(int width, int height, glm::vec4 fill) : m_width(width), m_height(height) {
    checkSize("Image", width, height);
    m_data.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4);
    for (std::size_t i = 0; i < m_data.size(); i += 4) std::memcpy(&m_data[i], &fill, sizeof(fill));
}

glm::vec4& Image::at(int x, int y) {
    return *reinterpret_cast<glm::vec4*>(&m_data[4 * pixelIndex("Image::at", x, y, m_width, m_height)]);
}

const glm::vec4& Image::at(int x, int y) const {
    return *reinterpret_cast<const glm::vec4*>(&m_data[4 * pixelIndex("Image::at", x, y, m_width, m_height)]);
}

Image8 Image::toRgba8() const {
    Image8 out(m_width, m_height);
    std::transform(m_data.begin(), m_data.end(), out.data().begin(), toByte);
    return out;
}

Image Image::flippedVertically() const {
    Image out(m_width, m_height);
    out.m_data = flipRows(m_data, m_width, m_height);
    return out;
}


Image8::Image8(int width, int height, glm::u8vec4 fill) : m_width(width), m_height(height) {
    checkSize("Image8", width, height);
    m_data.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4);
    for (std::size_t i = 0; i < m_data.size(); i += 4) std::memcpy(&m_data[i], &fill, sizeof(fill));
}

glm::u8vec4& Image8::at(int x, int y) {
    return *reinterpret_cast<glm::u8vec4*>(&m_data[4 * pixelIndex("Image8::at", x, y, m_width, m_height)]);
}

const glm::u8vec4& Image8::at(int x, int y) const {
    return *reinterpret_cast<const glm::u8vec4*>(&m_data[4 * pixelIndex("Image8::at", x, y, m_width, m_height)]);
}

Image Image8::toFloat() const {
    Image out(m_width, m_height);
    std::transform(m_data.begin(), m_data.end(), out.data().begin(),
                   [](uint8_t v) { return static_cast<float>(v) / 255.0f; });
    return out;
}

Image8 Image8::flippedVertically() const {
    Image8 out(m_width, m_height);
    out.m_data = flipRows(m_data, m_width, m_height);
    return out;
}

}  // namespace sss
