#pragma once
// What the current context's GL device is, for choices made per device.
#include <string_view>

namespace sss::gl {

/// True for the names software rasterisers give as GL_RENDERER (llvmpipe, softpipe,
/// SwiftShader, Apple's and Microsoft's software renderers).
bool isSoftwareRendererName(std::string_view renderer);

/// isSoftwareRendererName of the current context's GL_RENDERER.
bool currentDeviceIsSoftware();

}  // namespace sss::gl
