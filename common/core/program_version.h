#pragma once
// The program's version and the git revision it was configured from ("0.1.0 (git 1a2b3c4d5e6f)",
// "-dirty" when the checkout had changes, "unknown" outside a git checkout): what a result set
// records so that two of them can be told apart.
#include <string>

namespace hybridlab {

const std::string& programVersion();

}  // namespace hybridlab
