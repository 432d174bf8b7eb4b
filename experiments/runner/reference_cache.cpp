#include "experiments/runner/reference_cache.h"

#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <fstream>

#include <nlohmann/json.hpp>

#include "common/core/atomic_file.h"
#include "common/image/image_io.h"
#include "common/core/cache_dir.h"
#include "common/core/content_hash.h"
#include "common/core/log.h"

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
    // A cache folder the file system refuses to look into (a name too long, a link loop) holds nothing.
    std::error_code error;
    for (const char* suffix : {".json", ".exr", ".mask.exr"})
        if (!fs::exists(dir_ / (key + suffix), error)) return false;
    return true;
}

namespace {

// The entry's images as their bytes were stored: an image copied over an entry (another view's,
// another scene's, a truncated one) is found out before it is scored against.
std::string fileHash(const fs::path& file) { return ContentHash().addFile(file).hex(); }

// The stored entry, or the reason it cannot be the reference its key names.
CachedReference readEntry(const fs::path& dir, const std::string& key) {
    const fs::path meta = dir / (key + ".json"), image = dir / (key + ".exr"), mask = dir / (key + ".mask.exr");
    std::ifstream in(meta);
    const nlohmann::json j = nlohmann::json::parse(in);  // throws on a folder, an empty file, bad JSON
    const auto number = [&](const char* name) {
        if (!j.is_object() || !j.contains(name) || !j.at(name).is_number()) throw std::runtime_error(std::string("no number '") + name + "'");
        return j.at(name).get<double>();
    };
    const double frameMs = number("frame_ms"), width = number("width"), height = number("height");
    if (!(std::isfinite(frameMs) && frameMs > 0.0)) throw std::runtime_error("frame_ms is not a positive time");
    if (!j.at("image_hash").is_string() || !j.at("mask_hash").is_string() || j.at("image_hash") != fileHash(image) ||
        j.at("mask_hash") != fileHash(mask))
        throw std::runtime_error("its images are not the ones stored with it");
    CachedReference r{key, readImage(image), readImage(mask), frameMs, true};
    if (r.image.width() != width || r.image.height() != height || r.mask.width() != width || r.mask.height() != height)
        throw std::runtime_error("its images are not of the size stored with it");
    return r;
}

}  // namespace

std::optional<CachedReference> ReferenceCache::find(const std::string& key) const {
    if (!contains(key)) return std::nullopt;
    try {
        return readEntry(dir_, key);
    } catch (const std::exception& e) {
        // A cache holds copies: one that cannot be trusted is rendered again and overwritten.
        warn("reference cache entry " + (dir_ / (key + ".json")).string() + " is unusable (" + e.what() + "); rendering it again");
        return std::nullopt;
    }
}

void ReferenceCache::store(const CachedReference& entry) const {
    try {
        write(entry);
    } catch (const std::exception& e) {
        // The reference is rendered and in hand: a cache that cannot keep it costs time, not the run.
        warn(std::string(e.what()) + ": the reference cache cannot keep references; going on without it");
    }
}

void ReferenceCache::write(const CachedReference& entry) const {
    createDirectories(dir_);
    const fs::path image = dir_ / (entry.key + ".exr"), mask = dir_ / (entry.key + ".mask.exr");
    writeImageAtomically(image, entry.image);
    writeImageAtomically(mask, entry.mask);
    // The metadata last: an entry counts only once all of it is there.
    const nlohmann::json meta{{"frame_ms", entry.frameMilliseconds}, {"width", entry.image.width()}, {"height", entry.image.height()},
                              {"image_hash", fileHash(image)}, {"mask_hash", fileHash(mask)}};
    writeFileAtomically(dir_ / (entry.key + ".json"), meta.dump() + "\n");
}

}  // namespace hybridlab
