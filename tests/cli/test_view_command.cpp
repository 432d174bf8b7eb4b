// `hybridlab view`'s refusals, each on one line with its exit status: a port another program holds
// (the machine's answer: 3) and a folder without a report to serve (bad input: 2).
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/cli_runner.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

TEST(ViewCommand, APortInUseAndAMissingReportAreOneLineEach) {
    test::TempDir dir;
    test::writeTextFile(dir / "results.json", "[]\n");
    std::filesystem::create_directories(dir / "report");
    test::writeTextFile(dir / "report" / "viewer.html", "<html></html>\n");

    // A port held by this test.
    const int held = socket(AF_INET, SOCK_STREAM, 0);
    ASSERT_GE(held, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ASSERT_EQ(bind(held, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
    ASSERT_EQ(listen(held, 1), 0);
    socklen_t length = sizeof address;
    ASSERT_EQ(getsockname(held, reinterpret_cast<sockaddr*>(&address), &length), 0);
    const std::string port = std::to_string(ntohs(address.sin_port));

    const test::CliResult inUse = test::runHybridlab({"view", dir.path().string(), "--port", port});
    close(held);
    EXPECT_EQ(inUse.exitStatus, 3) << inUse.err;
    EXPECT_EQ(inUse.err, "hybridlab: error: cannot listen on 127.0.0.1:" + port + ": Address already in use\n");

    std::filesystem::remove(dir / "report" / "viewer.html");
    const test::CliResult noReport = test::runHybridlab({"view", dir.path().string(), "--port", "0"});
    EXPECT_EQ(noReport.exitStatus, 2) << noReport.err;
    EXPECT_CONTAINS(noReport.err, "no viewer.html (write the report first: hybridlab report ");
    EXPECT_EQ(std::count(noReport.err.begin(), noReport.err.end(), '\n'), 1) << noReport.err;
}

}  // namespace
}  // namespace hybridlab
