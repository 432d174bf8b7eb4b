#pragma once
// How much of the machine other processes used over an interval: the CPU time every core spent
// busy (/proc/stat, steal time included: a virtual machine's host taking the core) less this
// process's own, over the interval's wall time times the cores. Load slows settings unequally (a
// parallel frame waits for its preempted thread, a serial one barely notices: measured under two
// busy loops on two cores, 1.6x to 3.0x by setting), so wall-time ranks measured under load answer
// for a loaded machine, not an idle one; the runner records this beside each group's times and
// the report says where it was high.
#include <optional>

#include "common/core/wall_clock.h"

namespace hybridlab {

class OtherLoadMeter {
public:
    OtherLoadMeter();  // the interval starts here

    // Other processes' share of the machine's cores since construction, in [0, 1]; none where
    // /proc/stat cannot be read or no time has passed.
    std::optional<double> fraction() const;

private:
    std::optional<double> busyStartS_;  // every core's busy CPU time, seconds
    double ownStartMs_ = 0.0;
    WallClock::time_point wallStart_;
};

// Every core's busy CPU time so far in seconds (user, nice, system, irq, softirq, steal), from
// the first line of /proc/stat text; none if it is not such a line.
std::optional<double> busyCpuSeconds(const char* procStatText, long ticksPerSecond);

}  // namespace hybridlab
