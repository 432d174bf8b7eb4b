#pragma once
// Files that are either absent or complete: write to a temporary name beside the target (unique
// to this process), then rename over it. A process killed mid-write leaves the old file intact.
#include <filesystem>
#include <string>

namespace hybridlab {

void writeFileAtomically(const std::filesystem::path& path, const std::string& contents);

}  // namespace hybridlab
