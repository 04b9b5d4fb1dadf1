#include "io/image_decoding.h"

#include "sss/error.h"
#include "sss/log.h"

#include <stb/stb_image.h>

#include <climits>
#include <cstring>
#include <functional>
#include <memory>
#include <string>

namespace sss::detail {
namespace {

using StbPixels = std::unique_ptr<stbi_uc, void (*)(void*)>;

std::string stbReason() {
    const char* reason = stbi_failure_reason();
    return reason ? reason : "unknown stb_image error";
}

// The size is checked from the header before decoding, so that an oversized image is rejected
// without allocating its pixels.
void checkSide(int w, int h, const std::string& name) {
    if (w > kMaxImageSide || h > kMaxImageSide)
        throw Error(ErrorKind::InvalidArgument, name + ": image is " + std::to_string(w) + "x" + std::to_string(h) +
                                                    ", larger than the " + std::to_string(kMaxImageSide) +
                                                    " pixel limit");
}

Image8 toImage8(StbPixels pixels, int w, int h, const std::string& name) {
    if (!pixels) throw Error(ErrorKind::Parse, name + ": cannot decode image: " + stbReason());
    checkSide(w, h, name);
    Image8 out(w, h);
    std::memcpy(out.data().data(), pixels.get(), out.data().size());
    return out;
}

std::shared_ptr<const Image8> orWarn(const std::function<Image8()>& read, const std::string& context) {
    try {
        return std::make_shared<const Image8>(read());
    } catch (const Error& e) {
        log(LogLevel::Warning, context + ": " + e.what() + "; the mesh loads without a texture");
        return nullptr;
    }
}

}  // namespace

Image8 readImage8(const std::filesystem::path& path) {
    const std::string file = path.string();
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw Error(ErrorKind::Io, file + ": file does not exist");
    if (std::filesystem::is_directory(path, ec)) throw Error(ErrorKind::Io, file + ": is a directory, not an image");
    // A device or FIFO would block the read or never end.
    if (!std::filesystem::is_regular_file(path, ec)) throw Error(ErrorKind::Io, file + ": is not a regular file");
    int w = 0, h = 0, channels = 0;
    if (stbi_info(file.c_str(), &w, &h, &channels)) checkSide(w, h, file);
    return toImage8(StbPixels(stbi_load(file.c_str(), &w, &h, &channels, 4), stbi_image_free), w, h, file);
}

Image8 decodeImage8(std::string_view bytes, const std::string& name) {
    if (bytes.size() > static_cast<std::size_t>(INT_MAX))
        throw Error(ErrorKind::InvalidArgument, name + ": image of " + std::to_string(bytes.size()) +
                                                    " bytes is larger than stb_image reads");
    const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
    const int size = static_cast<int>(bytes.size());
    int w = 0, h = 0, channels = 0;
    if (stbi_info_from_memory(data, size, &w, &h, &channels)) checkSide(w, h, name);
    return toImage8(StbPixels(stbi_load_from_memory(data, size, &w, &h, &channels, 4), stbi_image_free), w, h, name);
}

std::shared_ptr<const Image8> loadTextureOrWarn(const std::filesystem::path& path, const std::string& context) {
    return orWarn([&] { return readImage8(path); }, context);
}

std::shared_ptr<const Image8> decodeTextureOrWarn(std::string_view bytes, const std::string& name,
                                                  const std::string& context) {
    return orWarn([&] { return decodeImage8(bytes, name); }, context);
}

}  // namespace sss::detail
