#include "gl/device.h"

#include "gl/gl.h"

namespace sss::gl {

bool isSoftwareRendererName(std::string_view renderer) {
    for (std::string_view soft : {"llvmpipe", "softpipe", "SwiftShader", "Software Rasterizer"})
        if (renderer.find(soft) != std::string_view::npos) return true;
    return false;
}

bool currentDeviceIsSoftware() {
    const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    return renderer && isSoftwareRendererName(renderer);
}

}  // namespace sss::gl
