#include "common/core/realtime_priority.h"

#include <dirent.h>
#include <sched.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace hybridlab {

namespace {

std::string reasonFor(int error) {
    return std::string("this process may not run at real-time priority (sched_setscheduler: ") + std::strerror(error) +
           "): run it as root or with CAP_SYS_NICE (in a container: --cap-add SYS_NICE), or raise its real-time limit "
           "(`ulimit -r`, RLIMIT_RTPRIO) to at least " + std::to_string(kTimingRealTimePriority);
}

// The ids of this process's threads (/proc/self/task).
std::vector<pid_t> threads() {
    std::vector<pid_t> out;
    DIR* dir = opendir("/proc/self/task");
    if (!dir) return out;
    while (const dirent* e = readdir(dir)) {
        if (e->d_name[0] >= '0' && e->d_name[0] <= '9') out.push_back(static_cast<pid_t>(std::atol(e->d_name)));
    }
    closedir(dir);
    return out;
}

}  // namespace

std::optional<std::string> realTimePriorityUnavailable() {
    const int policy = sched_getscheduler(0);
    sched_param before{};
    sched_getparam(0, &before);
    sched_param fifo{};
    fifo.sched_priority = kTimingRealTimePriority;
    if (sched_setscheduler(0, SCHED_FIFO, &fifo) != 0) return reasonFor(errno);
    sched_setscheduler(0, policy & ~SCHED_RESET_ON_FORK, &before);
    return std::nullopt;
}

RealTimePriority::RealTimePriority(int priority) {
    sched_param fifo{};
    fifo.sched_priority = priority;
    // Until no thread is new: one started between the listing and its parent's change is not in
    // the listing and may have inherited the normal policy.
    for (bool changed = true; changed;) {
        changed = false;
        for (const pid_t t : threads()) {
            if (std::any_of(saved_.begin(), saved_.end(), [t](const SavedPolicy& s) { return s.thread == t; })) continue;
            const int policy = sched_getscheduler(t);
            sched_param own{};
            if (policy < 0 || sched_getparam(t, &own) != 0) continue;  // it ended meanwhile
            if (sched_setscheduler(t, SCHED_FIFO, &fifo) != 0) {
                if (errno == ESRCH) continue;
                const int error = errno;
                restore();
                throw std::runtime_error(reasonFor(error));
            }
            saved_.push_back({t, policy & ~SCHED_RESET_ON_FORK, own.sched_priority});
            changed = true;
        }
    }
}

RealTimePriority::~RealTimePriority() { restore(); }

void RealTimePriority::restore() noexcept {
    for (const pid_t t : threads()) {
        const auto s = std::find_if(saved_.begin(), saved_.end(), [t](const SavedPolicy& p) { return p.thread == t; });
        sched_param param{};
        param.sched_priority = s != saved_.end() ? s->priority : 0;
        sched_setscheduler(t, s != saved_.end() ? s->policy : SCHED_OTHER, &param);  // ESRCH: it ended meanwhile
    }
    saved_.clear();
}

}  // namespace hybridlab
