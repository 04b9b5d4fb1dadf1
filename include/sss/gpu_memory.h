#pragma once
/// @file
/// What fits on the GPU. Every texture and buffer libsss creates is checked before it is
/// allocated (against the implementation's size limits, the driver's free memory where the
/// driver tells, and an optional budget) and after (GL_OUT_OF_MEMORY). A request that does not
/// fit throws Error(ErrorKind::GpuLimit) naming the object, the size asked and the limit; the
/// volume renderer's light volumes fall back to a lower resolution instead (see
/// VolumeRenderOptions::lightVolumeFallback).

#include "sss/api.h"
#include <cstdint>

SSS_BEGIN_API

namespace sss {

/// What the current context's implementation allows.
struct GpuLimits {
    int maxTextureSize = 0;         ///< GL_MAX_TEXTURE_SIZE: width and height of 2D (array) textures
    int max3DTextureSize = 0;       ///< GL_MAX_3D_TEXTURE_SIZE: each side of a 3D texture
    int maxArrayTextureLayers = 0;  ///< GL_MAX_ARRAY_TEXTURE_LAYERS
    /// Dedicated video memory and what is free of it now, in bytes, where the driver tells
    /// (GL_NVX_gpu_memory_info, GL_ATI_meminfo); 0 where it does not (Mesa's llvmpipe).
    std::uint64_t totalMemoryBytes = 0;
    std::uint64_t availableMemoryBytes = 0;
};

/// Queries the current context. Needs a current GlContext.
GpuLimits queryGpuLimits();

/// Caps the bytes of GPU textures and buffers libsss holds at once, over all contexts of the
/// process (0: no cap, the default). An allocation that would pass the cap throws
/// Error(GpuLimit). The environment variable SSS_GPU_MEMORY_BUDGET_MB sets the initial value.
/// Thread-safe.
void setGpuMemoryBudget(std::uint64_t bytes);
std::uint64_t gpuMemoryBudget();

/// Bytes of GPU textures and buffers libsss holds now (their storage as allocated, not the
/// driver's padding).
std::uint64_t gpuMemoryInUse();

}  // namespace sss

SSS_END_API
