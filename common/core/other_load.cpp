#include "common/core/other_load.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>

#include "common/core/process_cpu_clock.h"
#include "common/core/wall_clock.h"

namespace hybridlab {

namespace {

std::optional<double> readBusySeconds() {
    std::ifstream in("/proc/stat");
    std::string line;
    if (!in || !std::getline(in, line)) return std::nullopt;
    return busyCpuSeconds(line.c_str(), sysconf(_SC_CLK_TCK));
}

}  // namespace

std::optional<double> busyCpuSeconds(const char* procStatText, long ticksPerSecond) {
    unsigned long long user, nice, system, idle, iowait, irq, softirq, steal = 0;
    const int n = std::sscanf(procStatText, "cpu %llu %llu %llu %llu %llu %llu %llu %llu", &user, &nice, &system, &idle, &iowait, &irq,
                              &softirq, &steal);
    if (n < 7 || ticksPerSecond <= 0) return std::nullopt;
    // guest time is counted in user already.
    return static_cast<double>(user + nice + system + irq + softirq + steal) / static_cast<double>(ticksPerSecond);
}

OtherLoadMeter::OtherLoadMeter() : busyStartS_(readBusySeconds()), ownStartMs_(processCpuMilliseconds()), wallStart_(WallClock::now()) {}

std::optional<double> OtherLoadMeter::fraction() const {
    const std::optional<double> busyNow = readBusySeconds();
    const double wallS = millisecondsSince(wallStart_) / 1000.0;
    const long cores = sysconf(_SC_NPROCESSORS_ONLN);
    if (!busyStartS_ || !busyNow || wallS <= 0.0 || cores <= 0) return std::nullopt;
    const double others = (*busyNow - *busyStartS_) - (processCpuMilliseconds() - ownStartMs_) / 1000.0;
    return std::clamp(others / (wallS * static_cast<double>(cores)), 0.0, 1.0);
}

}  // namespace hybridlab
