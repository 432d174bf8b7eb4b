#pragma once
// Shared helpers of the test suite: temporary folders, file writing, vector comparisons and the
// locations of scenes, fixtures and assets.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <gtest/gtest.h>

namespace hybridlab::test {

// A new, empty folder under the system temporary folder; removed with its contents on destruction.
class TempDir {
public:
    TempDir();
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    const std::filesystem::path& path() const { return path_; }
    std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

private:
    std::filesystem::path path_;
};

void writeTextFile(const std::filesystem::path& path, const std::string& text);
// The whole file as text ("" if it cannot be read).
std::string readTextFile(const std::filesystem::path& path);
void writeBinaryFile(const std::filesystem::path& path, const std::vector<std::uint8_t>& bytes);
// The lines of `text`, without their line breaks.
std::vector<std::string> textLines(const std::string& text);
// Every file and folder under `dir`, as sorted relative paths (none if `dir` does not exist).
std::vector<std::string> fileTree(const std::filesystem::path& dir);

// tests/fixtures in the source tree.
std::filesystem::path fixturesDir();
// The source tree's root.
std::filesystem::path sourceDir();
// scenes/<name>.toml in the source tree.
std::filesystem::path builtinSceneFile(const std::string& name);

// The name of a test instantiated per scene (GoogleTest names allow no '-'): the scene name with '_'.
struct SceneTestName {
    template <class ParamInfo>
    std::string operator()(const ParamInfo& info) const {
        std::string n = info.param;
        for (char& c : n)
            if (c == '-') c = '_';
        return n;
    }
};

::testing::AssertionResult vecNear(glm::vec2 actual, glm::vec2 expected, float tolerance);
::testing::AssertionResult vecNear(glm::vec3 actual, glm::vec3 expected, float tolerance);
::testing::AssertionResult vecNear(glm::vec4 actual, glm::vec4 expected, float tolerance);

// Whether `text` contains `fragment`, with both in the message when not.
::testing::AssertionResult contains(const std::string& text, const std::string& fragment);

}  // namespace hybridlab::test

#define EXPECT_VEC_NEAR(actual, expected, tolerance) EXPECT_TRUE(::hybridlab::test::vecNear((actual), (expected), (tolerance)))
#define ASSERT_VEC_NEAR(actual, expected, tolerance) ASSERT_TRUE(::hybridlab::test::vecNear((actual), (expected), (tolerance)))
#define EXPECT_CONTAINS(text, fragment) EXPECT_TRUE(::hybridlab::test::contains((text), (fragment)))
