// Real-time priority for timed frames (realtime_priority.h): every thread of the process under
// SCHED_FIFO while the scope lives, each thread's own policy back after it, and a refusal naming
// what would allow it where the process lacks the privilege.
#include "common/core/realtime_priority.h"

#include <sched.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <atomic>
#include <thread>

#include <gtest/gtest.h>

#include "tests/support/realtime_privilege.h"

namespace hybridlab {
namespace {

pid_t threadId() { return static_cast<pid_t>(syscall(SYS_gettid)); }

int policyOf(pid_t thread) { return sched_getscheduler(thread) & ~SCHED_RESET_ON_FORK; }

int priorityOf(pid_t thread) {
    sched_param p{};
    sched_getparam(thread, &p);
    return p.sched_priority;
}

// A thread that reports its id and waits until told to end.
class Sleeper {
public:
    Sleeper() : thread_([this] {
          id_ = threadId();
          while (!stop_) std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }) {
        while (id_ == 0) std::this_thread::yield();
    }
    ~Sleeper() {
        stop_ = true;
        thread_.join();
    }
    pid_t id() const { return id_; }

private:
    std::atomic<pid_t> id_{0};
    std::atomic<bool> stop_{false};
    std::thread thread_;
};

TEST(RealTimePriority, EveryThreadRunsAheadThenGetsItsOwnPolicyBack) {
    if (const auto reason = realTimePriorityUnavailable()) GTEST_SKIP() << *reason;
    Sleeper before;
    const sched_param zero{};
    ASSERT_EQ(sched_setscheduler(before.id(), SCHED_BATCH, &zero), 0);  // a policy of its own, like Mesa's compiler thread
    const pid_t self = threadId();
    ASSERT_EQ(policyOf(self), SCHED_OTHER);
    std::optional<Sleeper> bornInside;
    {
        const RealTimePriority ahead;
        for (const pid_t t : {self, before.id()}) {
            EXPECT_EQ(policyOf(t), SCHED_FIFO) << t;
            EXPECT_EQ(priorityOf(t), kTimingRealTimePriority) << t;
        }
        bornInside.emplace();
        EXPECT_EQ(policyOf(bornInside->id()), SCHED_FIFO);  // inherited from its parent
    }
    EXPECT_EQ(policyOf(self), SCHED_OTHER);
    EXPECT_EQ(policyOf(before.id()), SCHED_BATCH);
    EXPECT_EQ(policyOf(bornInside->id()), SCHED_OTHER);
    EXPECT_EQ(priorityOf(self), 0);
}

TEST(RealTimePriority, RefusedWithoutThePrivilegeNamingWhatAllowsIt) {
    // 0: refused as asked; 1: not refused; 2: wrong message; 3: no exception; 4: policy changed.
    const int status = test::inChildWithoutRealTimePrivilege(0, [] {
        const auto reason = realTimePriorityUnavailable();
        if (!reason) return 1;
        for (const char* what : {"may not run at real-time priority", "CAP_SYS_NICE", "ulimit -r"})
            if (reason->find(what) == std::string::npos) return 2;
        try {
            const RealTimePriority ahead;
            return 3;
        } catch (const std::runtime_error& e) {
            if (std::string(e.what()) != *reason) return 2;
        }
        return policyOf(0) == SCHED_OTHER ? 0 : 4;
    });
    if (status == test::kChildCannotDrop) GTEST_SKIP() << "this process cannot drop CAP_SYS_NICE";
    EXPECT_EQ(status, 0);
}

TEST(RealTimePriority, AnRtprioLimitIsEnoughWithoutTheCapability) {
    // Where a normal user's limits allow priority 10 (`ulimit -r 10`), the process may.
    const int status = test::inChildWithoutRealTimePrivilege(kTimingRealTimePriority, [] {
        if (realTimePriorityUnavailable()) return 1;
        const RealTimePriority ahead;
        return policyOf(0) == SCHED_FIFO ? 0 : 4;
    });
    if (status == test::kChildCannotDrop) GTEST_SKIP() << "this process cannot raise its RLIMIT_RTPRIO to 10 (that needs CAP_SYS_RESOURCE)";
    EXPECT_EQ(status, 0);
}

}  // namespace
}  // namespace hybridlab
