#pragma once
// Checked GPU allocations. Every texture and buffer libsss creates goes through here, so that a
// request the implementation cannot satisfy becomes Error(ErrorKind::GpuLimit) naming the
// object, the size asked and the limit, instead of a GL error and a blank picture.
//
// Checked before: implementation size limits (by the texture code), the budget of
// setGpuMemoryBudget() and the driver's free memory where it tells. Checked after:
// GL_OUT_OF_MEMORY (llvmpipe, for one, refuses single resources over 1 GiB). The KHR_debug
// callback reports an out-of-memory error raised inside a checked allocation as a warning,
// not as a libsss bug, because the allocation turns it into an Error the caller sees.

#include "gl/gl.h"

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

namespace sss::gl {

/// Bytes one allocation holds, counted in gpuMemoryInUse() while the reservation lives.
class MemoryReservation {
public:
    MemoryReservation() = default;
    ~MemoryReservation() { release(); }
    MemoryReservation(const MemoryReservation&) = delete;
    MemoryReservation& operator=(const MemoryReservation&) = delete;
    MemoryReservation(MemoryReservation&& other) noexcept : m_bytes(other.m_bytes) { other.m_bytes = 0; }
    MemoryReservation& operator=(MemoryReservation&& other) noexcept {
        if (this != &other) {
            release();
            m_bytes = other.m_bytes;
            other.m_bytes = 0;
        }
        return *this;
    }
    std::uint64_t bytes() const { return m_bytes; }

private:
    friend MemoryReservation allocateChecked(std::string_view, std::string_view, std::uint64_t,
                                             const std::function<void()>&);
    explicit MemoryReservation(std::uint64_t bytes) : m_bytes(bytes) {}
    void release() noexcept;
    std::uint64_t m_bytes = 0;
};

/// Reserves `bytes` for the object `what` (described as `description`, e.g. "256x256x256 R8
/// texture"), runs `allocate` (one glTextureStorage* or glNamedBufferStorage call) and checks
/// it. Throws Error(GpuLimit) if the budget or the driver's free memory is too small, or if the
/// driver answers GL_OUT_OF_MEMORY; `allocate` has then allocated nothing the caller must keep.
MemoryReservation allocateChecked(std::string_view what, std::string_view description, std::uint64_t bytes,
                                  const std::function<void()>& allocate);

/// "1.5 GiB", "512 MiB", "64 kiB", "12 bytes".
std::string formatBytes(std::uint64_t bytes);

/// Called by the KHR_debug callback for every GL error message. While a checked allocation runs
/// on this thread it keeps the message and returns true: allocateChecked() then decides, from
/// glGetError(), whether it was the out-of-memory answer it handles (logged as a warning) or a
/// real error (sent again through glDebugMessageInsert, so it counts as one).
bool deferAllocationError(std::string_view message);

}  // namespace sss::gl
