#pragma once
// One way to spread independent work items over threads, for the CPU references.
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace sss::detail {

/// Runs body(state, index) for every index in [0, count), handing the indices out in order to
/// `threads` threads (0: one per core; the calling thread is one of them). Each thread makes its
/// own state with makeState() and hands it to finish(state) when it runs out of work, one thread
/// at a time. The first exception a thread throws stops the others and is rethrown here.
template <typename MakeState, typename Body, typename Finish>
void parallelFor(int threads, std::int64_t count, MakeState makeState, Body body, Finish finish) {
    if (count <= 0) return;
    if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    threads = static_cast<int>(std::clamp<std::int64_t>(threads, 1, count));
    std::atomic<std::int64_t> next{0};
    std::mutex mutex;
    std::exception_ptr failure;
    auto worker = [&] {
        try {
            auto state = makeState();
            for (std::int64_t i = next++; i < count; i = next++) body(state, i);
            const std::lock_guard lock(mutex);
            finish(state);
        } catch (...) {
            const std::lock_guard lock(mutex);
            if (!failure) failure = std::current_exception();
            next = count;
        }
    };
    std::vector<std::thread> pool;
    for (int i = 1; i < threads; ++i) pool.emplace_back(worker);
    worker();
    for (std::thread& t : pool) t.join();
    if (failure) std::rethrow_exception(failure);
}

}  // namespace sss::detail
