// The results store: a finished run writes its record alone; results.json and results.csv are
// written when the records are final, by the runner or by a reader of a killed runner's set. What a
// run costs to record as the set grows is timed by a benchmark, not a test (the timings are the
// machine's): run it with
//   build/hybridlab_tests --gtest_also_run_disabled_tests --gtest_filter='ResultsStoreBenchmark.*'
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <limits>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/core/directory_lock.h"
#include "common/core/input_error.h"
#include "experiments/runner/experiment_runner.h"
#include "experiments/runner/results_store.h"
#include "tests/support/runner_checks.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::TempDir;

// One real run's record, the template of the synthetic ones.
RunRecord oneRealRecord(const TempDir& dir) {
    const fs::path config = dir / "one.toml";
    test::writeTextFile(config, R"(
[experiment]
name = "one"
warmup_frames = 0
repeats = 1
[[scenes]]
scene = "whitted-classic"
resolutions = [[48, 27]]
[[techniques]]
name = "whitted"
)");
    EXPECT_TRUE(runExperiment(loadExperimentConfig(config), test::quietRunnerOptions(dir / "one", dir / "cache")).complete);
    return ResultsStore(dir / "one").loadRecords().at(0);
}

double medianOf(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

TEST(ResultsStore, RecordingARunWritesItsRecordAloneAndAReaderWritesTheResultsOfAKilledSet) {
    TempDir dir;
    const RunRecord model = oneRealRecord(dir);
    const ResultsStore store(dir / "one");
    ASSERT_TRUE(store.hasResults());  // written when the runner stopped
    EXPECT_EQ(writeMissingResults(store.dir()), std::nullopt);
    // A runner that adds a record removes results.json first and writes it when it stops; killed
    // in between, it leaves the records alone.
    store.removeResults();
    EXPECT_FALSE(fs::exists(store.dir() / "results.json"));
    EXPECT_FALSE(fs::exists(store.dir() / "results.csv"));
    RunRecord second = model;
    second.index = 1;
    second.id = "second";
    store.recordRun(second);
    EXPECT_FALSE(store.hasResults());
    {
        // While a runner holds the folder, a reader writes nothing there.
        const DirectoryLock runner(store.dir());
        EXPECT_THROW(writeMissingResults(store.dir()), InputError);
        EXPECT_FALSE(store.hasResults());
    }
    EXPECT_EQ(writeMissingResults(store.dir()), std::optional<std::size_t>(2));
    const auto rows = test::readResults(store.dir());
    ASSERT_EQ(rows.size(), 2u);
    EXPECT_EQ(rows[0].at("id"), model.id);
    EXPECT_EQ(rows[1].at("id"), "second");
    const std::string csv = test::readTextFile(store.dir() / "results.csv");
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 3);
    EXPECT_FALSE(fs::exists(store.dir() / DirectoryLock::kFileName));
    EXPECT_EQ(writeMissingResults(dir / "nothing-here"), std::nullopt);
}

// Numbers the runner cannot have written, each refused as `refusal` says (the message of reading
// the record with one change): sizes and frames outside what it renders (a 2^63 is not the 0 an
// int would wrap it to), indices past what the report reads exactly, negative or infinite times, a
// scene time outside --time's range, a parameter past 2^53.
void expectNumbersTheRunnerCannotHaveWrittenRefused(const std::function<std::string(const std::function<void(json&)>&)>& refusal) {
    EXPECT_EQ(refusal([](json& j) { j["width"] = -5; }), "results record $.width: expected an integer in [1, 16384], got -5");
    EXPECT_EQ(refusal([](json& j) { j["height"] = 0; }), "results record $.height: expected an integer in [1, 16384], got 0");
    EXPECT_EQ(refusal([](json& j) { j["width"] = 16385; }), "results record $.width: expected an integer in [1, 16384], got 16385");
    EXPECT_EQ(refusal([](json& j) { j["frame"] = 1ULL << 63; }),
              "results record $.frame: expected an integer in [-1, 10000000], got 9223372036854775808");
    EXPECT_EQ(refusal([](json& j) { j["frame"] = -2; }), "results record $.frame: expected an integer in [-1, 10000000], got -2");
    EXPECT_EQ(refusal([](json& j) { j["index"] = 1ULL << 60; }),
              "results record $.index: expected an integer in [0, 9007199254740992], got 1152921504606846976");
    EXPECT_EQ(refusal([](json& j) { j["frame_ms"]["median"] = -5.0; }), "results record $.frame_ms.median: expected a number in [0, inf], got -5.0");
    EXPECT_EQ(refusal([](json& j) { j["stages"]["trace"]["max"] = std::numeric_limits<double>::infinity(); }),
              "results record $.stages.trace.max: expected a finite number in [0, inf], got inf");
    EXPECT_EQ(refusal([](json& j) { j["timing"]["frame_ms_rounds"][0] = -1.0; }),
              "results record $.timing.frame_ms_rounds[0]: expected a number in [0, inf], got -1.0");
    EXPECT_EQ(refusal([](json& j) { j["time"] = 1e300; }), "results record $.time: expected a number in [-1e+06, 1e+06], got 1e+300");
    EXPECT_EQ(refusal([](json& j) { j["parameters"]["max_depth"] = 1ULL << 63; }),  // not the negative a long long would wrap it to
              "results record $.parameters.max_depth: expected an integer in [-9007199254740992, 9007199254740992], got 9223372036854775808");
}

// The record's one writer and its reader (run_record.h): a real run's file is toJson of the record
// read back, byte for byte; every optional part (error maps' absence, debug images, device,
// temporal errors) survives the round trip; anything else in a record is refused by name.
TEST(ResultsStore, RecordsRoundTripThroughTheirOneWriter) {
    TempDir dir;
    const RunRecord real = oneRealRecord(dir);
    const ResultsStore store(dir / "one");
    EXPECT_EQ(test::readTextFile(store.runsDir() / (real.id + ".json")), toJson(real).dump(1) + "\n");
    EXPECT_EQ(real.scene, "whitted-classic");
    EXPECT_EQ(real.width, 48);
    EXPECT_EQ(real.frame, -1);
    EXPECT_EQ(real.view, "camera");
    EXPECT_GT(real.sceneStats.triangles, 0u);
    EXPECT_GT(real.counters.at("rays_total"), 0.0);
    EXPECT_TRUE(real.runSeconds.has_value());
    EXPECT_FALSE(real.device.has_value());
    EXPECT_FALSE(real.temporalError.has_value());

    RunRecord full = real;
    full.images.maps.reset();
    full.images.debug = {{"source", "images/x.source.png"}, {"confidence", "images/x.confidence.png"}};
    full.device = json{{"vulkan_device", "Imaginary GPU 9000"}, {"cpu_cores", 2}};
    full.temporalError = 0.125;
    full.temporalErrorMasked = 0.5;
    full.temporalPreviousFrame = 3;
    full.parameters = {{"flag", true}, {"count", 7LL}, {"scale", 0.25}, {"mode", std::string("linear")}};
    const json written = toJson(full);
    EXPECT_TRUE(written.at("images").at("maps").is_null());
    EXPECT_EQ(written.at("images").at("debug").size(), 2u);
    EXPECT_EQ(written.at("temporal_previous_frame"), 3);
    EXPECT_EQ(written.at("parameters").at("count"), 7);
    EXPECT_TRUE(written.at("parameters").at("count").is_number_integer());
    EXPECT_EQ(written.at("parameters").at("scale"), 0.25);
    EXPECT_EQ(toJson(fromJson(written)).dump(1), written.dump(1));
    EXPECT_EQ(toJson(fromJson(json::parse(written.dump()))).dump(1), written.dump(1));

    const auto refusal = [&](const std::function<void(json&)>& change) {
        json broken = written;
        change(broken);
        try {
            fromJson(broken);
        } catch (const std::runtime_error& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    EXPECT_EQ(refusal([](json& j) { j["colour"] = 1; }), "results record $: unexpected 'colour'");
    EXPECT_EQ(refusal([](json& j) { j.erase("id"); }), "results record $: missing 'id'");
    EXPECT_EQ(refusal([](json& j) { j["width"] = "48"; }), "results record $.width: expected an integer");
    EXPECT_EQ(refusal([](json& j) { j["reference"]["extra"] = 0; }), "results record $.reference: unexpected 'extra'");
    EXPECT_EQ(refusal([](json& j) { j["stages"]["trace"].erase("median"); }), "results record $.stages.trace: missing 'median'");
    EXPECT_EQ(refusal([](json& j) { j["counters"]["rays_total"] = "many"; }), "results record $.counters.rays_total: expected a number");
    expectNumbersTheRunnerCannotHaveWrittenRefused(refusal);

    // A record file the store cannot read names itself.
    test::writeTextFile(store.runsDir() / "broken.json", R"({"index": 1})");
    try {
        store.loadRecords();
        ADD_FAILURE() << "a broken record was read";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("broken.json: results record $: missing 'id'"), std::string::npos) << e.what();
    }
    fs::remove(store.runsDir() / "broken.json");
    // One file a run, named by the run's id, in a folder runs/: a record copied under another name,
    // or renamed with its id, is a second record of its run; both files are named.
    const auto loadRefusal = [&] {
        try {
            store.loadRecords();
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    const fs::path own = store.runsDir() / (real.id + ".json");
    json copy = toJson(real);
    test::writeTextFile(store.runsDir() / "copy.json", copy.dump());
    EXPECT_EQ(loadRefusal(), (store.runsDir() / "copy.json").string() + ": holds the record of run '" + real.id +
                                 "', expected the run its name says, 'copy' (" + own.string() + " holds that run's record too)");
    copy["id"] = "copy";
    test::writeTextFile(store.runsDir() / "copy.json", copy.dump());
    EXPECT_EQ(loadRefusal(), (store.runsDir() / "copy.json").string() + ": records run 0 of the plan, as " + own.string() +
                                 " does; expected one record a run");
    fs::remove_all(store.runsDir());
    test::writeTextFile(store.runsDir(), "not a folder");
    EXPECT_EQ(loadRefusal(), store.runsDir().string() + ": is not a folder, expected the folder of the set's records (runs/<id>.json)");
}

TEST(ResultsStoreBenchmark, DISABLED_RecordingTheThousandthRunCostsAsMuchAsTheTenth) {
    TempDir dir;
    const RunRecord model = oneRealRecord(dir);
    const ResultsStore store(dir / "set");
    store.createLayout();
    constexpr int kRuns = 1000;
    std::vector<double> ms;
    for (int i = 0; i < kRuns; ++i) {
        RunRecord record = model;
        record.index = static_cast<std::size_t>(i);
        record.id = model.id + "-" + std::to_string(i);
        const auto start = std::chrono::steady_clock::now();
        store.recordRun(record);
        ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
    // Medians over 11 neighbouring runs: the 5th to the 15th, and the 990th to the 1,000th.
    const double tenth = medianOf({ms.begin() + 4, ms.begin() + 15});
    const double thousandth = medianOf({ms.end() - 11, ms.end()});
    // And once, when the runner stops: results.json and results.csv of every record.
    const auto start = std::chrono::steady_clock::now();
    store.writeResults(store.loadRecords());
    const double results = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::printf("record of %zu bytes; recording the 10th run: %.3f ms, the 1000th: %.3f ms (median of 11 around each), ratio %.2f; "
                "results.json and results.csv of the 1000 records, once: %.1f ms\n",
                toJson(model).dump(1).size(), tenth, thousandth, thousandth / tenth, results);
    EXPECT_EQ(test::readResults(store.dir()).size(), static_cast<std::size_t>(kRuns));
}

}  // namespace
}  // namespace hybridlab
