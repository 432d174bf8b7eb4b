// `hybridlab help [COMMAND]` prints what --help prints and refuses an unknown command as bad input.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/cli_runner.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

TEST(HelpCommand, PrintsTheProgramsOrACommandsHelp) {
    const std::vector<test::CliResult> r = test::runHybridlabAll({{{"help"}, {}},
                                                                 {{"--help"}, {}},
                                                                 {{"help", "compare"}, {}},
                                                                 {{"compare", "--help"}, {}},
                                                                 {{"help", "paint"}, {}},
                                                                 {{"help", ""}, {}},
                                                                 {{"help", "help"}, {}}});
    for (int i = 0; i < 4; ++i) ASSERT_EQ(r[i].exitStatus, 0) << i << ": " << r[i].err;
    EXPECT_EQ(r[0].out, r[1].out);
    EXPECT_CONTAINS(r[0].out, "render");
    EXPECT_CONTAINS(r[0].out, "help");
    EXPECT_CONTAINS(r[2].out, "--fail-above");
    EXPECT_CONTAINS(r[2].out, "flip_hdr.png");
    EXPECT_EQ(r[2].out, r[3].out);
    EXPECT_EQ(r[4].exitStatus, 2);
    EXPECT_EQ(r[4].out, "");
    EXPECT_CONTAINS(r[4].err, "hybridlab: error: help: unknown command 'paint' (commands: scenes, ");
    EXPECT_EQ(r[5].exitStatus, 2);  // an empty name is no command, not the program's help
    EXPECT_CONTAINS(r[5].err, "hybridlab: error: help: unknown command '' (commands: ");
    EXPECT_EQ(r[6].exitStatus, 0) << r[6].err;
    EXPECT_CONTAINS(r[6].out, "A command's name");
}

}  // namespace
}  // namespace hybridlab
