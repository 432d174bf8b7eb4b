#pragma once
// CPU time of every thread of this process (user and system, lavapipe's and TBB's workers
// included), in milliseconds. On a shared machine it moves far less with other processes' load
// than the wall clock does: the experiment runner records it per frame beside the wall time.
#include <sys/resource.h>

namespace hybridlab {

inline double processCpuMilliseconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    auto ms = [](const timeval& t) { return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_usec) * 1e-3; };
    return ms(u.ru_utime) + ms(u.ru_stime);
}

}  // namespace hybridlab
