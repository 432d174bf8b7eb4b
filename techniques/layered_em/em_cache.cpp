#include "techniques/layered_em/em_cache.h"

#include <cstring>
#include <fstream>
#include <sstream>
#include <type_traits>

#include "common/core/atomic_file.h"
#include "common/core/cache_dir.h"
#include "common/core/content_hash.h"

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

class Reader {
public:
    explicit Reader(std::ifstream& in) : in_(in) {}
    template <typename T>
    bool pod(T& v) {
        return static_cast<bool>(in_.read(reinterpret_cast<char*>(&v), sizeof v));
    }
    template <typename T>
    bool vec(std::vector<T>& v) {
        std::uint64_t n = 0;
        if (!pod(n) || n > (1ull << 32)) return false;
        v.resize(n);
        return static_cast<bool>(in_.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(n * sizeof(T))));
    }
    bool str(std::string& s) {
        std::uint64_t n = 0;
        if (!pod(n) || n > (1u << 20)) return false;
        s.resize(n);
        return static_cast<bool>(in_.read(s.data(), static_cast<std::streamsize>(n)));
    }

private:
    std::ifstream& in_;
};

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

std::optional<LayeredEm> readLayeredEm(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) return std::nullopt;
    char magic[sizeof kMagic];
    if (!in.read(magic, sizeof magic) || std::memcmp(magic, kMagic, sizeof kMagic) != 0) return std::nullopt;
    Reader r(in);
    LayeredEm em;
    std::uint64_t layers = 0, views = 0;
    if (!r.str(em.system) || !r.pod(em.center) || !r.pod(layers) || layers > 64) return std::nullopt;
    em.layers.resize(layers);
    for (EmLayer& l : em.layers) {
        if (!r.pod(l.shell) || !r.vec(l.objects) || !r.pod(l.meanDistance)) return std::nullopt;
    }
    if (!r.pod(views) || views > 100000) return std::nullopt;
    em.viewpoints.resize(views);
    for (EmViewpoint& v : em.viewpoints) {
        std::uint64_t maps = 0;
        if (!r.pod(v.camera) || !r.vec(v.unobservedTexels) || !r.pod(maps) || maps != layers) return std::nullopt;
        v.maps.resize(maps);
        for (LayerCubeMap& m : v.maps) {
            if (!r.pod(m.size) || !r.vec(m.texels) || m.texels.size() != cubeMapTexelCount(m.size)) return std::nullopt;
        }
    }
    char extra;
    if (in.read(&extra, 1)) return std::nullopt;  // trailing bytes: not an entry of this format
    return em;
}

}  // namespace hybridlab
