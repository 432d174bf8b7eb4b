#pragma once
// Where hybridlab keeps caches: $HYBRIDLAB_CACHE, else $XDG_CACHE_HOME/hybridlab, else
// ~/.cache/hybridlab, with one folder per kind of entry inside.
#include <filesystem>
#include <string>

namespace hybridlab {

std::filesystem::path cacheDir(const std::string& folder);

}  // namespace hybridlab
