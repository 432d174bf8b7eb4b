#include "common/core/program_version.h"

#include "git_revision.h"  // generated at build time (cmake/GitRevision.cmake)

namespace hybridlab {

const std::string& programVersion() {
    // The version from CMake's project(), the revision from the build (common/core/CMakeLists.txt).
    static const std::string version = std::string(HYBRIDLAB_VERSION) + " (git " + HYBRIDLAB_GIT_REVISION + ")";
    return version;
}

}  // namespace hybridlab
