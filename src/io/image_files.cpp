// The image files (declared in sss/image.h, built in the io component): PNG through stb,
// OpenEXR through the OpenEXR library when libsss is built with SSS_WITH_OPENEXR.
#include "sss/image.h"

#include "io/image_decoding.h"

#include "sss/error.h"

#if SSS_WITH_OPENEXR
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#endif
#include <stb/stb_image_write.h>

#include <string>

namespace sss {

void Image::savePng(const std::filesystem::path& path) const { toRgba8().savePng(path); }

#if SSS_WITH_OPENEXR

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

#else

namespace {
[[noreturn]] void exrNotBuilt(const std::filesystem::path& path) {
    throw Error(ErrorKind::Unsupported, path.string() +
                ": OpenEXR files need libsss built with SSS_WITH_OPENEXR=ON (libopenexr-dev)");
}
}  // namespace

void Image::saveExr(const std::filesystem::path& path) const { exrNotBuilt(path); }
Image Image::loadExr(const std::filesystem::path& path) { exrNotBuilt(path); }

#endif

void Image8::savePng(const std::filesystem::path& path) const {
    const std::string file = path.string();
    std::error_code ec;
    const std::filesystem::path parent = path.parent_path();
    if (!parent.empty() && !std::filesystem::is_directory(parent, ec))
        throw Error(ErrorKind::Io, file + ": cannot write PNG: directory " + parent.string() + " does not exist");
    if (!stbi_write_png(file.c_str(), m_width, m_height, 4, m_data.data(), m_width * 4))
        throw Error(ErrorKind::Io, file + ": cannot write PNG (not writable, or the disk is full)");
}

// PNG, JPEG, TGA, BMP, ...: any format stb_image decodes (src/io/image_decoding.cpp).
Image8 Image8::loadPng(const std::filesystem::path& path) { return detail::readImage8(path); }

}  // namespace sss
