#pragma once
// Reference images rendered once per (scene content, view, resolution, reference settings,
// program version) and kept under a content hash, reused across runs and experiments. The scene
// content is every file the scene was built from, so editing a scene file or replacing an asset
// invalidates its entries; the program version is the hash of the program binary.
#include <filesystem>
#include <optional>
#include <string>

#include "common/image/image.h"
#include "common/scene/scene.h"
#include "common/scene/view.h"
#include "experiments/runner/experiment_config.h"

namespace hybridlab {

// $HYBRIDLAB_CACHE, else $XDG_CACHE_HOME/hybridlab, else ~/.cache/hybridlab (a "references"
// folder inside).
std::filesystem::path defaultReferenceCacheDir();

struct CachedReference {
    std::string key;
    Image image;           // linear, as rendered
    Image mask;            // 1 where the primary hit is reflective or refractive, else 0
    double frameMilliseconds = 0.0;  // the reference's render time when it was made
    bool cacheHit = false;
};

class ReferenceCache {
public:
    explicit ReferenceCache(std::filesystem::path dir) : dir_(std::move(dir)) {}

    static std::string key(const Scene& scene, const View& view, int width, int height, const ParameterList& referenceParameters);

    // Whether the entry is cached (without reading it).
    bool contains(const std::string& key) const;
    // The cached entry, or nullopt.
    std::optional<CachedReference> find(const std::string& key) const;
    // Keeps the entry, or says why it cannot (a warning): the run goes on with the reference in hand.
    void store(const CachedReference& entry) const;

    const std::filesystem::path& dir() const { return dir_; }

private:
    void write(const CachedReference& entry) const;  // throws IoError

    std::filesystem::path dir_;
};

}  // namespace hybridlab
