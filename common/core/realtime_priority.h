#pragma once
// Timing ahead of other processes (`run --realtime`): while a RealTimePriority lives, every thread
// of this process runs under SCHED_FIFO, so that a normal process's load no longer decides which
// setting is faster. Interleaving cannot cancel load: it slows settings unequally (under two busy
// loops on a two-core machine, 1.7x to 4.4x by setting, because a parallel Embree frame waits for
// its preempted thread and a mostly serial lavapipe one barely notices), while at real-time
// priority the busy loops only run in what the kernel's real-time throttling leaves them (by
// default 5% of each second, /proc/sys/kernel/sched_rt_runtime_us), which also keeps a runaway
// frame from taking the machine. Threads started meanwhile inherit the policy from their parent;
// at the end each thread gets its own policy back (those started meanwhile the normal one).
#include <sys/types.h>

#include <optional>
#include <string>
#include <vector>

namespace hybridlab {

// Below the kernel's threaded interrupt handlers (SCHED_FIFO 50), above every normal process.
constexpr int kTimingRealTimePriority = 10;

// Why this process may not run at real-time priority (a sentence naming what would allow it), or
// none where it may. Leaves the calling thread's policy as it was.
std::optional<std::string> realTimePriorityUnavailable();

class RealTimePriority {
public:
    // Throws std::runtime_error (with realTimePriorityUnavailable()'s reason) where the process
    // may not; every thread is back to its own policy then.
    explicit RealTimePriority(int priority = kTimingRealTimePriority);
    ~RealTimePriority();
    RealTimePriority(const RealTimePriority&) = delete;
    RealTimePriority& operator=(const RealTimePriority&) = delete;

private:
    struct SavedPolicy {
        pid_t thread;
        int policy;
        int priority;
    };
    void restore() noexcept;
    std::vector<SavedPolicy> saved_;
};

}  // namespace hybridlab
