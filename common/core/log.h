#pragma once
// Warnings and progress go to stderr so that stdout stays machine-readable.
#include <cstdio>
#include <mutex>
#include <set>
#include <string>

namespace hybridlab {

// Each warning once a process: a model that two scenes share (Sponza's) is loaded twice by
// `hybridlab scenes`, and its warnings say nothing new the second time.
inline void warn(const std::string& message) {
    static std::mutex mutex;
    static std::set<std::string> said;
    const std::lock_guard<std::mutex> lock(mutex);
    if (said.insert(message).second) std::fprintf(stderr, "warning: %s\n", message.c_str());
}
inline void info(const std::string& message) { std::fprintf(stderr, "%s\n", message.c_str()); }

}  // namespace hybridlab
