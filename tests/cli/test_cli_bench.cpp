// `hybridlab bench` at a small size: the reference's rays all logged and replayed, the throughput
// lines and a ratio that is a share, not a stray number.
#include <regex>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/cli_runner.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

TEST(CliBench, LogsEveryRayOfTheReferenceAndComparesItsThroughput) {
    const test::CliResult r =
        test::runHybridlab({"bench", "--scene", "whitted-classic", "--width", "48", "--height", "27", "--repeats", "3", "--threads", "2"},
                           {{"VK_ICD_FILENAMES", "/nonexistent"}});
    ASSERT_EQ(r.exitStatus, 0) << r.err;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(r.out, m, std::regex(R"(rays per frame +(\d+) \(primary (\d+),.*\); logged (\d+))"))) << r.out;
    EXPECT_EQ(m[1], m[3]);        // every ray the frame counted was logged for the replay
    EXPECT_EQ(m[2].str(), "1296");  // one camera ray a pixel
    ASSERT_TRUE(std::regex_search(r.out, m, std::regex(R"(reference / bare Embree +([0-9.]+) %)"))) << r.out;
    const double percent = std::stod(m[1]);
    EXPECT_GT(percent, 5.0);
    EXPECT_LT(percent, 200.0);
    EXPECT_CONTAINS(r.out, "bare Embree, same rays");
    EXPECT_CONTAINS(r.out, "vulkan: not measured");  // no device here: said, not failed
}

}  // namespace
}  // namespace hybridlab
