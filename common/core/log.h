#pragma once
// Warnings and progress go to stderr so that stdout stays machine-readable.
#include <cstdio>
#include <string>

namespace hybridlab {

inline void warn(const std::string& message) { std::fprintf(stderr, "warning: %s\n", message.c_str()); }
inline void info(const std::string& message) { std::fprintf(stderr, "%s\n", message.c_str()); }

}  // namespace hybridlab
