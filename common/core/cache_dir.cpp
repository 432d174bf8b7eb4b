#include "common/core/cache_dir.h"

#include <cstdlib>

namespace hybridlab {

std::filesystem::path cacheDir(const std::string& folder) {
    namespace fs = std::filesystem;
    if (const char* c = std::getenv("HYBRIDLAB_CACHE"); c && *c) return fs::path(c) / folder;
    if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return fs::path(x) / "hybridlab" / folder;
    if (const char* h = std::getenv("HOME"); h && *h) return fs::path(h) / ".cache" / "hybridlab" / folder;
    return fs::temp_directory_path() / "hybridlab-cache" / folder;
}

}  // namespace hybridlab
