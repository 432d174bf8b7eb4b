#pragma once
// A stable 64-bit content hash (FNV-1a) for cache keys and run ids: the same bytes give the same
// hash on every machine and in every run.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace hybridlab {

class ContentHash {
public:
    ContentHash& add(std::string_view bytes);
    ContentHash& add(double v);
    ContentHash& add(std::int64_t v);
    // The file's bytes (and its name, so that swapping two files changes the hash).
    ContentHash& addFile(const std::filesystem::path& file);

    std::uint64_t value() const { return h_; }
    std::string hex() const;  // 16 hex digits

private:
    std::uint64_t h_ = 1469598103934665603ull;
};

// The hash of the running program's own binary: "program version" in cache keys, so that any
// rebuild of the renderer invalidates cached references.
const std::string& programVersionHash();

}  // namespace hybridlab
