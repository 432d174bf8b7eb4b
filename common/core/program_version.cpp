#include "common/core/program_version.h"

namespace hybridlab {

const std::string& programVersion() {
    // Both baked in by CMake at configure time (common/core/CMakeLists.txt).
    static const std::string version = std::string(HYBRIDLAB_VERSION) + " (git " + HYBRIDLAB_GIT_REVISION + ")";
    return version;
}

}  // namespace hybridlab
