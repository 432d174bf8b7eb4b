#pragma once
// Runs a shell command (sh -c) in a child process and collects its standard output.
#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace hybridlab::test {

struct CommandOutput {
    std::string out;
    int exitStatus = -1;  // -1 when it could not start or was killed by a signal
};

inline CommandOutput commandOutput(const std::string& shellCommand) {
    CommandOutput result;
    FILE* pipe = ::popen(shellCommand.c_str(), "r");
    if (!pipe) return result;
    char chunk[4096];
    while (std::size_t n = std::fread(chunk, 1, sizeof chunk, pipe)) result.out.append(chunk, n);
    const int status = ::pclose(pipe);
    result.exitStatus = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
}

}  // namespace hybridlab::test
