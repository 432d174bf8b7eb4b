#pragma once
// Wall-clock timing of consecutive stages: a frame's (FrameResult::stages, named from
// stage_names.h) or a bake's. Laps cover the whole time from the clock's start, so the stages add
// up to the wall clock.
#include <algorithm>
#include <string>
#include <vector>

#include "techniques/technique.h"
#include "common/core/wall_clock.h"

namespace hybridlab {

class StageClock {
public:
    explicit StageClock(std::vector<StageTime>& stages) : stages_(stages), start_(WallClock::now()) {}
    explicit StageClock(FrameResult& result) : StageClock(result.stages) {}

    // Ends the current stage under `name` and starts the next. A name timed before gets the time
    // added, so work done in a loop is one stage.
    void lap(const std::string& name) { lap({}, name); }

    // Ends the current stage split into the parts timed inside it (each added as lap adds it) and
    // the rest of its time under `rest` (0 when the parts cover it).
    void lap(const std::vector<StageTime>& parts, const std::string& rest) {
        const auto now = WallClock::now();
        double remaining = millisecondsBetween(start_, now);
        for (const StageTime& p : parts) {
            add(p.name, p.milliseconds);
            remaining -= p.milliseconds;
        }
        add(rest, std::max(0.0, remaining));
        start_ = now;
    }

private:
    void add(const std::string& name, double milliseconds) {
        auto it = std::find_if(stages_.begin(), stages_.end(), [&](const StageTime& s) { return s.name == name; });
        if (it == stages_.end()) stages_.push_back({name, milliseconds});
        else it->milliseconds += milliseconds;
    }

    std::vector<StageTime>& stages_;
    WallClock::time_point start_;
};

}  // namespace hybridlab
