#pragma once
// What the libFuzzer targets share: the readers take files, so each input is written to a file in
// a folder of this process's own (removed at exit), and the one rule every target checks.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "common/core/input_error.h"

namespace hybridlab::fuzz {

inline std::filesystem::path processFolder() {
    return std::filesystem::temp_directory_path() / ("hybridlab-fuzz-" + std::to_string(::getpid()));
}

// The input as the file `name` in this process's folder; relative paths in it resolve there, to
// nothing but the previous inputs.
inline std::filesystem::path inputFile(const std::uint8_t* data, std::size_t size, const std::string& name) {
    static const bool created = [] {
        std::filesystem::create_directories(processFolder());
        std::atexit([] {
            std::error_code ignored;
            std::filesystem::remove_all(processFolder(), ignored);
        });
        return true;
    }();
    (void)created;
    const std::filesystem::path file = processFolder() / name;
    std::ofstream(file, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    return file;
}

// Every input loads or is refused with an InputError (the program's exit status 2). Any other
// exception leaves the target, which libFuzzer reports as a crash, as it does the sanitizers'
// findings, a hang (-timeout) and memory beyond -rss_limit_mb.
template <class Load>
int loadOrRefuse(Load&& load) {
    try {
        load();
    } catch (const InputError&) {
    }
    return 0;
}

}  // namespace hybridlab::fuzz
