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
