// The runner under the failures a long experiment meets: killed at random moments, the disk
// filling up, a second runner on the same folder. Each time the files under their final names
// are whole, nothing of the failed writes remains once --resume has finished, and the result set
// equals an uninterrupted run's (records apart from times, images byte for byte).
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <iterator>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/core/atomic_file.h"
#include "common/core/directory_lock.h"
#include "common/image/image_io.h"
#include "tests/support/cli_runner.h"
#include "tests/support/runner_checks.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::TempDir;

// 2 views x 2 frames... : 12 small runs, each writing a record, an EXR, a PNG and error maps.
const char* kConfig = R"(
[experiment]
name = "interrupted"
warmup_frames = 0
repeats = 2

[reference]
params = { max_depth = 3 }

[[scenes]]
scene = "whitted-classic"
resolutions = [[40, 24]]
[[scenes.views]]
path = "orbit"
frames = [0, 50]
stride = 10

[[techniques]]
name = "whitted"
params = { max_depth = [1, 2] }
)";

constexpr std::size_t kRuns = 12;

std::vector<std::string> runArgs(const fs::path& config, const fs::path& out, const fs::path& cache, bool resume) {
    std::vector<std::string> a = {"run", config.string(), "--out", out.string(), "--cache", cache.string(), "--quiet"};
    if (resume) a.push_back("--resume");
    return a;
}

std::size_t recordCount(const fs::path& out) {
    std::size_t n = 0;
    std::error_code ec;
    for (fs::directory_iterator it(out / "runs", ec), end; !ec && it != end; it.increment(ec)) n += it->path().filename().string().front() != '.';
    return n;
}

std::vector<fs::path> leftovers(const fs::path& out) {
    std::vector<fs::path> found;
    for (const auto& e : fs::recursive_directory_iterator(out)) {
        const std::string name = e.path().filename().string();
        if (name.rfind(".tmp-", 0) == 0 || name == DirectoryLock::kFileName) found.push_back(e.path());
    }
    return found;
}

// Every file under its final name is whole: JSON parses, images decode.
void expectWholeFiles(const fs::path& out) {
    for (const auto& e : fs::recursive_directory_iterator(out)) {
        if (!e.is_regular_file() || e.path().filename().string().front() == '.') continue;
        const std::string ext = e.path().extension().string();
        SCOPED_TRACE(e.path().string());
        if (ext == ".json") {
            std::ifstream in(e.path());
            EXPECT_FALSE(json::parse(in, nullptr, false).is_discarded());
        } else if (ext == ".exr" || ext == ".png") {
            EXPECT_NO_THROW(EXPECT_GT(readImage(e.path()).pixelCount(), 0u));
        }
    }
}

// Same records apart from times, and every image byte for byte.
void expectSameResultSet(const fs::path& expected, const fs::path& actual) {
    auto a = test::readResults(expected), b = test::readResults(actual);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(test::comparableRecord(a[i]), test::comparableRecord(b[i])) << a[i].at("id");
    std::size_t images = 0;
    for (const auto& e : fs::recursive_directory_iterator(expected)) {
        const std::string ext = e.path().extension().string();
        if (ext != ".exr" && ext != ".png") continue;
        const fs::path other = actual / fs::relative(e.path(), expected);
        SCOPED_TRACE(other.string());
        ASSERT_TRUE(fs::exists(other));
        EXPECT_EQ(test::readTextFile(e.path()), test::readTextFile(other)) << "not byte-identical";
        ++images;
    }
    EXPECT_GE(images, 2 * kRuns);
}

TEST(RunnerInterruptions, FiveRandomKillsThenResumeEqualsAnUninterruptedRun) {
    TempDir dir;
    const fs::path config = dir / "interrupted.toml", cache = dir / "cache", killed = dir / "killed", whole = dir / "whole";
    test::writeTextFile(config, kConfig);
    // The uninterrupted run first: it fills the reference cache both then share.
    const auto reference = test::runHybridlab(runArgs(config, whole, cache, false));
    ASSERT_EQ(reference.exitStatus, 0) << reference.err;

    std::mt19937 random(20261125);
    int kills = 0;
    for (int attempt = 0; attempt < 5; ++attempt) {
        const std::vector<std::string> args = runArgs(config, killed, cache, attempt > 0);
        const pid_t pid = fork();
        ASSERT_GE(pid, 0);
        if (pid == 0) {
            std::vector<char*> argv = {const_cast<char*>(HYBRIDLAB_BIN)};
            for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
            argv.push_back(nullptr);
            execv(HYBRIDLAB_BIN, argv.data());
            _exit(127);
        }
        // A random moment after the next record or two, so that each kill lands mid-way: within 2 ms
        // of the record (a group of this config's tiny frames can take less than 40 ms), and at
        // once where the runner ended first (it finished: nothing to wait for).
        const std::size_t target = recordCount(killed) + 1 + random() % 2;
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
        int status = 0;
        bool exited = false;
        while (recordCount(killed) < target && std::chrono::steady_clock::now() < deadline && !exited) {
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
            exited = waitpid(pid, &status, WNOHANG) == pid;
        }
        if (!exited) {
            std::this_thread::sleep_for(std::chrono::microseconds(random() % 2000));
            kill(pid, SIGKILL);
            waitpid(pid, &status, 0);
        }
        if (WIFSIGNALED(status)) ++kills;
        expectWholeFiles(killed);
    }
    EXPECT_GE(kills, 3) << "most kills should land before the run finishes";
    const auto resumed = test::runHybridlab(runArgs(config, killed, cache, true));
    ASSERT_EQ(resumed.exitStatus, 0) << resumed.err;
    EXPECT_EQ(recordCount(killed), kRuns);
    EXPECT_EQ(leftovers(killed), std::vector<fs::path>{}) << "no .tmp-* or .lock left";
    expectSameResultSet(whole, killed);
}

TEST(RunnerInterruptions, FullDiskNamesTheFileLeavesNothingTruncatedAndResumes) {
    TempDir dir;
    const fs::path config = dir / "interrupted.toml", cache = dir / "cache", full = dir / "full", whole = dir / "whole";
    test::writeTextFile(config, kConfig);
    const auto reference = test::runHybridlab(runArgs(config, whole, cache, false));
    ASSERT_EQ(reference.exitStatus, 0) << reference.err;
    // The disk fills after 40 kB: a few runs in, in the middle of some file.
    const auto failed = test::runHybridlab(runArgs(config, full, cache, false), {{"HYBRIDLAB_TEST_WRITE_LIMIT", "40000"}});
    EXPECT_EQ(failed.exitStatus, 3) << failed.err;
    EXPECT_EQ(failed.err.rfind("hybridlab: error: " + full.string() + "/", 0), 0u) << failed.err;
    EXPECT_NE(failed.err.find(": cannot write (No space left on device)\n"), std::string::npos) << failed.err;
    const std::size_t recorded = recordCount(full);
    EXPECT_LT(recorded, kRuns);
    expectWholeFiles(full);
    std::vector<fs::path> temporaries;
    for (const auto& p : leftovers(full))
        if (p.filename() != DirectoryLock::kFileName) temporaries.push_back(p);
    EXPECT_EQ(temporaries, std::vector<fs::path>{}) << "a failed write removes its temporary";
    // Space freed: --resume completes the set.
    const auto resumed = test::runHybridlab(runArgs(config, full, cache, true));
    ASSERT_EQ(resumed.exitStatus, 0) << resumed.err;
    EXPECT_NE(resumed.out.find(std::to_string(recorded) + " already done"), std::string::npos) << resumed.out;
    EXPECT_EQ(leftovers(full), std::vector<fs::path>{});
    expectSameResultSet(whole, full);
}

TEST(RunnerInterruptions, SecondRunnerIsRefusedAndADeadOnesLockAndTemporariesAreTakenOver) {
    TempDir dir;
    const fs::path config = dir / "interrupted.toml", cache = dir / "cache", out = dir / "out";
    test::writeTextFile(config, kConfig);
    const auto first = test::runHybridlab(runArgs(config, out, cache, false));
    ASSERT_EQ(first.exitStatus, 0) << first.err;
    char host[256] = {};
    gethostname(host, sizeof host - 1);

    // A live owner (this test process): refused, naming it, nothing written.
    test::writeTextFile(out / DirectoryLock::kFileName, std::to_string(getpid()) + " " + host + "\n");
    const auto refused = test::runHybridlab(runArgs(config, out, cache, true));
    EXPECT_EQ(refused.exitStatus, 2) << refused.err;
    EXPECT_NE(refused.err.find(out.string() + ": in use by process " + std::to_string(getpid()) + " on " + host + " (lock file "),
              std::string::npos)
        << refused.err;

    // A dead owner (a child that has exited) and the partial files it left: taken over, removed.
    const pid_t dead = fork();
    if (dead == 0) _exit(0);
    waitpid(dead, nullptr, 0);
    test::writeTextFile(out / DirectoryLock::kFileName, std::to_string(dead) + " " + host + "\n");
    test::writeTextFile(out / "images" / (".tmp-" + std::to_string(dead) + "-00003-whatever.png"), "half a PNG");
    test::writeTextFile(out / "runs" / (".tmp-" + std::to_string(dead) + "-00003-whatever.json"), "{\"half");
    const auto resumed = test::runHybridlab(runArgs(config, out, cache, true));
    EXPECT_EQ(resumed.exitStatus, 0) << resumed.err;
    EXPECT_NE(resumed.out.find("removed 2 partial file(s) (.tmp-*) left by interrupted runs"), std::string::npos) << resumed.out;
    EXPECT_EQ(leftovers(out), std::vector<fs::path>{});
}

// Two cluster nodes filling one shared reference cache may run writers of the same PID: the one
// that finds the temporary name taken writes under another, and neither file is touched by the
// other's writes.
TEST(RunnerInterruptions, TemporaryNameHeldByAnotherMachinesProcessIsLeftAlone) {
    TempDir dir;
    const fs::path target = dir / "key.json", image = dir / "key.txt";
    for (const fs::path& p : {target, image}) test::writeTextFile(temporaryPathFor(p), "the other node's half-written file");
    writeFileAtomically(target, "mine\n");
    writeAtomically(image, [](const fs::path& tmp) { test::writeTextFile(tmp, "encoded\n"); });
    EXPECT_EQ(test::readTextFile(target), "mine\n");
    EXPECT_EQ(test::readTextFile(image), "encoded\n");
    for (const fs::path& p : {target, image}) EXPECT_EQ(test::readTextFile(temporaryPathFor(p)), "the other node's half-written file");
    // Nothing else left: the two taken names and the two targets.
    EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 4);
}

// A merge or bundle killed while filling its folder leaves the folder's temporary beside it: the
// next write of that folder removes it, and leaves other folders' temporaries alone.
TEST(RunnerInterruptions, AStagingFolderAKilledProcessLeftIsRemovedByTheNextWrite) {
    test::TempDir dir;
    const pid_t dead = fork();
    if (dead == 0) _exit(0);
    waitpid(dead, nullptr, 0);
    const fs::path stale = dir / (".tmp-" + std::to_string(dead) + "-merged");
    const fs::path otherTarget = dir / (".tmp-" + std::to_string(dead) + "-other");
    fs::create_directories(stale / "runs");
    fs::create_directories(otherTarget);
    test::writeTextFile(stale / "runs" / "half.json", "{\"half");
    test::writeTextFile(otherTarget / "x", "1");
    writeFolderAtomically(dir / "merged", [](const fs::path& staging) { test::writeTextFile(staging / "results.json", "[]\n"); });
    EXPECT_FALSE(fs::exists(stale));
    EXPECT_TRUE(fs::exists(dir / "merged" / "results.json"));
    EXPECT_TRUE(fs::exists(otherTarget)) << "another folder's temporary is its own write's to collect";
}

}  // namespace
}  // namespace hybridlab
