#pragma once
// A file that could not be written or read for a reason outside the input: a full disk, a
// read-only or missing folder, no permission. The message names the user's path and the
// operating system's reason; the CLI turns it into exit status 3 (bad input is 2; DESIGN.md
// "Conventions").
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace hybridlab {

class IoError : public std::runtime_error {
public:
    explicit IoError(const std::string& message) : std::runtime_error(message) {}

    // "PATH: cannot ACTION (the text of errno `error`)".
    static IoError fromErrno(const std::filesystem::path& path, const std::string& action, int error) {
        return IoError(path.string() + ": cannot " + action + " (" + std::strerror(error) + ")");
    }
};

}  // namespace hybridlab
