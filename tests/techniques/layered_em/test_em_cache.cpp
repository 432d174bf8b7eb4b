// The layered-EM cache reads a damaged or foreign entry as a miss, saying why, and never draws,
// prints or crashes on it; the render bakes such an entry again and draws what a clean cache gives,
// and draws it too where the cache cannot be written.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>

#include <gtest/gtest.h>

#include "common/image/image_io.h"
#include "common/scene/scene_file.h"
#include "techniques/layered_em/em_cache.h"
#include "techniques/shared/lens_system.h"
#include "tests/support/cli_runner.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

// A two-layer, two-sample bake of teapot-lens's cup at 4 texels a side: the settings the entries
// below are checked against.
EmBakeSettings tinyBake() {
    EmBakeSettings s;
    s.viewpoints.maxSamples = 2;
    s.inference.size = 4;
    s.layers = 2;
    return s;
}

class EmCacheEntry : public ::testing::Test {
protected:
    EmCacheEntry()
        : scene_(loadSceneFile(test::builtinSceneFile("teapot-lens"), {.loadTextures = false})),
          system_(findLensSystems(scene_).at(1)),
          settings_(tinyBake()),
          file_(dir_ / "entry.hlem") {}

    // An entry that fits the settings (what the bake's shape is, not its values: the check is
    // about what the renderer indexes and draws).
    LayeredEm fittingEntry() const {
        LayeredEm em;
        em.system = system_.name;
        em.center = {0.0f, 0.5f, 0.0f};
        em.layers.resize(2);
        em.layers[0].objects = {0};
        em.layers[1].objects = {1, 2};
        for (const Camera& c : viewpointSamples(scene_, em.center, settings_.viewpoints)) {
            EmViewpoint v;
            v.camera = c;
            v.maps.assign(em.layers.size(), LayerCubeMap(settings_.inference.size));
            v.unobservedTexels.assign(em.layers.size(), 0);
            em.viewpoints.push_back(std::move(v));
        }
        return em;
    }

    CachedLayeredEm read() const { return readLayeredEm(file_, scene_, system_, settings_); }

    // The fitting entry's bytes after `damage`.
    void writeDamagedBytes(const std::function<void(std::string&)>& damage) const {
        writeLayeredEm(file_, fittingEntry());
        std::string bytes = test::readTextFile(file_);
        damage(bytes);
        test::writeTextFile(file_, bytes);
    }

    test::TempDir dir_;
    Scene scene_;
    LensSystemInfo system_;
    EmBakeSettings settings_;
    std::filesystem::path file_;
};

void putCount(std::string& bytes, std::size_t offset, std::uint64_t count) { std::memcpy(bytes.data() + offset, &count, sizeof count); }

TEST_F(EmCacheEntry, AnEntryThatFitsReadsBackAndNoFileIsAPlainMiss) {
    const CachedLayeredEm absent = read();
    EXPECT_FALSE(absent.em.has_value());
    EXPECT_EQ(absent.problem, "");
    writeLayeredEm(file_, fittingEntry());
    const CachedLayeredEm cached = read();
    ASSERT_TRUE(cached.em.has_value()) << cached.problem;
    EXPECT_EQ(cached.em->viewpoints.size(), 2u);
    EXPECT_EQ(cached.em->layers[1].objects, (std::vector<std::uint32_t>{1, 2}));
}

struct ContentDamage {
    const char* name;
    std::function<void(LayeredEm&)> damage;
    const char* problem;  // a part of what the miss says
};

TEST_F(EmCacheEntry, AnEntryThatIsNotWhatTheBakeGivesIsAMissSayingWhy) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const ContentDamage damages[] = {
        {"no viewpoint samples", [](LayeredEm& em) { em.viewpoints.clear(); }, "it has no viewpoint samples"},
        {"no layers", [](LayeredEm& em) { em.layers.clear(); }, "it has no layers"},
        {"a sample too many", [](LayeredEm& em) { em.viewpoints.push_back(em.viewpoints[0]); }, "it has 3 viewpoint samples; the bake makes 2"},
        {"more layers than asked for",
         [](LayeredEm& em) {
             em.layers.push_back(em.layers[0]);
             for (EmViewpoint& v : em.viewpoints) {
                 v.maps.push_back(v.maps[0]);
                 v.unobservedTexels.push_back(0);
             }
         },
         "it has 3 layers; the bake makes 1 to 2"},
        {"an object past the scene's", [](LayeredEm& em) { em.layers[1].objects = {0xfffffff0u}; }, "layer 2 names object 4294967280; the scene has"},
        {"maps of another size",
         [](LayeredEm& em) {
             for (EmViewpoint& v : em.viewpoints) std::fill(v.maps.begin(), v.maps.end(), LayerCubeMap(2));
         },
         "viewpoint sample 0's cube map of layer 1 is 2 texels a side; the bake's em_size is 4"},
        {"texels short of the map's size", [](LayeredEm& em) { em.viewpoints[1].maps[0].texels.pop_back(); }, "layer 1 holds"},
        {"a layer without its map", [](LayeredEm& em) { em.viewpoints[1].maps.pop_back(); }, "viewpoint sample 1 has 1 cube maps"},
        {"no unobserved-texel counts", [](LayeredEm& em) { em.viewpoints[0].unobservedTexels.clear(); }, "0 unobserved-texel counts for 2 layers"},
        {"a non-finite texel", [nan](LayeredEm& em) { em.viewpoints[1].maps[1].texels[3].g = nan; }, "layer 2 has a non-finite texel"},
        {"a camera at infinity", [](LayeredEm& em) { em.viewpoints[0].camera.position.x = std::numeric_limits<float>::infinity(); }, "unusable camera"},
        {"a non-finite impostor", [nan](LayeredEm& em) { em.layers[0].shell.radius = nan; }, "layer 1 has an unknown or non-finite impostor"},
        {"an unknown impostor", [](LayeredEm& em) { em.layers[0].shell.kind = static_cast<ShellKind>(7); }, "unknown or non-finite impostor"},
        {"another lens system's", [](LayeredEm& em) { em.system = "vase"; }, "it is an entry of lens system 'vase', not 'cup'"},
        {"a non-finite origin", [nan](LayeredEm& em) { em.center.y = nan; }, "EM origin is not finite"},
    };
    for (const ContentDamage& d : damages) {
        LayeredEm em = fittingEntry();
        d.damage(em);
        writeLayeredEm(file_, em);
        const CachedLayeredEm cached = read();
        EXPECT_FALSE(cached.em.has_value()) << d.name;
        EXPECT_CONTAINS(cached.problem, d.problem) << d.name << ": " << cached.problem;
    }
}

struct ByteDamage {
    const char* name;
    std::function<void(std::string&)> damage;
    const char* problem;
};

TEST_F(EmCacheEntry, AFileThatIsNotAWholeEntryIsAMissSayingWhy) {
    // The layout (em_cache.cpp): magic, the system's name, the origin, the layer count, ...; the
    // file ends with the last map's texel count and its texels.
    const std::size_t layerCount = 8 + 8 + system_.name.size() + sizeof(glm::vec3);
    const std::size_t lastTexels = cubeMapTexelCount(settings_.inference.size) * sizeof(glm::vec4);
    const ByteDamage damages[] = {
        {"a texel count of 2^32", [&](std::string& b) { putCount(b, b.size() - lastTexels - 8, 1ull << 32); },
         "a count of 4294967296 items does not fit in the"},
        {"a layer count of 2^60", [&](std::string& b) { putCount(b, layerCount, 1ull << 60); }, "a count of 1152921504606846976 items"},
        {"three bytes cut off", [](std::string& b) { b.resize(b.size() - 3); }, "does not fit"},
        {"cut off in the middle of a texel", [&](std::string& b) { b.resize(b.size() - lastTexels / 2 - 3); }, "does not fit"},
        {"cut off inside the magic", [](std::string& b) { b.resize(5); }, "it ends early"},
        {"empty", [](std::string& b) { b.clear(); }, "it ends early"},
        {"a byte past the end", [](std::string& b) { b.push_back('\0'); }, "it has 1 bytes past the entry's end"},
        {"another format's magic", [](std::string& b) { b[6] = 'a'; }, "it is not an entry of this version"},
    };
    for (const ByteDamage& d : damages) {
        writeDamagedBytes(d.damage);
        const CachedLayeredEm cached = read();
        EXPECT_FALSE(cached.em.has_value()) << d.name;
        EXPECT_CONTAINS(cached.problem, d.problem) << d.name << ": " << cached.problem;
    }
    std::filesystem::remove(file_);
    std::filesystem::create_directory(file_);
    EXPECT_CONTAINS(read().problem, "it cannot be read") << "a folder where the entry belongs";
}

// The render's layered_em at a size where the bake takes about a second.
std::vector<std::string> tinyRender(const std::filesystem::path& out) {
    std::vector<std::string> args = {"render", "--scene", "em-disocclusion", "--technique", "layered_em", "--width", "32", "--height", "18",
                                     "--out", out.string()};
    for (const char* p : {"em_size=4", "bake_width=16", "bake_height=12", "supersampling=1", "viewpoints=2", "layers=2"})
        args.insert(args.end(), {"--param", p});
    return args;
}

bool samePixels(const Image& a, const Image& b) {
    return a.width() == b.width() && a.height() == b.height() && std::equal(a.data(), a.data() + a.pixelCount(), b.data());
}

TEST(EmCache, RenderBakesADamagedEntryAgainAndDrawsWhatACleanCacheGives) {
    test::TempDir dir;
    const std::filesystem::path cache = dir / "cache";
    const test::EnvChanges inCache = {{"HYBRIDLAB_CACHE", cache.string()}};
    test::writeTextFile(dir / "a-file", "");
    // An unwritable cache (a file where its folder would be) costs the render the cache, not the
    // frame; bake-em, whose product is the entry, stops before its bake.
    const std::string unwritable = (dir / "a-file" / "cache").string();
    const auto first = test::runHybridlabAll({{tinyRender(dir / "clean.exr"), inCache},
                                              {tinyRender(dir / "uncached.exr"), {{"HYBRIDLAB_CACHE", unwritable}}},
                                              {{"bake-em", "--scene", "em-disocclusion", "--cache", unwritable}, {}}});
    ASSERT_EQ(first[0].exitStatus, 0) << first[0].err;
    EXPECT_EQ(first[1].exitStatus, 0) << first[1].err;
    EXPECT_CONTAINS(first[1].err, "a-file/cache/layered-em: cannot create folder (Not a directory)); rendering without storing the baked EMs");
    EXPECT_TRUE(samePixels(readImage(dir / "uncached.exr"), readImage(dir / "clean.exr")));
    EXPECT_EQ(first[2].exitStatus, 3);
    EXPECT_EQ(first[2].err, "hybridlab: error: " + unwritable + ": cannot create folder (Not a directory)\n");

    std::vector<std::filesystem::path> entries;
    for (const auto& e : std::filesystem::directory_iterator(cache / "layered-em")) entries.push_back(e.path());
    ASSERT_EQ(entries.size(), 1u);
    const std::string clean = test::readTextFile(entries[0]);
    // Every map a texel short of its size: the last map's texel count says one fewer, and the file
    // ends one texel earlier, so that only the check of the count against em_size finds it.
    std::string damaged = clean.substr(0, clean.size() - sizeof(glm::vec4));
    const std::size_t countAt = damaged.size() - (cubeMapTexelCount(4) - 1) * sizeof(glm::vec4) - 8;
    putCount(damaged, countAt, cubeMapTexelCount(4) - 1);
    test::writeTextFile(entries[0], damaged);

    const test::CliResult again = test::runHybridlab(tinyRender(dir / "again.exr"), inCache);
    ASSERT_EQ(again.exitStatus, 0) << again.err;
    EXPECT_CONTAINS(again.err, entries[0].filename().string() + ": not a usable layered-EM cache entry (viewpoint sample 1's cube map of layer 2 holds");
    EXPECT_CONTAINS(again.err, "baking it again");
    EXPECT_TRUE(samePixels(readImage(dir / "again.exr"), readImage(dir / "clean.exr")));
    EXPECT_EQ(test::readTextFile(entries[0]), clean) << "the damaged entry is overwritten by the bake";

    // bake-em with the options of the same bake finds the same entry; one whose first layer names
    // an object the scene lacks is baked again, not printed.
    std::uint64_t nameLength = 0;
    std::memcpy(&nameLength, clean.data() + 8, sizeof nameLength);
    const std::size_t firstObject = 8 + 8 + nameLength + sizeof(glm::vec3) + 8 + sizeof(Shell) + 8;
    std::string foreign = clean;
    const std::uint32_t missing = 0xfffffff0u;
    std::memcpy(foreign.data() + firstObject, &missing, sizeof missing);
    test::writeTextFile(entries[0], foreign);
    const test::CliResult bake = test::runHybridlab({"bake-em", "--scene", "em-disocclusion", "--cache", (cache / "layered-em").string(), "--width",
                                                     "16", "--height", "12", "--supersampling", "1", "--em-size", "4", "--max-viewpoints", "2",
                                                     "--layers", "2", "--quiet"});
    ASSERT_EQ(bake.exitStatus, 0) << bake.err;
    EXPECT_CONTAINS(bake.err, "not a usable layered-EM cache entry (layer 1 names object 4294967280; the scene has");
    EXPECT_CONTAINS(bake.out, "baked 2 viewpoints");
    EXPECT_EQ(test::readTextFile(entries[0]), clean);
}

}  // namespace
}  // namespace hybridlab
