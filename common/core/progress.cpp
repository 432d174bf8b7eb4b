#include "common/core/progress.h"

#include <unistd.h>

#include <cstdio>
#include <utility>

namespace hybridlab {

Progress::Progress(std::size_t total, bool quiet, std::string unit)
    : total_(total), quiet_(quiet), terminal_(::isatty(STDERR_FILENO) != 0), unit_(std::move(unit)), begin_(std::chrono::steady_clock::now()) {}

void Progress::start(std::size_t done, const std::string& current, std::size_t runs) {
    if (quiet_) return;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin_).count();
    char eta[32] = "?";
    if (started_ > 0) {
        const double left = elapsed / static_cast<double>(started_) * static_cast<double>(total_ - done);
        std::snprintf(eta, sizeof eta, "%dm%02ds", static_cast<int>(left) / 60, static_cast<int>(left) % 60);
    }
    started_ += runs;
    if (terminal_) {
        constexpr int kWidth = 30;
        const int filled = total_ ? static_cast<int>(kWidth * done / total_) : kWidth;
        std::fprintf(stderr, "\r\033[K[%.*s%*s] %zu/%zu  left %s  %s", filled, "##############################", kWidth - filled, "", done,
                     total_, eta, current.c_str());
    } else {
        if (runs == 1) std::fprintf(stderr, "%s %zu/%zu (left %s): %s\n", unit_.c_str(), done + 1, total_, eta, current.c_str());
        else std::fprintf(stderr, "%ss %zu-%zu/%zu (left %s): %s\n", unit_.c_str(), done + 1, done + runs, total_, eta, current.c_str());
    }
    std::fflush(stderr);
}

void Progress::finish() {
    if (!quiet_ && terminal_) std::fprintf(stderr, "\r\033[K");
}

}  // namespace hybridlab
