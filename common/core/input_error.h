#pragma once
// Bad input (scene, config, asset, argument): one clear message naming the file, the line and
// what was expected. The CLI turns it into exit status 2 (DESIGN.md "Conventions").
#include <filesystem>
#include <stdexcept>
#include <string>

namespace hybridlab {

class InputError : public std::runtime_error {
public:
    explicit InputError(const std::string& message) : std::runtime_error(message) {}

    // "file:line:column: message"; line/column 0 means "no position".
    static InputError at(const std::filesystem::path& file, int line, int column,
                         const std::string& message) {
        std::string where = file.string();
        if (line > 0) where += ":" + std::to_string(line);
        if (column > 0) where += ":" + std::to_string(column);
        return InputError(where + ": " + message);
    }
};

}  // namespace hybridlab
