#pragma once
// The on-disk cache of baked layered EMs (Hakura & Snyder 2001 §4: a preprocess), one file per
// lens system, keyed by a hash of the scene content (every file the scene was built from), the
// lens system and every bake setting. Entries are written atomically; a file that is not a
// complete entry of this format reads as absent.
#include <filesystem>
#include <optional>
#include <string>

#include "techniques/layered_em/em_bake.h"

namespace hybridlab {

std::string layeredEmCacheKey(const Scene& scene, const LensSystemInfo& system, const EmBakeSettings& settings);

// cacheDir("layered-em"), the default folder of entries.
std::filesystem::path defaultLayeredEmCacheDir();

void writeLayeredEm(const std::filesystem::path& file, const LayeredEm& em);
std::optional<LayeredEm> readLayeredEm(const std::filesystem::path& file);

}  // namespace hybridlab
