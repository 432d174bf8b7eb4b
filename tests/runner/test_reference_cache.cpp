// The reference cache keeps copies: an entry whose files are not the ones stored with it (another
// entry's image copied over, a truncated image, a damaged or foreign metadata file) is a miss,
// rendered again, never a reference scored against.
#include <fstream>
#include <functional>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "experiments/runner/reference_cache.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

namespace fs = std::filesystem;

CachedReference entry(const std::string& key, float value) {
    return CachedReference{key, Image(8, 6, glm::vec4(value, 0.5f * value, 0.25f, 1.0f)), Image(8, 6, glm::vec4(value > 0.5f ? 1.0f : 0.0f)), 12.5, false};
}

void overwrite(const fs::path& file, const std::string& text) { std::ofstream(file, std::ios::trunc) << text; }

TEST(ReferenceCache, AnEntryIsFoundAsStoredAndAnyDamageMakesItAMiss) {
    test::TempDir dir;
    const ReferenceCache cache(dir.path());
    cache.store(entry("a", 0.75f));
    cache.store(entry("b", 0.25f));
    const std::optional<CachedReference> a = cache.find("a");
    ASSERT_TRUE(a.has_value());
    EXPECT_TRUE(a->cacheHit);
    EXPECT_EQ(a->frameMilliseconds, 12.5);
    EXPECT_EQ(a->image.width(), 8);
    EXPECT_FLOAT_EQ(a->image.at(3, 2).x, 0.75f);

    // Each damage on a fresh copy of the entry "a".
    const auto damaged = [&](const std::function<void()>& damage) {
        cache.store(entry("a", 0.75f));
        damage();
        return !cache.find("a").has_value();
    };
    EXPECT_TRUE(damaged([&] { fs::copy_file(dir / "b.exr", dir / "a.exr", fs::copy_options::overwrite_existing); }));
    EXPECT_TRUE(damaged([&] { fs::resize_file(dir / "a.exr", fs::file_size(dir / "a.exr") / 2); }));
    EXPECT_TRUE(damaged([&] { fs::copy_file(dir / "b.mask.exr", dir / "a.mask.exr", fs::copy_options::overwrite_existing); }));
    EXPECT_TRUE(damaged([&] { overwrite(dir / "a.json", ""); }));
    EXPECT_TRUE(damaged([&] { overwrite(dir / "a.json", "\"frame_ms\""); }));
    EXPECT_TRUE(damaged([&] { overwrite(dir / "a.json", "{\"frame_ms\": 12.5}"); }));  // an entry of an older program
    EXPECT_TRUE(damaged([&] {
        std::ifstream in(dir / "a.json");
        std::string meta((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        meta.replace(meta.find("12.5"), 4, "-5");
        overwrite(dir / "a.json", meta);
    }));
    EXPECT_TRUE(damaged([&] {
        fs::remove(dir / "a.json");
        fs::create_directory(dir / "a.json");
    }));
    // Stored again over the damage, it is found again.
    fs::remove_all(dir / "a.json");
    cache.store(entry("a", 0.75f));
    EXPECT_TRUE(cache.find("a").has_value());
}

// A cache that cannot be written is said and done without: the reference in hand is not lost.
TEST(ReferenceCache, ACacheThatCannotBeWrittenIsAWarningNotAFailure) {
    test::TempDir dir;
    overwrite(dir / "a-file", "x");
    const ReferenceCache underAFile(dir / "a-file" / "references");
    EXPECT_NO_THROW(underAFile.store(entry("a", 0.75f)));
    EXPECT_FALSE(underAFile.find("a").has_value());
}

}  // namespace
}  // namespace hybridlab
