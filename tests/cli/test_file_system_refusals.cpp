// Paths the file system refuses where no reader checked them first (a name longer than the file
// system allows, a loop of links): the machine's answer about a file, one line naming the path and
// the reason, exit status 3, never an internal error.
#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/cli_runner.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

namespace fs = std::filesystem;

TEST(FileSystemRefusals, ANameTooLongOrALinkLoopIsExitThreeNamingThePath) {
    test::TempDir dir;
    const fs::path tooLong = dir / std::string(300, 'n');
    fs::create_symlink("loop", dir / "loop");
    const fs::path inLoop = dir / "loop" / "x";
    for (const fs::path& out : {tooLong, inLoop}) {
        const std::string reason = out == tooLong ? "File name too long" : "Too many levels of symbolic links";
        for (const std::vector<std::string>& args :
             {std::vector<std::string>{"render", "--scene", "whitted-classic", "--width", "16", "--height", "16", "--out", out.string() + ".exr"},
              std::vector<std::string>{"bundle", "--out", out.string()}}) {
            const test::CliResult r = test::runHybridlab(args);
            EXPECT_EQ(r.exitStatus, 3) << args[0] << " " << r.err;
            EXPECT_CONTAINS(r.err, out.string());
            EXPECT_CONTAINS(r.err, reason);
            EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
            EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        }
    }
}

}  // namespace
}  // namespace hybridlab
