#pragma once
// The time spent inside Embree's calls (rtcIntersect1, rtcIntersect8, rtcOccluded1, with the
// filter functions they call back), summed over the calls a RayScene makes while a clock is set
// (RayScene::setCallClock). `hybridlab bench` splits the reference's frame with it into traversal
// and the work around it (hit resolution, shading, recursion), without a profiler. Readings come
// from the processor's time-stamp counter where there is one: a few nanoseconds each, against
// about 20 for the system clock, which would add half of whitted-classic's traversal time again.
#include <atomic>
#include <chrono>
#include <cstdint>
#if defined(__x86_64__) || defined(__i386__)
#include <x86intrin.h>
#endif

namespace hybridlab {

class EmbreeCallClock {
public:
    // Ticks of the time-stamp counter (or nanoseconds without one); convert by a span also timed
    // with the system clock.
    static std::uint64_t now() {
#if defined(__x86_64__) || defined(__i386__)
        return __rdtsc();
#else
        return static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
#endif
    }

    // One call's ticks. Atomic: the counters are shared by every thread that traces (bench times a
    // frame on one, where they are uncontended).
    void add(std::uint64_t ticks) {
        ticks_.fetch_add(ticks, std::memory_order_relaxed);
        calls_.fetch_add(1, std::memory_order_relaxed);
    }
    std::uint64_t ticks() const { return ticks_.load(std::memory_order_relaxed); }
    std::uint64_t calls() const { return calls_.load(std::memory_order_relaxed); }

private:
    std::atomic<std::uint64_t> ticks_{0};
    std::atomic<std::uint64_t> calls_{0};
};

// Runs `call`, timed on `clock` when there is one.
template <typename Call>
inline void timedEmbreeCall(EmbreeCallClock* clock, Call&& call) {
    if (!clock) {
        call();
        return;
    }
    const std::uint64_t start = EmbreeCallClock::now();
    call();
    clock->add(EmbreeCallClock::now() - start);
}

}  // namespace hybridlab
