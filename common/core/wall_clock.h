#pragma once
// Host wall-clock time for timing work (steady_clock: it never goes back), in milliseconds, the
// unit of every time the program records. Frames' stages are timed with techniques/stage_clock.h
// on top of it.
#include <chrono>

namespace hybridlab {

using WallClock = std::chrono::steady_clock;

inline double millisecondsBetween(WallClock::time_point start, WallClock::time_point end) {
    return std::chrono::duration<double, std::milli>(end - start).count();
}

inline double millisecondsSince(WallClock::time_point start) { return millisecondsBetween(start, WallClock::now()); }

}  // namespace hybridlab
