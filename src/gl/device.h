#pragma once
// What the current context's GL device is, for choices made per device.
#include <cstdint>
#include <string_view>

namespace sss::gl {

/// True for the names software rasterisers give as GL_RENDERER (llvmpipe, softpipe,
/// SwiftShader, Apple's and Microsoft's software renderers).
bool isSoftwareRendererName(std::string_view renderer);

/// isSoftwareRendererName of the current context's GL_RENDERER.
bool currentDeviceIsSoftware();

/// GL_MAX_SHADER_STORAGE_BLOCK_SIZE of the current context: the most bytes a shader may reach
/// through one storage-buffer binding (llvmpipe: 128 MiB; past 2 GiB its offsets wrap), or what
/// setStorageBlockLimitForTesting set.
std::int64_t storageBlockLimit();

/// Makes storageBlockLimit() return `bytes` (0: the context's value again), so that tests can
/// reach the paths that split a buffer over several bindings with small data.
void setStorageBlockLimitForTesting(std::int64_t bytes);

/// setStorageBlockLimitForTesting(bytes) for as long as it lives, however the test ends.
class StorageBlockLimitForTesting {
public:
    explicit StorageBlockLimitForTesting(std::int64_t bytes) { setStorageBlockLimitForTesting(bytes); }
    ~StorageBlockLimitForTesting() { setStorageBlockLimitForTesting(0); }
    StorageBlockLimitForTesting(const StorageBlockLimitForTesting&) = delete;
    StorageBlockLimitForTesting& operator=(const StorageBlockLimitForTesting&) = delete;
};

}  // namespace sss::gl
