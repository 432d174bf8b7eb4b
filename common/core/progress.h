#pragma once
// Progress of a long run on stderr: a bar with runs done, the current run and the estimated time
// left on a terminal; plain log lines otherwise (CI logs, redirected output).
#include <chrono>
#include <cstddef>
#include <string>

namespace hybridlab {

class Progress {
public:
    // `unit` names one step in plain log lines ("run 3/8", "bake step 3/8").
    Progress(std::size_t total, bool quiet, std::string unit = "run");
    // `runs` runs start now (a group's, timed together), `done` before them.
    void start(std::size_t done, const std::string& current, std::size_t runs = 1);
    void finish();

private:
    std::size_t total_;
    bool quiet_;
    bool terminal_;
    std::string unit_;
    std::size_t started_ = 0;
    std::chrono::steady_clock::time_point begin_;
};

}  // namespace hybridlab
