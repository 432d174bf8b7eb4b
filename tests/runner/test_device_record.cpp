// The device record: every key in every result set's experiment.json, `hybridlab --version --json`,
// `hybridlab merge` and `run --resume` refusing to mix devices unless --allow-mixed-devices, and
// the report's charts of a mixed set naming the devices.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "experiments/runner/device_record.h"
#include "experiments/runner/experiment_runner.h"
#include "tests/support/cli_runner.h"
#include "tests/support/runner_checks.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const char* const kDeviceKeys[] = {"cpu_model",          "cpu_cores",      "vulkan_device", "vulkan_device_type",
                                   "vulkan_driver",      "vulkan_api_version", "embree_version", "tbb_threads",
                                   "lp_num_threads",     "os",             "program_version"};

json readJsonFile(const fs::path& p) { return json::parse(test::readTextFile(p)); }

TEST(DeviceRecord, HasEveryKeyAndVersionPrintsIt) {
    const json d = deviceRecord();
    for (const char* k : kDeviceKeys) EXPECT_TRUE(d.contains(k)) << k;
    EXPECT_EQ(d.size(), std::size(kDeviceKeys));
    EXPECT_GT(d.at("cpu_cores").get<int>(), 0);
    EXPECT_GT(d.at("tbb_threads").get<int>(), 0);
    EXPECT_EQ(d.at("program_version").get<std::string>().rfind("0.1.0 (git ", 0), 0u) << d;
    EXPECT_EQ(d.at("embree_version").get<std::string>().rfind("3.", 0), 0u) << d;
    EXPECT_NE(d.at("cpu_model").get<std::string>(), "unknown");

    // `hybridlab --version`: one line; `--version --json`: this machine's record as JSON.
    const test::CliResult r = test::runHybridlab({"--version"});
    ASSERT_EQ(r.exitStatus, 0) << r.err;
    EXPECT_EQ(r.out, "hybridlab " + d.at("program_version").get<std::string>() + "\n");
    const test::CliResult j = test::runHybridlab({"--version", "--json"});
    ASSERT_EQ(j.exitStatus, 0) << j.err;
    EXPECT_EQ(json::parse(j.out), d);
}

// Two tiny whitted runs: enough for a shard or a resumed run on each side.
const char* kTwoRuns = R"(
[experiment]
name = "two"
warmup_frames = 0
repeats = 1
metrics = ["ssim"]
[[scenes]]
scene = "whitted-classic"
resolutions = [[32, 18]]
[[techniques]]
name = "whitted"
params = { max_depth = [0, 1] }
)";

TEST(DeviceRecord, MergeRefusesShardsFromTwoDevicesUnlessAllowed) {
    test::TempDir dir;
    const fs::path config = dir.path() / "two.toml";
    test::writeTextFile(config, kTwoRuns);
    std::vector<fs::path> shards;
    for (int i = 0; i < 2; ++i) {
        RunnerOptions o = test::quietRunnerOptions(dir.path() / ("shard" + std::to_string(i)), dir.path() / "cache");
        o.shardIndex = i;
        o.shardCount = 2;
        ASSERT_TRUE(runExperiment(loadExperimentConfig(config), o).complete);
        shards.push_back(o.outDir);
        EXPECT_EQ(readJsonFile(o.outDir / "experiment.json").at("device"), deviceRecord());
    }
    // Shard 1 as if measured on another machine; a rebuilt program alone is the same device.
    json meta = readJsonFile(shards[1] / "experiment.json");
    const std::string here = meta["device"]["vulkan_device"];
    json other = meta;
    other["device"]["program_version"] = "0.0.9 (git 000000000000)";
    test::writeTextFile(shards[1] / "experiment.json", other.dump(1));
    test::CliResult same = test::runHybridlab({"merge", "--out", (dir.path() / "same").string(), shards[0].string(), shards[1].string()});
    EXPECT_EQ(same.exitStatus, 0) << same.err;
    EXPECT_NE(same.out.find("shard  runs  estimated cost (share)  time s (share)  folder\n"), std::string::npos) << same.out;
    other["device"]["vulkan_device"] = "Imaginary GPU 9000";
    other["device"]["vulkan_device_type"] = "discrete_gpu";
    test::writeTextFile(shards[1] / "experiment.json", other.dump(1));

    const fs::path refused = dir.path() / "refused";
    test::CliResult r = test::runHybridlab({"merge", "--out", refused.string(), shards[0].string(), shards[1].string()});
    EXPECT_EQ(r.exitStatus, 2) << r.err;
    EXPECT_NE(r.err.find(here), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("Imaginary GPU 9000"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--allow-mixed-devices"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(refused));

    const fs::path mixed = dir.path() / "mixed";
    r = test::runHybridlab({"merge", "--allow-mixed-devices", "--out", mixed.string(), shards[0].string(), shards[1].string()});
    ASSERT_EQ(r.exitStatus, 0) << r.err;
    const auto rows = test::readResults(mixed);
    ASSERT_EQ(rows.size(), 2u);
    for (const json& row : rows) {
        // Each run keeps the device of the shard that recorded it.
        const bool shard1 = fs::exists(shards[1] / "runs" / (row.at("id").get<std::string>() + ".json"));
        EXPECT_EQ(row.at("device").at("vulkan_device"), shard1 ? "Imaginary GPU 9000" : here) << row.at("id");
    }
    EXPECT_EQ(readJsonFile(mixed / "experiment.json").at("devices").size(), 2u);

    // The report labels every chart of the mixed set with both devices, each with its runs' setting.
    const fs::path report = dir.path() / "report";
    r = test::runHybridlab({"report", mixed.string(), "--out", report.string()});
    ASSERT_EQ(r.exitStatus, 0) << r.err;
    std::size_t charts = 0;
    for (const auto& f : fs::directory_iterator(report / "figures")) {
        if (f.path().extension() != ".svg") continue;
        SCOPED_TRACE(f.path().filename().string());
        ++charts;
        const std::string svg = test::readTextFile(f.path());
        EXPECT_NE(svg.find("MIXED devices"), std::string::npos);
        EXPECT_NE(svg.find("(1) " + here), std::string::npos);
        EXPECT_NE(svg.find("(2) Imaginary GPU 9000"), std::string::npos);
        EXPECT_NE(svg.find("whitted [max_depth=1]"), std::string::npos);
    }
    EXPECT_GE(charts, 3u);  // speed-accuracy, stages, rays per pixel
}

// The same machine's rule for `run --resume`: a result set whose experiment.json records another
// device is refused (exit 2, both devices named, nothing written) unless --allow-mixed-devices;
// then the runs recorded before keep that device and the new ones record this machine's.
TEST(DeviceRecord, ResumeRefusesAResultSetFromAnotherDeviceUnlessAllowed) {
    test::TempDir dir;
    const fs::path config = dir.path() / "two.toml";
    test::writeTextFile(config, kTwoRuns);
    RunnerOptions o = test::quietRunnerOptions(dir.path() / "set", dir.path() / "cache");
    o.maxRuns = 1;
    ASSERT_FALSE(runExperiment(loadExperimentConfig(config), o).complete);
    json meta = readJsonFile(o.outDir / "experiment.json");
    const std::string here = meta["device"]["vulkan_device"];
    meta["device"]["vulkan_device"] = "Imaginary GPU 9000";
    const std::string before = meta.dump(1);
    test::writeTextFile(o.outDir / "experiment.json", before);

    const std::vector<std::string> resume = {"run", config.string(), "--out", o.outDir.string(), "--cache", o.cacheDir.string(), "--resume", "--quiet"};
    test::CliResult r = test::runHybridlab(resume);
    EXPECT_EQ(r.exitStatus, 2) << r.err;
    EXPECT_NE(r.err.find("Imaginary GPU 9000"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("here: " + here), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--allow-mixed-devices"), std::string::npos) << r.err;
    EXPECT_EQ(test::readTextFile(o.outDir / "experiment.json"), before);
    EXPECT_EQ(test::readResults(o.outDir).size(), 1u);

    std::vector<std::string> allowed = resume;
    allowed.push_back("--allow-mixed-devices");
    r = test::runHybridlab(allowed);
    ASSERT_EQ(r.exitStatus, 0) << r.err;
    const auto rows = test::readResults(o.outDir);
    ASSERT_EQ(rows.size(), 2u);
    for (const json& row : rows) {
        // Run 0 was recorded before the resume.
        EXPECT_EQ(row.at("device").at("vulkan_device"), row.at("index").get<int>() == 0 ? "Imaginary GPU 9000" : here) << row.at("id");
    }
    meta = readJsonFile(o.outDir / "experiment.json");
    EXPECT_EQ(meta.at("device").at("vulkan_device"), "Imaginary GPU 9000");
    ASSERT_EQ(meta.at("devices").size(), 2u);
    EXPECT_EQ(meta.at("devices")[1], deviceRecord());

    // Resumed again here: nothing to do, no refusal (this machine is one of the set's devices).
    allowed.pop_back();
    r = test::runHybridlab(allowed);
    EXPECT_EQ(r.exitStatus, 0) << r.err;
}

}  // namespace
}  // namespace hybridlab
