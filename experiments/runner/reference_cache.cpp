#include "experiments/runner/reference_cache.h"

#include <cstdlib>
#include <fstream>

#include <nlohmann/json.hpp>

#include "common/core/atomic_file.h"
#include "common/image/image_io.h"
#include "common/core/cache_dir.h"
#include "common/core/content_hash.h"

namespace hybridlab {
namespace fs = std::filesystem;

fs::path defaultReferenceCacheDir() { return cacheDir("references"); }

std::string ReferenceCache::key(const Scene& scene, const View& view, int width, int height, const ParameterList& referenceParameters) {
    ContentHash h;
    h.add(std::string_view("hybridlab reference v1"));
    for (const auto& f : scene.sourceFiles) h.addFile(f);
    // The view as the camera it resolves to (so a renamed path that moves the same way still hits).
    const Camera& c = view.camera;
    for (float v : {c.position.x, c.position.y, c.position.z, c.orientation.w, c.orientation.x, c.orientation.y, c.orientation.z,
                    c.fovYDegrees, c.orthoHeight, c.nearPlane, c.farPlane})
        h.add(static_cast<double>(v));
    h.add(static_cast<std::int64_t>(c.projection == Camera::Projection::Perspective));
    h.add(view.time);
    h.add(static_cast<std::int64_t>(width)).add(static_cast<std::int64_t>(height));
    for (const auto& [k, v] : referenceParameters) h.add(k).add(formatParamValue(v));
    h.add(programVersionHash());
    return h.hex();
}

bool ReferenceCache::contains(const std::string& key) const {
    return fs::exists(dir_ / (key + ".json")) && fs::exists(dir_ / (key + ".exr")) && fs::exists(dir_ / (key + ".mask.exr"));
}

std::optional<CachedReference> ReferenceCache::find(const std::string& key) const {
    if (!contains(key)) return std::nullopt;
    const fs::path meta = dir_ / (key + ".json");
    CachedReference r;
    r.key = key;
    std::ifstream in(meta);
    r.frameMilliseconds = nlohmann::json::parse(in).at("frame_ms").get<double>();
    r.image = readImage(dir_ / (key + ".exr"));
    r.mask = readImage(dir_ / (key + ".mask.exr"));
    r.cacheHit = true;
    return r;
}

void ReferenceCache::store(const CachedReference& entry) const {
    createDirectories(dir_);
    writeImageAtomically(dir_ / (entry.key + ".exr"), entry.image);
    writeImageAtomically(dir_ / (entry.key + ".mask.exr"), entry.mask);
    // The metadata last: an entry counts only once all of it is there.
    writeFileAtomically(dir_ / (entry.key + ".json"), nlohmann::json{{"frame_ms", entry.frameMilliseconds}}.dump() + "\n");
}

}  // namespace hybridlab
