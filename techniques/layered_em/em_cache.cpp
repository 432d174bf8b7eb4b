#include "techniques/layered_em/em_cache.h"

#include <cstring>
#include <fstream>
#include <sstream>
#include <type_traits>

#include <unistd.h>

#include "common/core/atomic_file.h"
#include "common/core/cache_dir.h"
#include "common/core/content_hash.h"
#include "common/core/io_error.h"
#include "common/core/log.h"
#include "techniques/layered_em/em_cache_entry_check.h"

namespace hybridlab {
namespace {

constexpr char kMagic[8] = {'H', 'L', 'E', 'M', 'v', '3', 'g', '\0'};  // v3: the solve over the active texels; b: half-footprint levels; c: empty fill; d: origin images; e: quads hold their rectangle; f: origin images fill only unread texels; g: round impostors by their objects' shape, direct images observe empty layers

class Writer {
public:
    explicit Writer(std::ostream& out) : out_(out) {}
    template <typename T>
    void pod(const T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        out_.write(reinterpret_cast<const char*>(&v), sizeof v);
    }
    template <typename T>
    void vec(const std::vector<T>& v) {
        pod(static_cast<std::uint64_t>(v.size()));
        out_.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(T)));
    }
    void str(const std::string& s) {
        pod(static_cast<std::uint64_t>(s.size()));
        out_.write(s.data(), static_cast<std::streamsize>(s.size()));
    }

private:
    std::ostream& out_;
};

// Why a file is not an entry of this format.
struct Unreadable {
    std::string why;
};

// Reads an entry of `bytes` bytes; every read fails with Unreadable past them.
class Reader {
public:
    Reader(std::istream& in, std::uint64_t bytes) : in_(in), left_(bytes) {}
    template <typename T>
    void pod(T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        read(&v, sizeof v);
    }
    // A count of items of `itemBytes` or more each, bounded by the bytes left: a damaged count fails
    // here rather than asking for memory the file cannot fill.
    std::size_t count(std::size_t itemBytes) {
        std::uint64_t n = 0;
        pod(n);
        if (n > left_ / itemBytes)
            throw Unreadable{"a count of " + std::to_string(n) + " items does not fit in the " + std::to_string(left_) + " bytes left"};
        return static_cast<std::size_t>(n);
    }
    template <typename T>
    void vec(std::vector<T>& v) {
        v.resize(count(sizeof(T)));
        read(v.data(), v.size() * sizeof(T));
    }
    void str(std::string& s) {
        s.resize(count(1));
        read(s.data(), s.size());
    }
    std::uint64_t left() const { return left_; }

private:
    void read(void* to, std::size_t bytes) {
        if (bytes > left_ || !in_.read(static_cast<char*>(to), static_cast<std::streamsize>(bytes))) throw Unreadable{"it ends early"};
        left_ -= bytes;
    }

    std::istream& in_;
    std::uint64_t left_;
};

// The entry in `file`, read as written, checked only for its format.
LayeredEm parseLayeredEm(const std::filesystem::path& file) {
    std::error_code error;
    const std::uint64_t bytes = std::filesystem::file_size(file, error);
    std::ifstream in(file, std::ios::binary);
    if (error || !in) throw Unreadable{"it cannot be read"};
    Reader r(in, bytes);
    char magic[sizeof kMagic];
    r.pod(magic);
    if (std::memcmp(magic, kMagic, sizeof kMagic) != 0) throw Unreadable{"it is not an entry of this version"};
    LayeredEm em;
    r.str(em.system);
    r.pod(em.center);
    constexpr std::size_t kLeastLayerBytes = sizeof(Shell) + 2 * sizeof(std::uint64_t);
    em.layers.resize(r.count(kLeastLayerBytes));
    for (EmLayer& l : em.layers) {
        r.pod(l.shell);
        r.vec(l.objects);
        r.pod(l.meanDistance);
    }
    constexpr std::size_t kLeastViewpointBytes = sizeof(Camera) + 2 * sizeof(std::uint64_t);
    em.viewpoints.resize(r.count(kLeastViewpointBytes));
    for (EmViewpoint& v : em.viewpoints) {
        r.pod(v.camera);
        r.vec(v.unobservedTexels);
        constexpr std::size_t kLeastMapBytes = sizeof(int) + sizeof(std::uint64_t);
        v.maps.resize(r.count(kLeastMapBytes));
        for (LayerCubeMap& m : v.maps) {
            r.pod(m.size);
            r.vec(m.texels);
        }
    }
    if (r.left() != 0) throw Unreadable{"it has " + std::to_string(r.left()) + " bytes past the entry's end"};
    return em;
}

}  // namespace

std::string layeredEmCacheKey(const Scene& scene, const LensSystemInfo& system, const EmBakeSettings& s) {
    ContentHash h;
    h.add(std::string_view(kMagic, sizeof kMagic));
    for (const auto& f : scene.sourceFiles) h.addFile(f);
    h.add(std::string_view(system.name));
    for (std::uint32_t o : system.objects) h.add(static_cast<std::int64_t>(o));
    for (std::int64_t v : {std::int64_t{s.width}, std::int64_t{s.height}, std::int64_t{s.records.supersampling},
                           std::int64_t{s.records.maxHitsPerRay}, std::int64_t{s.records.continueRays},
                           std::int64_t{s.records.paths.maxInterfaces}, std::int64_t{s.tessellation.maxLevels},
                           std::int64_t{s.viewpoints.frameStride}, std::int64_t{s.viewpoints.maxSamples}, std::int64_t{s.viewpoints.heightSet}, std::int64_t{s.layers},
                           std::int64_t{s.maxLayers}, std::int64_t{s.inference.size}, std::int64_t{s.inference.maxIterations}, std::int64_t{s.inference.ring},
                           std::int64_t{s.inference.finerLevels},
                           std::int64_t{s.neighbourViewpoints}, std::int64_t{s.directImages}, std::int64_t{s.originImages},
                           static_cast<std::int64_t>(directImageSourceFor(scene, system, s.directImageSource)),
                           static_cast<std::int64_t>(s.clusterSampleLimit)}) {
        h.add(v);
    }
    for (double v : {double{s.records.confidenceAngleDegrees}, double{s.tessellation.tauPixels}, double{s.tessellation.maxAngleDegrees},
                     double{s.viewpoints.stepDegrees}, double{s.viewpoints.radius}, double{s.viewpoints.height}, s.maxRelativeRms,
                     s.inference.smoothness, s.inference.pyramid, s.inference.damping, s.inference.tolerance, s.inference.observedWeight, double{s.directMissingDistance}}) {
        h.add(v);
    }
    h.add(std::string_view(s.viewpoints.cameraPath));
    return h.hex();
}

std::filesystem::path defaultLayeredEmCacheDir() { return cacheDir("layered-em"); }

void writeLayeredEm(const std::filesystem::path& file, const LayeredEm& em) {
    createDirectories(file.parent_path());
    {
        std::ostringstream out(std::ios::binary);
        Writer w(out);
        out.write(kMagic, sizeof kMagic);
        w.str(em.system);
        w.pod(em.center);
        w.pod(static_cast<std::uint64_t>(em.layers.size()));
        for (const EmLayer& l : em.layers) {
            w.pod(l.shell);
            w.vec(l.objects);
            w.pod(l.meanDistance);
        }
        w.pod(static_cast<std::uint64_t>(em.viewpoints.size()));
        for (const EmViewpoint& v : em.viewpoints) {
            w.pod(v.camera);
            w.vec(v.unobservedTexels);
            w.pod(static_cast<std::uint64_t>(v.maps.size()));
            for (const LayerCubeMap& m : v.maps) {
                w.pod(m.size);
                w.vec(m.texels);
            }
        }
        writeFileAtomically(file, std::move(out).str());
    }
}

CachedLayeredEm readLayeredEm(const std::filesystem::path& file, const Scene& scene, const LensSystemInfo& system,
                              const EmBakeSettings& settings) {
    std::error_code error;
    if (!std::filesystem::exists(file, error)) return {};
    try {
        LayeredEm em = parseLayeredEm(file);
        if (std::optional<std::string> mismatch = layeredEmEntryMismatch(em, scene, system, settings)) return {std::nullopt, *mismatch};
        return {std::move(em), {}};
    } catch (const Unreadable& u) {
        return {std::nullopt, u.why};
    }
}

std::optional<LayeredEm> findLayeredEm(const std::filesystem::path& file, const Scene& scene, const LensSystemInfo& system,
                                       const EmBakeSettings& settings) {
    CachedLayeredEm cached = readLayeredEm(file, scene, system, settings);
    if (!cached.problem.empty()) warn(file.string() + ": not a usable layered-EM cache entry (" + cached.problem + "); baking it again");
    return std::move(cached.em);
}

void requireWritableLayeredEmCache(const std::filesystem::path& dir) {
    createDirectories(dir);
    if (::access(dir.c_str(), W_OK) != 0) throw IoError::fromErrno(dir, "write entries into the layered-EM cache folder", errno);
}

}  // namespace hybridlab
