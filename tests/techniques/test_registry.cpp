// The registry (techniques/registry.cpp) is the one way to a technique: the program and the runner
// (experiments/) include no header of a technique's folder, and reach what a technique offers
// beyond rendering (its bake command) through TechniqueInfo.
#include <regex>
#include <string>

#include <gtest/gtest.h>

#include "techniques/technique.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

namespace fs = std::filesystem;

TEST(Registry, TheProgramReachesTechniquesOnlyThroughIt) {
    const fs::path source = test::sourceDir();
    const std::regex include(R"re(#include "techniques/(\w+)/)re");
    std::size_t files = 0;
    for (const auto& entry : fs::recursive_directory_iterator(source / "experiments")) {
        if (entry.path().extension() != ".cpp" && entry.path().extension() != ".h") continue;
        ++files;
        const std::string text = test::readTextFile(entry.path());
        for (std::sregex_iterator m(text.begin(), text.end(), include), end; m != end; ++m) {
            const std::string folder = (*m)[1];
            EXPECT_FALSE(fs::exists(source / "techniques" / folder / "CMakeLists.txt"))
                << entry.path() << " includes a header of technique folder techniques/" << folder;
        }
    }
    EXPECT_GT(files, 20u);
}

// What `hybridlab tune` searches: every declared knob names a parameter of its technique and every
// grid value is one the parameter accepts, at a small and a large frame (a budget per pixel).
TEST(Registry, EverySearchSpaceNamesItsParametersAndTheirRanges) {
    std::size_t searched = 0;
    for (const TechniqueInfo& t : registeredTechniques()) {
        for (const double pixels : {64.0 * 36.0, 3840.0 * 2160.0}) EXPECT_NO_THROW(checkSearchSpace(t.name, t.parameters, t.searchSpace, pixels)) << t.name;
        searched += !t.searchSpace.empty();
    }
    EXPECT_GE(searched, 4u);  // whitted, rt_only, heuristic_rt, ssr_fallback
    for (const char* name : {"heuristic_rt", "ssr_fallback"}) EXPECT_FALSE(findTechnique(name).searchSpace.empty()) << name;
}

TEST(Registry, ASearchSpaceDeclarationErrorIsCaught) {
    const std::vector<ParamSpec> specs = {ParamSpec::integer("steps", 8, 1, 64, "steps"), ParamSpec::choice("mode", "a", {"a", "b"}, "mode")};
    using S = SearchDimension::Scale;
    EXPECT_NO_THROW(checkSearchSpace("t", specs, {{"steps", {2LL, 8LL, 32LL}, S::Log}, {"mode", {std::string("a"), std::string("b")}, S::Choice}}));
    EXPECT_THROW(checkSearchSpace("t", specs, {{"stride", {2LL}, S::Log}}), std::logic_error);              // no such parameter
    EXPECT_THROW(checkSearchSpace("t", specs, {{"steps", {2LL, 128LL}, S::Log}}), std::logic_error);        // out of range
    EXPECT_THROW(checkSearchSpace("t", specs, {{"steps", {8LL, 2LL}, S::Linear}}), std::logic_error);       // not increasing
    EXPECT_THROW(checkSearchSpace("t", specs, {{"mode", {std::string("a")}, S::Linear}}), std::logic_error);  // a choice refined
    EXPECT_THROW(checkSearchSpace("t", specs, {{"steps", {1LL, 2LL}, S::Log, /*perPixel=*/true}}, 100.0), std::logic_error);  // 200 > 64
}

TEST(Registry, LayeredEmOffersItsBakeCommand) {
    const TechniqueInfo& info = findTechnique("layered_em");
    ASSERT_TRUE(info.bakeCommand);
    EXPECT_EQ(info.bakeCommand->name, "bake-em");
    for (const TechniqueInfo& other : registeredTechniques()) {
        if (other.name != "layered_em") {
            EXPECT_FALSE(other.bakeCommand) << other.name;
        }
    }
}

}  // namespace
}  // namespace hybridlab
