#include "gl/device.h"

#include "gl/gl.h"

namespace sss::gl {
namespace {
std::int64_t g_storageBlockLimitForTesting = 0;
}  // namespace

bool isSoftwareRendererName(std::string_view renderer) {
    for (std::string_view soft : {"llvmpipe", "softpipe", "SwiftShader", "Software Rasterizer"})
        if (renderer.find(soft) != std::string_view::npos) return true;
    return false;
}

bool currentDeviceIsSoftware() {
    const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    return renderer && isSoftwareRendererName(renderer);
}

std::int64_t storageBlockLimit() {
    if (g_storageBlockLimitForTesting > 0) return g_storageBlockLimitForTesting;
    GLint64 limit = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &limit);
    return limit;
}

void setStorageBlockLimitForTesting(std::int64_t bytes) { g_storageBlockLimitForTesting = bytes; }

}  // namespace sss::gl
