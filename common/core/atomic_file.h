#pragma once
// Files that are either absent or complete: write to a temporary name beside the target (unique
// to this process, keeping the extension last so that writers that choose a format by it still
// can), then rename over the target. A process killed mid-write leaves the old file intact; a
// writer that throws leaves nothing behind.
#include <filesystem>
#include <functional>
#include <string>

namespace hybridlab {

// `write` writes the complete file at the path it is given.
void writeAtomically(const std::filesystem::path& path, const std::function<void(const std::filesystem::path&)>& write);

void writeFileAtomically(const std::filesystem::path& path, const std::string& contents);

}  // namespace hybridlab
