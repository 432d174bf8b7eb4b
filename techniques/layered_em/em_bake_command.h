#pragma once
// `hybridlab bake-em`: bakes the layered EMs of every lens system of a scene (Hakura & Snyder 2001
// §4) into the on-disk cache ahead of rendering, with a progress bar and the time of each stage.
// An entry already in the cache is reported and kept unless --force. The technique's bake
// capability (techniques/cache_bake_command.h), which the CLI finds in the registry.
#include "techniques/cache_bake_command.h"

namespace hybridlab {

CacheBakeCommand emBakeCommand();

}  // namespace hybridlab
