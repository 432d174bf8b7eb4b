#pragma once
// The report's Python scripts (report/*.py, in the source folder compiled into the program), run
// by Debian's python3, which has the packages the set-up script installs (matplotlib); a python3
// found first on the PATH (pyenv, a virtualenv) may not.
#include <string>
#include <vector>

namespace hybridlab::cli {

// How a script's run treats Ctrl-C: stop the program with it (the default), or leave it to the
// script alone (a server that stops on Ctrl-C and says so), the program returning its status.
enum class Interrupt { StopsBoth, ScriptOnly };

// Runs report/SCRIPT with `args` and returns its exit status (128 + the signal where one ended it).
// Its standard output passes through, or with `output` is collected there instead.
int runReportScript(const std::string& script, const std::vector<std::string>& args, Interrupt interrupt = Interrupt::StopsBoth,
                    std::string* output = nullptr);

// runReportScript for a script that says its own refusals on one line (report.py, serve.py): its
// exit status 2 (bad input) or 3 (I/O) ends the program with that status and no line of its own
// (CommandExit); any other failure is the program's (std::runtime_error).
void runReportScriptSayingItsErrors(const std::string& script, const std::vector<std::string>& args,
                                    Interrupt interrupt = Interrupt::StopsBoth);

// The same for a script elsewhere in the source folder (`path` relative to it: experiments/tune/tune.py).
int runSourceScript(const std::string& path, const std::vector<std::string>& args, Interrupt interrupt = Interrupt::StopsBoth,
                    std::string* output = nullptr);

}  // namespace hybridlab::cli
