#pragma once
// The report's Python scripts (report/), started by `report` and `run`: Debian's /usr/bin/python3,
// which has the packages setup.sh installs (matplotlib, OpenImageIO, jsonschema); a python3 found
// first on the PATH (pyenv, a virtualenv) may not.
#include <string>
#include <vector>

namespace hybridlab::cli {

// report/NAME under the source tree the program was built from.
std::string reportScript(const std::string& name);

// Runs `python3 script args...`, its output passing through (or, with `output`, collected there
// instead of stdout); returns its exit status (128 + the signal's number when killed by one).
int runPython(const std::string& script, const std::vector<std::string>& args, std::string* output = nullptr);

}  // namespace hybridlab::cli
