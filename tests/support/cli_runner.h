#pragma once
// Runs the real hybridlab program (HYBRIDLAB_BIN) in a child process and collects what it did.
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace hybridlab::test {

struct CliResult {
    int exitStatus = -1;  // the exit code; 128 + signal number when killed by a signal
    std::string out;      // everything written to stdout
    std::string err;      // everything written to stderr
};

// Environment changes for the child only: a value sets the variable, std::nullopt unsets it; every
// other variable is inherited.
using EnvChanges = std::map<std::string, std::optional<std::string>>;

// Runs `hybridlab args...`; stdin is /dev/null.
CliResult runHybridlab(const std::vector<std::string>& args, const EnvChanges& env = {});

struct CliRun {
    std::vector<std::string> args;
    EnvChanges env;
};

// Runs all the invocations at once, so that their renders overlap; the results come back in the
// order of `runs`.
std::vector<CliResult> runHybridlabAll(const std::vector<CliRun>& runs);

}  // namespace hybridlab::test
