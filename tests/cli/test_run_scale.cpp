// `hybridlab run --scale S` (experiments/runner/resolution_scale.h): every configured resolution at
// a fraction, rounded to even pixels, at least 16; the dry run lists the scaled sizes; the scale is
// recorded in experiment.json, printed under every paper table and in the report's header, and a
// set is resumed only at its own scale; a bad scale is refused before anything is written. And the
// paper configs and table scripts on both ray backends: walewski2019.toml and ssr.toml run every
// ray-tracing technique with `rays = "embree"` and `rays = "vulkan"`, and walewski_tables.py,
// ssr_speed_table.py and the report's speed-accuracy chart keep the two apart, each ratio within
// its backend.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/core/input_error.h"
#include "common/raster/vulkan_device.h"
#include "common/raster/vulkan_error.h"
#include "experiments/runner/resolution_scale.h"
#include "tests/support/cli_runner.h"
#include "tests/support/runner_checks.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

json readJsonFile(const fs::path& file) { return json::parse(test::readTextFile(file)); }

// What `command` wrote to standard output; fails the test when it exits with another status.
std::string outputOf(const std::string& command) {
    std::string out;
    FILE* p = popen(command.c_str(), "r");
    if (!p) {
        ADD_FAILURE() << "cannot start " << command;
        return out;
    }
    char buffer[4096];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, p)) > 0;) out.append(buffer, n);
    EXPECT_EQ(pclose(p), 0) << command;
    return out;
}

// paper_figures/`script` on a result set: its Markdown table.
std::string tableOf(const std::string& script, const fs::path& results) {
    return outputOf("/usr/bin/python3 '" + (test::sourceDir() / "paper_figures" / script).string() + "' '" + results.string() + "'");
}

// The dry-run rows of the config `name` in experiments/configs, after the header and column lines.
std::vector<std::string> dryRunRows(const std::string& name, const std::vector<std::string>& extra, const fs::path& cache) {
    std::vector<std::string> args{"run", (test::sourceDir() / "experiments" / "configs" / name).string(), "--dry-run", "--cache", cache.string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const test::CliResult r = test::runHybridlab(args);
    EXPECT_EQ(r.exitStatus, 0) << r.err;
    std::vector<std::string> rows;
    for (const std::string& l : test::textLines(r.out))
        if (!l.empty() && l.find_first_not_of(' ') != std::string::npos && std::isdigit(static_cast<unsigned char>(l[l.find_first_not_of(' ')])))
            rows.push_back(l);
    return rows;
}

TEST(RunScale, ParsesFractionsAndRefusesEverythingElse) {
    EXPECT_EQ(parseResolutionScale("0.25"), 0.25);
    EXPECT_EQ(parseResolutionScale("1"), 1.0);
    EXPECT_EQ(parseResolutionScale("1e-1"), 0.1);
    for (const char* bad : {"0", "abc", "1.5", "-0.25", "nan", "inf", "", " 0.5", "0.5x", "0x"}) {
        SCOPED_TRACE(bad);
        try {
            parseResolutionScale(bad);
            ADD_FAILURE() << "accepted";
        } catch (const InputError& e) {
            EXPECT_EQ(std::string(e.what()).rfind("--scale " + std::string(bad) + ": expected a number greater than 0 and at most 1", 0), 0u)
                << e.what();
        }
    }
}

TEST(RunScale, RoundsEverySideToEvenPixelsAtLeast16) {
    EXPECT_EQ(scaledSide(1280, 0.25), 320);
    EXPECT_EQ(scaledSide(720, 0.25), 180);
    EXPECT_EQ(scaledSide(1280, 1.0), 1280);
    EXPECT_EQ(scaledSide(720, 0.3), 216);     // 216 exactly
    EXPECT_EQ(scaledSide(1001, 0.5), 500);    // 500.5: the nearest even count
    EXPECT_EQ(scaledSide(1000, 0.003), 16);   // 3 pixels: the minimum
    EXPECT_EQ(scaledSide(12, 0.5), 12);       // a side below the minimum stays as configured
    EXPECT_EQ(scaledSide(33, 1.0), 33);       // scale 1 changes nothing, odd sides included
    ExperimentConfig c;
    c.scenes.resize(2);
    c.scenes[0].resolutions = {{1280, 720}, {640, 360}};
    c.scenes[1].resolutions = {{100, 50}};
    scaleResolutions(c, 0.25);
    EXPECT_EQ(c.resolutionScale, 0.25);
    EXPECT_EQ(c.scenes[0].resolutions, (std::vector<std::pair<int, int>>{{320, 180}, {160, 90}}));
    EXPECT_EQ(c.scenes[1].resolutions, (std::vector<std::pair<int, int>>{{26, 16}}));  // 25 -> 26, 12.5 -> 16
}

// The paper configs run every ray-tracing technique on both backends, and the dry run lists them at
// the scaled size.
TEST(RunScale, DryRunListsThePaperConfigsOnBothBackendsAtTheScaledSize) {
    test::TempDir dir;
    for (const char* name : {"walewski2019.toml", "ssr.toml"}) {
        SCOPED_TRACE(name);
        const std::vector<std::string> full = dryRunRows(name, {}, dir / "cache");
        const std::vector<std::string> rows = dryRunRows(name, {"--scale", "0.25"}, dir / "cache");
        ASSERT_EQ(rows.size(), full.size());
        ASSERT_GT(rows.size(), 0u);
        std::map<std::string, int> perBackend;
        for (std::size_t i = 0; i < rows.size(); ++i) {
            EXPECT_CONTAINS(full[i], " 1280x720 ");
            EXPECT_CONTAINS(rows[i], " 320x180 ");
            EXPECT_EQ(rows[i].find("1280x720"), std::string::npos) << rows[i];
            const bool raster = rows[i].find(" raster ") != std::string::npos;
            const bool embree = rows[i].find("rays=embree") != std::string::npos, vulkan = rows[i].find("rays=vulkan") != std::string::npos;
            EXPECT_EQ(embree || vulkan, !raster) << rows[i];  // every ray-tracing technique names its backend
            // Each setting once per backend: the row without its backend counted per backend.
            std::string setting = rows[i].substr(rows[i].find(' ', rows[i].find_first_not_of(' ')));
            const std::size_t at = setting.find("rays=");
            if (at != std::string::npos) setting.erase(at, setting.find_first_of(" \n", at) - at);
            for (const char* size : {"320x180"}) setting.erase(setting.find(size), 7);
            if (!raster) perBackend[setting] += vulkan ? 1 : 100;
        }
        for (const auto& [setting, count] : perBackend) EXPECT_EQ(count, 101) << setting;  // one embree, one vulkan
    }
    // The header says the sizes are scaled.
    const test::CliResult r = test::runHybridlab({"run", (test::sourceDir() / "experiments" / "configs" / "ssr.toml").string(), "--dry-run",
                                                  "--scale", "0.25", "--cache", (dir / "cache").string()});
    EXPECT_CONTAINS(r.out, "\nsizes at --scale 0.25 of the configured ones\n");
    EXPECT_EQ(test::fileTree(dir.path()), std::vector<std::string>{});
}

const std::string kTinyConfig =
    "[experiment]\nwarmup_frames = 0\nrepeats = 1\nkeep = []\n"
    "[[scenes]]\nscene = \"whitted-classic\"\nresolutions = [[64, 36]]\n[[scenes.views]]\n"
    "[[techniques]]\nname = \"raster\"\n[[techniques]]\nname = \"rt_only\"\n[[techniques]]\nname = \"whitted\"\n";

TEST(RunScale, BadScaleExitsTwoAndWritesNothing) {
    test::TempDir dir;
    const fs::path config = dir / "tiny.toml";
    test::writeTextFile(config, kTinyConfig);
    for (const char* bad : {"0", "abc", "1.5", "-0.25"}) {
        SCOPED_TRACE(bad);
        for (const bool dryRun : {false, true}) {
            std::vector<std::string> args{"run", config.string(), "--out", (dir / "out").string(), "--cache", (dir / "cache").string(),
                                          "--scale=" + std::string(bad)};
            if (dryRun) args.push_back("--dry-run");
            const test::CliResult r = test::runHybridlab(args);
            EXPECT_EQ(r.exitStatus, 2);
            EXPECT_CONTAINS(r.err, "--scale " + std::string(bad) + ": expected a number greater than 0 and at most 1");
            EXPECT_EQ(test::fileTree(dir.path()), std::vector<std::string>{"tiny.toml"});
        }
    }
    // Two configured sizes that the scale makes one would render every run of them twice.
    const fs::path twoSizes = dir / "two-sizes.toml";
    test::writeTextFile(twoSizes, "[[scenes]]\nscene = \"whitted-classic\"\nresolutions = [[32, 18], [33, 19]]\n[[techniques]]\nname = \"rt_only\"\n");
    const test::CliResult r = test::runHybridlab({"run", twoSizes.string(), "--out", (dir / "out").string(), "--scale", "0.5", "--dry-run"});
    EXPECT_EQ(r.exitStatus, 2);
    EXPECT_CONTAINS(r.err, "two-sizes.toml: --scale 0.5 makes 32x18 and 33x19 of scene 'whitted-classic' both 16x16");
    EXPECT_EQ(test::fileTree(dir.path()), (std::vector<std::string>{"tiny.toml", "two-sizes.toml"}));
}

// Rendered at the scaled size, recorded, resumed only at the same scale (exit 2 naming both, nothing
// written otherwise), and named under the tables and in the report.
TEST(RunScale, RecordsTheScaleAndResumesOnlyAtIt) {
    test::TempDir dir;
    const fs::path config = dir / "tiny.toml", out = dir / "out";
    test::writeTextFile(config, kTinyConfig);
    const std::vector<std::string> base{"run", config.string(), "--out", out.string(), "--cache", (dir / "cache").string(), "--quiet"};
    auto with = [&](std::vector<std::string> extra) {
        std::vector<std::string> args = base;
        args.insert(args.end(), extra.begin(), extra.end());
        return test::runHybridlab(args);
    };
    test::CliResult r = with({"--scale", "0.5", "--max-runs", "1"});
    ASSERT_EQ(r.exitStatus, 0) << r.err;
    EXPECT_CONTAINS(r.out, "--scale 0.5 --resume` continues");
    EXPECT_EQ(readJsonFile(out / "experiment.json").at("resolution_scale"), 0.5);
    const std::string meta = test::readTextFile(out / "experiment.json");
    const std::vector<std::string> before = test::fileTree(out);

    struct Refusal {
        std::vector<std::string> args;
        std::string message;
    };
    for (const Refusal& refused : {Refusal{{"--resume"}, ": was rendered at 0.5 of the configured size (--scale 0.5), not at 1 (--scale 1)"},
                                   Refusal{{"--resume", "--scale", "0.25"},
                                           ": was rendered at 0.5 of the configured size (--scale 0.5), not at 0.25 (--scale 0.25); resume it with "
                                           "--scale 0.5, or choose another --out"}}) {
        r = with(refused.args);
        EXPECT_EQ(r.exitStatus, 2);
        EXPECT_CONTAINS(r.err, out.string() + refused.message);
        EXPECT_EQ(test::readTextFile(out / "experiment.json"), meta);
        EXPECT_EQ(test::fileTree(out), before);
    }

    r = with({"--resume", "--scale", "0.5"});
    ASSERT_EQ(r.exitStatus, 0) << r.err;
    const std::vector<json> records = test::readResults(out);
    ASSERT_EQ(records.size(), 3u);
    for (const json& rec : records) {
        EXPECT_EQ(rec.at("width"), 32);
        EXPECT_EQ(rec.at("height"), 18);
    }
    EXPECT_EQ(readJsonFile(out / "experiment.json").at("resolution_scale"), 0.5);

    // Under every table of a table script, and in the report's header.
    const std::string table = tableOf("ssr_speed_table.py", out);
    std::size_t tables = 0;
    const std::vector<std::string> ls = test::textLines(table);
    for (std::size_t i = 0; i + 2 < ls.size(); ++i) {
        if (ls[i].rfind("|", 0) != 0 || ls[i + 1].rfind("|", 0) == 0) continue;
        ++tables;
        EXPECT_EQ(ls[i + 2].rfind("Measured on: ", 0), 0u) << ls[i + 2];
        EXPECT_CONTAINS(ls[i + 2], "; rendered at 0.5 of the configured size (hybridlab run --scale 0.5)");
    }
    EXPECT_GT(tables, 0u) << table;
    r = test::runHybridlab({"report", out.string(), "--out", (dir / "report").string()});
    ASSERT_EQ(r.exitStatus, 0) << r.err;
    EXPECT_CONTAINS(test::readTextFile(dir / "report" / "report.md"), "size: rendered at 0.5 of the configured size (hybridlab run --scale 0.5)");
    EXPECT_CONTAINS(test::readTextFile(dir / "report" / "index.html"), "rendered at 0.5 of the configured size");
}

// Shards merge only when rendered at one scale, which the merged set keeps.
TEST(RunScale, MergeKeepsTheScaleAndRefusesShardsOfAnother) {
    test::TempDir dir;
    const fs::path config = dir / "tiny.toml";
    test::writeTextFile(config, kTinyConfig);
    auto shard = [&](const std::string& name, const std::string& index, const std::string& scale) {
        const test::CliResult r = test::runHybridlab({"run", config.string(), "--out", (dir / name).string(), "--cache", (dir / "cache").string(),
                                                      "--quiet", "--shard", index + "/2", "--scale", scale});
        EXPECT_EQ(r.exitStatus, 0) << r.err;
    };
    shard("a0", "0", "0.5");
    shard("a1", "1", "0.5");
    shard("b1", "1", "0.25");
    test::CliResult r = test::runHybridlab({"merge", "--out", (dir / "mixed").string(), (dir / "a0").string(), (dir / "b1").string()});
    EXPECT_EQ(r.exitStatus, 2);
    EXPECT_CONTAINS(r.err, "merge: " + (dir / "b1").string() + " was rendered at 0.25 of the configured size (--scale 0.25), " + (dir / "a0").string() +
                               " at 0.5 (--scale 0.5)");
    EXPECT_FALSE(fs::exists(dir / "mixed"));
    r = test::runHybridlab({"merge", "--out", (dir / "merged").string(), (dir / "a0").string(), (dir / "a1").string()});
    ASSERT_EQ(r.exitStatus, 0) << r.err;
    EXPECT_EQ(readJsonFile(dir / "merged" / "experiment.json").at("resolution_scale"), 0.5);
    for (const json& rec : test::readResults(dir / "merged")) EXPECT_EQ(rec.at("width"), 32);
}

// The cells of the table row starting "| `name` |" in `text`, from `from` on.
std::vector<std::string> rowCells(const std::string& text, const std::string& name, std::size_t from = 0) {
    const std::size_t at = text.find("| " + name + " |", from);
    if (at == std::string::npos) return {};
    std::vector<std::string> cells;
    std::istringstream row(text.substr(at + 1, text.find('\n', at) - at - 1));
    for (std::string cell; std::getline(row, cell, '|');) cells.push_back(cell.substr(1, cell.size() - 2));
    return cells;
}

std::string ratio(double numerator, double denominator, const char* format) {
    char text[32];
    std::snprintf(text, sizeof text, format, numerator / denominator);
    return text;
}

// A result set holding both backends, rendered at 32x18 (--scale 0.5 of 64x36): walewski_tables.py
// prints Table 5 once per backend, its speed-ups over rt_only and whitted those of the same backend's
// runs; ssr_speed_table.py a row per setting and backend, each ratio to the whitted of its backend;
// the report's speed-accuracy chart a series per setting and backend.
TEST(PaperTablesByBackend, WalewskiAndSsrTablesAndTheReportKeepTheBackendsApart) {
    try {
        VulkanDevice::shared({.rayTracing = true});
    } catch (const VulkanUnavailable& e) {
        GTEST_SKIP() << "no ray-tracing Vulkan device: " << e.what();
    }
    test::TempDir dir;
    const fs::path config = dir / "backends.toml", out = dir / "out";
    test::writeTextFile(config,
                        "[experiment]\nwarmup_frames = 0\nrepeats = 1\nkeep = []\n"
                        "[[scenes]]\nscene = \"whitted-classic\"\nresolutions = [[64, 36]]\n[[scenes.views]]\n"
                        "[[techniques]]\nname = \"heuristic_rt\"\nlabel = \"heuristic\"\nparams = { budget = 500.0, rays = [\"embree\", \"vulkan\"] }\n"
                        "[[techniques]]\nname = \"heuristic_rt\"\nlabel = \"no-heuristic\"\nparams = { heuristic = false, rays = [\"embree\", \"vulkan\"] }\n"
                        "[[techniques]]\nname = \"rt_only\"\nparams = { rays = [\"embree\", \"vulkan\"] }\n"
                        "[[techniques]]\nname = \"whitted\"\nparams = { rays = [\"embree\", \"vulkan\"] }\n"
                        "[[techniques]]\nname = \"ssr_fallback\"\nparam_sets = [ { rays = [\"embree\", \"vulkan\"] } ]\n");
    test::CliResult r = test::runHybridlab({"run", config.string(), "--out", out.string(), "--cache", (dir / "cache").string(), "--quiet", "--scale", "0.5"});
    ASSERT_EQ(r.exitStatus, 0) << r.err;
    std::map<std::string, double> frameMs;  // "label rays=backend"
    for (const json& rec : test::readResults(out)) {
        EXPECT_EQ(rec.at("width"), 32);
        frameMs[rec.at("label").get<std::string>() + " " + rec.at("parameters_text").get<std::string>().substr(
                                                               rec.at("parameters_text").get<std::string>().find("rays="))] =
            rec.at("frame_ms").at("median").get<double>();
    }
    ASSERT_EQ(frameMs.size(), 10u);

    const std::string walewski = tableOf("walewski_tables.py", out);
    for (const std::string backend : {"embree", "vulkan"}) {
        SCOPED_TRACE(backend);
        const std::size_t section = walewski.find("### rays = " + backend + " (ratios to rt_only and whitted on this backend)");
        ASSERT_NE(section, std::string::npos) << walewski;
        const double heuristic = frameMs.at("heuristic rays=" + backend);
        const std::vector<std::string> overRtOnly = rowCells(walewski, "&nbsp;&nbsp;speed-up over rt_only", section);
        const std::vector<std::string> overWhitted = rowCells(walewski, "&nbsp;&nbsp;speed-up over whitted", section);
        ASSERT_EQ(overRtOnly.size(), 2u) << walewski;
        ASSERT_EQ(overWhitted.size(), 2u) << walewski;
        EXPECT_EQ(overRtOnly[1], ratio(frameMs.at("rt_only rays=" + backend), heuristic, "%.2fx"));
        EXPECT_EQ(overWhitted[1], ratio(frameMs.at("whitted rays=" + backend), heuristic, "%.2fx"));
        // The section's heuristic row has no backend left in it: the heading says it.
        const std::size_t next = walewski.find("### rays = ", section + 1);
        EXPECT_EQ(walewski.substr(section + 10, next == std::string::npos ? std::string::npos : next - section - 10).find("rays="),
                  std::string::npos);
    }
    EXPECT_LT(walewski.find("### rays = embree"), walewski.find("### rays = vulkan"));

    const std::string ssr = tableOf("ssr_speed_table.py", out);
    for (const std::string backend : {"embree", "vulkan"}) {
        SCOPED_TRACE(backend);
        const std::vector<std::string> row = rowCells(ssr, "whitted-classic | 32x18 | rays=" + backend);
        ASSERT_GE(row.size(), 6u) << ssr;
        char whittedMs[32];
        std::snprintf(whittedMs, sizeof whittedMs, "%.1f", frameMs.at("whitted rays=" + backend));
        EXPECT_EQ(row[3], whittedMs);
        EXPECT_EQ(row[5], ratio(frameMs.at("whitted rays=" + backend), frameMs.at("ssr_fallback rays=" + backend), "%.2f"));
    }
    EXPECT_CONTAINS(ssr, "; rendered at 0.5 of the configured size (hybridlab run --scale 0.5)");

    r = test::runHybridlab({"report", out.string(), "--out", (dir / "report").string()});
    ASSERT_EQ(r.exitStatus, 0) << r.err;
    std::size_t charts = 0;
    for (const auto& f : fs::directory_iterator(dir / "report" / "figures")) {
        // The wall clock's chart (the CPU's and the device's, speed-accuracy-cpu-* and -device-*, beside it).
        const std::string name = f.path().filename().string();
        if (name.rfind("speed-accuracy", 0) != 0 || f.path().extension() != ".svg" || name.rfind("speed-accuracy-cpu-", 0) == 0 ||
            name.rfind("speed-accuracy-device-", 0) == 0)
            continue;
        ++charts;
        const std::string svg = test::readTextFile(f.path());
        for (const char* series : {"rt_only [rays=embree]", "rt_only [rays=vulkan]", "ssr_fallback [rays=embree]", "ssr_fallback [rays=vulkan]",
                                   "whitted [rays=vulkan]", "heuristic [budget=500 rays=embree]", "heuristic [budget=500 rays=vulkan]"})
            EXPECT_CONTAINS(svg, series);
    }
    EXPECT_EQ(charts, 1u);
}

}  // namespace
}  // namespace hybridlab
