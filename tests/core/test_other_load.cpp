// Other processes' load while a group is timed (other_load.h): /proc/stat's first line parsed,
// this process's own work not counted, busy processes beside it counted.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "common/core/other_load.h"
#include "common/core/process_cpu_clock.h"

namespace hybridlab {
namespace {

void spinFor(std::chrono::milliseconds d) {
    const auto end = std::chrono::steady_clock::now() + d;
    volatile unsigned long x = 0;
    while (std::chrono::steady_clock::now() < end) x = x + 1;
}

TEST(OtherLoad, ProcStatBusyTimeIsEverythingButIdleAndIoWait) {
    // user nice system idle iowait irq softirq steal guest guest_nice, in ticks of 1/100 s.
    const std::optional<double> s = busyCpuSeconds("cpu  100 20 30 5000 70 4 6 40 9 0", 100);
    ASSERT_TRUE(s);
    EXPECT_DOUBLE_EQ(*s, (100 + 20 + 30 + 4 + 6 + 40) / 100.0);
    EXPECT_DOUBLE_EQ(*busyCpuSeconds("cpu 1 2 3 4 5 6 7", 1), 1 + 2 + 3 + 6 + 7.0);  // no steal column (old kernels)
    EXPECT_FALSE(busyCpuSeconds("intr 1 2 3", 100));
    EXPECT_FALSE(busyCpuSeconds("cpu 1 2", 100));
}

TEST(OtherLoad, CountsOtherProcessesAndNotThisOne) {
    const long cores = sysconf(_SC_NPROCESSORS_ONLN);
    ASSERT_GT(cores, 0);
    {
        // This process busy on every core: its CPU time is not others', so the two shares add up
        // to at most the machine (counting its own would give up to twice that).
        const double cpuStart = processCpuMilliseconds();
        const auto wallStart = std::chrono::steady_clock::now();
        const OtherLoadMeter meter;
        std::vector<std::thread> spinners;
        for (long k = 0; k < cores; ++k) spinners.emplace_back([] { spinFor(std::chrono::milliseconds(400)); });
        for (std::thread& t : spinners) t.join();
        const std::optional<double> f = meter.fraction();
        const double wallMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wallStart).count();
        const double ownShare = (processCpuMilliseconds() - cpuStart) / (wallMs * static_cast<double>(cores));
        ASSERT_TRUE(f);
        // That it ran at all (its clock is read): its share of a machine loaded 10 deep on 2 cores
        // was 0.17, so more than that would be a bound on the load, not on the meter.
        EXPECT_GT(ownShare, 0.05);
        EXPECT_LE(*f + ownShare, 1.1) << "others " << *f << ", this process " << ownShare;
    }
    // A busy process on every core: nearly all of the machine is others'.
    std::vector<pid_t> children;
    for (long k = 0; k < cores; ++k) {
        const pid_t pid = fork();
        if (pid == 0) {
            spinFor(std::chrono::seconds(5));
            _exit(0);
        }
        children.push_back(pid);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    const OtherLoadMeter meter;
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    const std::optional<double> f = meter.fraction();
    for (pid_t pid : children) {
        kill(pid, SIGKILL);
        waitpid(pid, nullptr, 0);
    }
    ASSERT_TRUE(f);
    EXPECT_GT(*f, 0.6);
}

}  // namespace
}  // namespace hybridlab
