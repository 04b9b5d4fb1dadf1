#include "sss/image.h"

#include "sss/error.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

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

void Image::savePng(const std::filesystem::path& path) const { toRgba8().savePng(path); }

namespace {
constexpr const char* kExrChannels[4] = {"R", "G", "B", "A"};
}

void Image::saveExr(const std::filesystem::path& path) const {
    try {
        Imf::Header header(m_width, m_height);
        for (const char* name : kExrChannels) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
        Imf::FrameBuffer frame;
        const std::size_t pixel = 4 * sizeof(float), row = pixel * static_cast<std::size_t>(m_width);
        auto* base = reinterpret_cast<char*>(const_cast<float*>(m_data.data()));
        for (int c = 0; c < 4; ++c)
            frame.insert(kExrChannels[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), pixel, row));
        Imf::OutputFile file(path.string().c_str(), header);
        file.setFrameBuffer(frame);
        file.writePixels(m_height);
    } catch (const std::exception& e) {
        throw Error(ErrorKind::Io, path.string() + ": cannot write OpenEXR: " + e.what());
    }
}

Image Image::loadExr(const std::filesystem::path& path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw Error(ErrorKind::Io, path.string() + ": file does not exist");
    try {
        Imf::InputFile file(path.string().c_str());
        const Imath::Box2i window = file.header().dataWindow();
        const long long width = static_cast<long long>(window.max.x) - window.min.x + 1;
        const long long height = static_cast<long long>(window.max.y) - window.min.y + 1;
        if (width < 1 || height < 1 || width > kMaxImageSide || height > kMaxImageSide)
            throw Error(ErrorKind::InvalidArgument, path.string() + ": OpenEXR data window is " + std::to_string(width) +
                                                        "x" + std::to_string(height) + ", outside 1..16384");
        Image image(static_cast<int>(width), static_cast<int>(height), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
        Imf::FrameBuffer frame;
        const std::size_t pixel = 4 * sizeof(float), row = pixel * static_cast<std::size_t>(width);
        // The slice base is where pixel (0, 0) of the data window's coordinate system would be.
        char* base = reinterpret_cast<char*>(image.data().data()) - static_cast<std::ptrdiff_t>(window.min.x) *
                     static_cast<std::ptrdiff_t>(pixel) - static_cast<std::ptrdiff_t>(window.min.y) *
                     static_cast<std::ptrdiff_t>(row);
        for (int c = 0; c < 4; ++c)
            frame.insert(kExrChannels[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), pixel, row, 1, 1,
                                                     c == 3 ? 1.0 : 0.0));
        file.setFrameBuffer(frame);
        file.readPixels(window.min.y, window.max.y);
        return image;
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(ErrorKind::Parse, path.string() + ": cannot read OpenEXR: " + e.what());
    }
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

void Image8::savePng(const std::filesystem::path& path) const {
    const std::string file = path.string();
    std::error_code ec;
    const std::filesystem::path parent = path.parent_path();
    if (!parent.empty() && !std::filesystem::is_directory(parent, ec))
        throw Error(ErrorKind::Io, file + ": cannot write PNG: directory " + parent.string() + " does not exist");
    if (!stbi_write_png(file.c_str(), m_width, m_height, 4, m_data.data(), m_width * 4))
        throw Error(ErrorKind::Io, file + ": cannot write PNG (not writable, or the disk is full)");
}

Image8 Image8::loadPng(const std::filesystem::path& path) {
    const std::string file = path.string();
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw Error(ErrorKind::Io, file + ": file does not exist");
    if (std::filesystem::is_directory(path, ec)) throw Error(ErrorKind::Io, file + ": is a directory, not a PNG");
    int w = 0, h = 0, channels = 0;
    std::unique_ptr<stbi_uc, void (*)(void*)> pixels(stbi_load(file.c_str(), &w, &h, &channels, 4), stbi_image_free);
    if (!pixels) {
        const char* reason = stbi_failure_reason();
        throw Error(ErrorKind::Parse, file + ": cannot decode image: " + (reason ? reason : "unknown stb_image error"));
    }
    if (w > kMaxImageSide || h > kMaxImageSide)
        throw Error(ErrorKind::InvalidArgument, file + ": image is " + std::to_string(w) + "x" + std::to_string(h) +
                                                    ", larger than the " + std::to_string(kMaxImageSide) +
                                                    " pixel limit");
    Image8 out(w, h);
    std::memcpy(out.m_data.data(), pixels.get(), out.m_data.size());
    return out;
}

}  // namespace sss
