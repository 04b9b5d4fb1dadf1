#include "gl/allocation.h"

#include "sss/error.h"
#include "sss/gpu_memory.h"
#include "sss/log.h"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace sss {
namespace {

std::atomic<std::uint64_t> g_inUse{0};

std::uint64_t budgetFromEnvironment() {
    const char* text = std::getenv("SSS_GPU_MEMORY_BUDGET_MB");
    if (!text || !*text) return 0;
    char* end = nullptr;
    const double mb = std::strtod(text, &end);
    if (end == text || *end != '\0' || !(mb >= 0.0) || mb > 1e12) {
        log(LogLevel::Warning, std::string("SSS_GPU_MEMORY_BUDGET_MB=\"") + text +
                                   "\" is not a number of megabytes >= 0; no budget is set");
        return 0;
    }
    return static_cast<std::uint64_t>(mb * 1024.0 * 1024.0);
}

std::atomic<std::uint64_t>& budget() {
    static std::atomic<std::uint64_t> value{budgetFromEnvironment()};
    return value;
}

bool hasExtension(const char* name) {
    GLint count = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &count);
    for (GLint i = 0; i < count; ++i) {
        const auto* ext = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, static_cast<GLuint>(i)));
        if (ext && std::strcmp(ext, name) == 0) return true;
    }
    return false;
}

// Not in the core-only glad loader; the values are from the extension specifications.
constexpr GLenum kDedicatedVidmemNvx = 0x9047;        // GL_GPU_MEMORY_INFO_DEDICATED_VIDMEM_NVX (kB)
constexpr GLenum kCurrentAvailableVidmemNvx = 0x9049; // GL_GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX (kB)
constexpr GLenum kTextureFreeMemoryAti = 0x87FC;      // GL_TEXTURE_FREE_MEMORY_ATI (4 values, kB)

}  // namespace

GpuLimits queryGpuLimits() {
    GpuLimits limits;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &limits.maxTextureSize);
    glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &limits.max3DTextureSize);
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &limits.maxArrayTextureLayers);
    if (hasExtension("GL_NVX_gpu_memory_info")) {
        GLint total = 0, available = 0;
        glGetIntegerv(kDedicatedVidmemNvx, &total);
        glGetIntegerv(kCurrentAvailableVidmemNvx, &available);
        limits.totalMemoryBytes = static_cast<std::uint64_t>(total) * 1024u;
        limits.availableMemoryBytes = static_cast<std::uint64_t>(available) * 1024u;
    } else if (hasExtension("GL_ATI_meminfo")) {
        GLint free[4] = {0, 0, 0, 0};
        glGetIntegerv(kTextureFreeMemoryAti, free);
        limits.availableMemoryBytes = static_cast<std::uint64_t>(free[0]) * 1024u;
    }
    return limits;
}

void setGpuMemoryBudget(std::uint64_t bytes) { budget() = bytes; }
std::uint64_t gpuMemoryBudget() { return budget(); }
std::uint64_t gpuMemoryInUse() { return g_inUse; }

namespace gl {
namespace {

struct PendingAllocation {
    bool active = false;
    std::string message;  // the GL error message received during the allocation, if any
};
thread_local PendingAllocation t_pending;

std::string glErrorName(GLenum e) {
    switch (e) {
        case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
        case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
        case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
        case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
        default: {
            char buf[16];
            std::snprintf(buf, sizeof buf, "0x%04X", e);
            return buf;
        }
    }
}

}  // namespace

void MemoryReservation::release() noexcept {
    if (m_bytes) g_inUse -= m_bytes;
    m_bytes = 0;
}

std::string formatBytes(std::uint64_t bytes) {
    const char* units[] = {"bytes", "kiB", "MiB", "GiB", "TiB"};
    double value = static_cast<double>(bytes);
    int unit = 0;
    while (value >= 1024.0 && unit < 4) {
        value /= 1024.0;
        ++unit;
    }
    char buf[32];
    if (unit == 0)
        std::snprintf(buf, sizeof buf, "%llu bytes", static_cast<unsigned long long>(bytes));
    else
        std::snprintf(buf, sizeof buf, "%.3g %s", value, units[unit]);
    return buf;
}

MemoryReservation allocateChecked(std::string_view what, std::string_view description, std::uint64_t bytes,
                                  const std::function<void()>& allocate) {
    const std::string subject = std::string(what) + ": " + std::string(description) + " (" + formatBytes(bytes) + ")";
    if (const std::uint64_t cap = budget(); cap != 0 && g_inUse + bytes > cap)
        throw Error(ErrorKind::GpuLimit, subject + " does not fit the GPU memory budget of " + formatBytes(cap) +
                                             ": libsss already holds " + formatBytes(g_inUse) +
                                             " (setGpuMemoryBudget, SSS_GPU_MEMORY_BUDGET_MB)");
    if (const std::uint64_t free = queryGpuLimits().availableMemoryBytes; free != 0 && bytes > free)
        throw Error(ErrorKind::GpuLimit, subject + " is more than the GPU has free (" + formatBytes(free) + ")");

    // Errors left by earlier calls would be blamed on this allocation; they are bugs elsewhere.
    for (GLenum stale = glGetError(); stale != GL_NO_ERROR; stale = glGetError())
        log(LogLevel::Warning, "GL error " + glErrorName(stale) + " was pending before allocating " + subject);

    t_pending = {true, {}};
    allocate();
    const GLenum error = glGetError();
    const std::string message = std::move(t_pending.message);
    t_pending = {};
    if (error == GL_OUT_OF_MEMORY) {
        if (!message.empty()) log(LogLevel::Warning, message + " (handled: " + subject + ")");
        throw Error(ErrorKind::GpuLimit, subject + ": the driver is out of memory (GL_OUT_OF_MEMORY)");
    }
    if (error != GL_NO_ERROR || !message.empty()) {
        // Not an allocation failure: a libsss bug. Report it as the GL error it is.
        const std::string text = message.empty() ? glErrorName(error) + " allocating " + subject
                                                 : message + " (allocating " + subject + ")";
        glDebugMessageInsert(GL_DEBUG_SOURCE_APPLICATION, GL_DEBUG_TYPE_ERROR, 1, GL_DEBUG_SEVERITY_HIGH, -1,
                             text.c_str());
        throw Error(ErrorKind::Gl, "unexpected " + glErrorName(error) + " allocating " + subject);
    }
    g_inUse += bytes;
    return MemoryReservation(bytes);
}

bool deferAllocationError(std::string_view message) {
    if (!t_pending.active) return false;
    if (t_pending.message.empty()) t_pending.message = std::string(message);
    return true;
}

}  // namespace gl
}  // namespace sss
