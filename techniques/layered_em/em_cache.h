#pragma once
// The on-disk cache of baked layered EMs (Hakura & Snyder 2001 §4: a preprocess), one file per
// lens system, keyed by a hash of the scene content (every file the scene was built from), the
// lens system and every bake setting. Entries are written atomically. The cache is only ever an
// optimisation, never input: every entry can be baked again, so a file that is not a complete
// entry of this format, or one whose contents are not what that bake would give
// (em_cache_entry_check.h), is a miss, baked again and overwritten.
#include <filesystem>
#include <optional>
#include <string>

#include "techniques/layered_em/em_bake.h"

namespace hybridlab {

std::string layeredEmCacheKey(const Scene& scene, const LensSystemInfo& system, const EmBakeSettings& settings);

// cacheDir("layered-em"), the default folder of entries.
std::filesystem::path defaultLayeredEmCacheDir();

void writeLayeredEm(const std::filesystem::path& file, const LayeredEm& em);

// What the cache holds at `file` for `system` of `scene` baked under `settings`.
struct CachedLayeredEm {
    std::optional<LayeredEm> em;  // the entry, when the file is one that fits
    std::string problem;          // else why the file is not usable; empty when there is no file
};
CachedLayeredEm readLayeredEm(const std::filesystem::path& file, const Scene& scene, const LensSystemInfo& system,
                              const EmBakeSettings& settings);

// readLayeredEm for a caller about to bake on a miss: an unusable file gets a one-line warning
// naming it and what was wrong, and reads as absent.
std::optional<LayeredEm> findLayeredEm(const std::filesystem::path& file, const Scene& scene, const LensSystemInfo& system,
                                       const EmBakeSettings& settings);

// Throws IoError naming `dir` when entries cannot be written into it (made when missing): so that
// `bake-em`, whose product is the entry, fails before its bake rather than after.
void requireWritableLayeredEmCache(const std::filesystem::path& dir);

}  // namespace hybridlab
