// The second round of hardening, through the real program, where the case is more than one
// message (the rest are rows of test_bad_input_table.cpp): a mirrored scene renders as the plain
// one's mirror image; runners started together on one folder, the losers told who holds it;
// non-finite pixels named by `compare` (or blacked out when asked) and counted in a run's record;
// a file `export-pov` cannot write named as the user gave it, not by its temporary name.
#include <algorithm>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/image/image_io.h"
#include "metrics/metrics.h"
#include "tests/support/cli_runner.h"
#include "tests/support/mirrored_scene.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

namespace fs = std::filesystem;
using test::CliResult;
using test::CliRun;
using test::runHybridlab;
using test::runHybridlabAll;
using test::TempDir;

std::vector<std::string> renderArgs(const fs::path& scene, const std::string& technique, const fs::path& out) {
    return {"render", "--scene", scene.string(), "--technique", technique, "--width", "48", "--height", "32", "--out", out.string()};
}

TEST(CliHardening, MirroredSceneRendersAsThePlainOneFlipped) {
    TempDir dir;
    const test::MirroredScenes files = test::writeMirroredScenes(dir.path());
    std::vector<CliRun> runs;
    for (const std::string technique : {"whitted", "raster"})
        for (const auto& [scene, name] : {std::pair{files.plain, "plain"}, std::pair{files.mirrored, "mirrored"}})
            runs.push_back({renderArgs(scene, technique, dir / (technique + "-" + name + ".exr")), {}});
    const std::vector<CliResult> results = runHybridlabAll(runs);
    for (const std::string technique : {"whitted", "raster"}) {
        SCOPED_TRACE(technique);
        const CliResult& plain = results[technique == "whitted" ? 0 : 2];
        const CliResult& mirrored = results[technique == "whitted" ? 1 : 3];
        if (technique == "raster" && plain.exitStatus == 1 && plain.err.find("Vulkan") != std::string::npos) {
            std::printf("[ mirror ] raster skipped, no Vulkan device: %s", plain.err.c_str());
            continue;
        }
        ASSERT_EQ(plain.exitStatus, 0) << plain.err;
        ASSERT_EQ(mirrored.exitStatus, 0) << mirrored.err;
        const Image a = readImage(dir / (technique + "-plain.exr")), b = readImage(dir / (technique + "-mirrored.exr"));
        const double ssim = computeMetrics(b, test::flippedLeftToRight(a)).whole.ssim;
        EXPECT_GE(ssim, 0.999);
        EXPECT_LT(computeMetrics(b, a).whole.ssim, 0.95) << "the scene is not its own mirror image";
        std::printf("[ mirror ] %s through the program: SSIM %.6f\n", technique.c_str(), ssim);
    }
}

// `text` as a regular expression that matches it alone.
std::string literal(const std::string& text) { return std::regex_replace(text, std::regex(R"([.^$|()\[\]{}*+?\\])"), R"(\$&)"); }

// Twenty pairs of runners, each pair started together on one new folder, one of each pair with
// --resume in every other pair: in each pair one runs the experiment, the other is refused naming
// the runner that holds the folder (its process, machine and start, from the lock file).
TEST(CliHardening, RunnersStartedTogetherOnOneFolderTellTheLoserWhoHoldsIt) {
    TempDir dir;
    const fs::path config = dir / "race.toml", cache = dir / "cache";
    // One frame of each: the winner holds its folder for its reference and its run, 0.2 s of
    // processor time, while the loser, started with it, reaches the lock as it does.
    test::writeTextFile(config, "[experiment]\nname = \"race\"\nwarmup_frames = 0\nrepeats = 1\nmax_rounds = 1\n\n"
                                "[[scenes]]\nscene = \"whitted-classic\"\nresolutions = [[64, 48]]\n\n"
                                "[[techniques]]\nname = \"whitted\"\nparams = { max_depth = 1 }\n");
    constexpr int kPairs = 20;
    std::vector<CliRun> runs;
    for (int k = 0; k < kPairs; ++k) {
        const fs::path out = dir / ("out-" + std::to_string(k));
        for (int r = 0; r < 2; ++r) {
            std::vector<std::string> args = {"run", config.string(), "--out", out.string(), "--cache", cache.string(), "--quiet"};
            if (r == 1 && k % 2 == 1) args.push_back("--resume");
            runs.push_back({args, {}});
        }
    }
    // A few pairs at a time: forty processes started at once on two cores left a pair's second
    // process waiting to be scheduled until its first had finished, and then a --resume found
    // nothing to do and the other the results already there (a race the lock never saw).
    constexpr int kPairsAtOnce = 4;
    std::vector<CliResult> results;
    for (int first = 0; first < kPairs; first += kPairsAtOnce) {
        const std::vector<CliRun> batch(runs.begin() + 2 * first, runs.begin() + 2 * std::min(kPairs, first + kPairsAtOnce));
        for (CliResult& r : runHybridlabAll(batch)) results.push_back(std::move(r));
    }
    char host[256] = {};
    gethostname(host, sizeof host - 1);
    int refused = 0;
    for (int k = 0; k < kPairs; ++k) {
        SCOPED_TRACE("pair " + std::to_string(k));
        const fs::path out = dir / ("out-" + std::to_string(k));
        const CliResult& a = results[2 * k];
        const CliResult& b = results[2 * k + 1];
        ASSERT_EQ((a.exitStatus == 0) + (b.exitStatus == 0), 1) << a.err << b.err;
        const CliResult& loser = a.exitStatus == 0 ? b : a;
        EXPECT_EQ(loser.exitStatus, 2) << loser.err;
        const std::regex holder(literal(out.string() + ": in use by process ") + "[0-9]+" + literal(" on " + std::string(host) + " since ") +
                                "[0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9]{2}:[0-9]{2}:[0-9]{2}Z" + literal(" (lock file "));
        EXPECT_TRUE(std::regex_search(loser.err, holder)) << loser.err;
        refused += loser.exitStatus == 2;
        EXPECT_TRUE(fs::exists(out / "results.json"));
        EXPECT_FALSE(fs::exists(out / ".lock"));
    }
    std::printf("[ race ] %d pairs: %d losers refused, each naming the holder\n", kPairs, refused);
}

// A --resume that finds one of the set's records broken, or a run recorded twice, stops before it
// renders or removes anything: the finished set's results.json is still there, byte for byte.
TEST(CliHardening, ResumeRefusesABrokenRecordBeforeTouchingTheSet) {
    TempDir dir;
    const fs::path config = dir / "small.toml", out = dir / "set", cache = dir / "cache";
    test::writeTextFile(config, "[experiment]\nname = \"small\"\nwarmup_frames = 0\nrepeats = 1\n\n"
                                "[[scenes]]\nscene = \"whitted-classic\"\nresolutions = [[32, 18]]\n\n"
                                "[[techniques]]\nname = \"whitted\"\nparams = { max_depth = [1, 2] }\n");
    const std::vector<std::string> run = {"run", config.string(), "--out", out.string(), "--cache", cache.string(), "--quiet"};
    const CliResult first = runHybridlab(run);
    ASSERT_EQ(first.exitStatus, 0) << first.err;
    const std::string results = test::readTextFile(out / "results.json");
    fs::path broken;
    for (const auto& e : fs::directory_iterator(out / "runs")) broken = e.path();
    ASSERT_FALSE(broken.empty());
    test::writeTextFile(broken, "{");
    std::vector<std::string> resume = run;
    resume.push_back("--resume");
    const CliResult again = runHybridlab(resume);
    EXPECT_EQ(again.exitStatus, 2) << again.err;
    EXPECT_CONTAINS(again.err, broken.filename().string());
    ASSERT_TRUE(fs::exists(out / "results.json"));
    EXPECT_EQ(test::readTextFile(out / "results.json"), results);
    EXPECT_TRUE(fs::exists(out / "results.csv"));
    // A record copied under another name: a second record of its run, refused naming both files
    // (resumed, it would be listed twice in results.json).
    fs::path whole;
    for (const auto& e : fs::directory_iterator(out / "runs"))
        if (e.path() != broken) whole = e.path();
    ASSERT_FALSE(whole.empty());
    fs::remove(broken);
    fs::copy_file(whole, out / "runs" / "copy.json");
    const CliResult copied = runHybridlab(resume);
    EXPECT_EQ(copied.exitStatus, 2) << copied.err;
    EXPECT_CONTAINS(copied.err, (out / "runs" / "copy.json").string() + ": holds the record of run '" + whole.stem().string() +
                                    "', expected the run its name says, 'copy' (" + whole.string() + " holds that run's record too)");
    EXPECT_EQ(test::readTextFile(out / "results.json"), results);
    fs::remove(out / "runs" / "copy.json");
    // A broken experiment.json: not JSON, or JSON that is no experiment record.
    for (const char* meta : {"{", "[]"}) {
        SCOPED_TRACE(meta);
        test::writeTextFile(out / "experiment.json", meta);
        const CliResult r = runHybridlab(resume);
        EXPECT_EQ(r.exitStatus, 2) << r.err;
        EXPECT_CONTAINS(r.err, (out / "experiment.json").string() + ": ");
        EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
    }
}

TEST(CliHardening, CompareNamesNonFinitePixelsAndScoresTheRestOnlyWhenAsked) {
    TempDir dir;
    Image reference(32, 24, glm::vec4(0.2f, 0.4f, 0.6f, 1.0f)), test = reference;
    test.at(3, 5).r = std::numeric_limits<float>::quiet_NaN();
    test.at(20, 9).b = std::numeric_limits<float>::infinity();
    writeExr(dir / "test.exr", test);
    writeExr(dir / "reference.exr", reference);
    const std::vector<std::string> compare = {"compare", (dir / "test.exr").string(), (dir / "reference.exr").string(), "--out",
                                              (dir / "maps").string()};
    const CliResult refused = runHybridlab(compare);
    EXPECT_EQ(refused.exitStatus, 2) << refused.err;
    EXPECT_EQ(refused.out, "");
    EXPECT_CONTAINS(refused.err, "hybridlab: error: " + (dir / "test.exr").string() +
                                     ": 2 non-finite pixels (NaN or infinite), the first at (3, 5): (nan, 0.4, 0.6, 1): every metric would be "
                                     "NaN (pass --ignore-nonfinite");
    EXPECT_FALSE(fs::exists(dir / "maps"));

    std::vector<std::string> ignoring = compare;
    ignoring.push_back("--ignore-nonfinite");
    const CliResult scored = runHybridlab(ignoring);
    EXPECT_EQ(scored.exitStatus, 0) << scored.err;
    EXPECT_CONTAINS(scored.out, "note: " + (dir / "test.exr").string() + ": 2 non-finite pixels (NaN or infinite), the first at (3, 5)");
    EXPECT_CONTAINS(scored.out, "ignored: black in both images");
    const std::string ssimRow = scored.out.substr(scored.out.find("\nSSIM"));
    EXPECT_EQ(ssimRow.find("nan"), std::string::npos) << ssimRow;
    EXPECT_TRUE(fs::exists(dir / "maps" / "metrics.json"));
}

// A light so bright that lit pixels come out infinite: `render` names them on stderr, and a run's
// record counts them while its metrics stay numbers.
TEST(CliHardening, NonFinitePixelsOfARenderAreNamedAndCountedInTheRunRecord) {
    TempDir dir;
    test::writeTextFile(dir / "blinding.toml",
                        "[materials.grey]\ndiffuse = [0.5, 0.5, 0.5]\n\n[[objects]]\nname = \"floor\"\nprimitive = \"plane\"\nmaterial = \"grey\"\n"
                        "scale = 10.0\n\n[[lights]]\ntype = \"point\"\nposition = [0.0, 2.0, 0.0]\ncolor = [3e38, 3e38, 3e38]\n"
                        "intensity = 1e12\n\n[camera]\nposition = [0.0, 3.0, 5.0]\nlook_at = [0.0, 0.0, 0.0]\n");
    test::writeTextFile(dir / "blinding-run.toml", "[experiment]\nwarmup_frames = 0\nrepeats = 1\n\n[[scenes]]\nscene = \"blinding.toml\"\n"
                                                   "resolutions = [[24, 16]]\n\n[[techniques]]\nname = \"whitted\"\n");
    const CliResult render = runHybridlab(renderArgs(dir / "blinding.toml", "whitted", dir / "x.exr"));
    EXPECT_EQ(render.exitStatus, 0) << render.err;
    EXPECT_CONTAINS(render.err, "hybridlab: warning: " + (dir / "x.exr").string() + ": ");
    EXPECT_CONTAINS(render.err, " non-finite pixels (NaN or infinite), the first at (");

    const CliResult run = runHybridlab({"run", (dir / "blinding-run.toml").string(), "--out", (dir / "out").string(), "--cache",
                                        (dir / "cache").string(), "--quiet"});
    ASSERT_EQ(run.exitStatus, 0) << run.err;
    std::ifstream in(dir / "out" / "results.json");
    const nlohmann::json records = nlohmann::json::parse(in);
    ASSERT_EQ(records.size(), 1u);
    EXPECT_GT(records[0].at("counters").at("nonfinite_pixels").get<double>(), 0.0);
    EXPECT_TRUE(records[0].at("metrics").at("whole").at("ssim").is_number()) << records[0].at("metrics").dump();
}

TEST(CliHardening, ExportPovNamesTheFileItCannotWriteNotItsTemporary) {
    TempDir dir;
    const std::vector<std::string> exportTo = {"export-pov", "--scene", "whitted-classic", "--width", "32", "--height", "24", "--out"};
    std::vector<CliRun> runs = {{exportTo, {}}, {exportTo, {{"HYBRIDLAB_TEST_WRITE_LIMIT", "0"}}}};
    runs[0].args.push_back("/proc/hybridlab-export.pov");  // no file can be made there, by root either
    runs[1].args.push_back((dir / "x.pov").string());       // a full disk
    const std::vector<CliResult> results = runHybridlabAll(runs);
    EXPECT_EQ(results[0].exitStatus, 3) << results[0].err;
    EXPECT_CONTAINS(results[0].err, "hybridlab: error: /proc/hybridlab-export.pov: cannot write (");
    EXPECT_EQ(results[1].exitStatus, 3) << results[1].err;
    EXPECT_CONTAINS(results[1].err, "hybridlab: error: " + (dir / "x.pov").string() + ": cannot write (No space left on device)");
    for (const CliResult& r : results) EXPECT_EQ(r.err.find(".tmp-"), std::string::npos) << r.err;
    EXPECT_EQ(test::fileTree(dir.path()), std::vector<std::string>{}) << "nothing left behind";
}

}  // namespace
}  // namespace hybridlab
