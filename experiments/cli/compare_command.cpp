// `hybridlab compare TEST... REFERENCE`: every metric of one or more test images against one reference
// (SSIM, RMSE, PSNR, FLIP, HDR-FLIP), over the whole image and over an optional mask, and the error
// maps, every difference map on one scale; --fail-above bounds a score for scripts and CI.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <iomanip>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "common/core/cli_number_validators.h"
#include "common/core/input_error.h"
#include "common/core/wall_clock.h"
#include "common/image/image_io.h"
#include "common/image/non_finite_pixels.h"
#include "experiments/cli/commands.h"
#include "metrics/metrics.h"
#include "metrics/report_files.h"

namespace hybridlab::cli {

namespace fs = std::filesystem;

namespace {

struct CompareOptions {
    std::vector<std::string> images;  // the tests, then the reference
    std::string mask;
    std::string out;
    bool linear = false;
    bool perChannel = false;
    double pixelsPerDegree = kDefaultPixelsPerDegree;
    bool timing = false;
    bool json = false;
    double range = 0.0;  // 0: the largest difference of all the tests
    std::vector<std::string> failAbove;
    bool ignoreNonFinite = false;
};

// A NaN or an infinity makes every metric NaN (and SSIM's window spreads it): such pixels are bad
// input unless --ignore-nonfinite, which blacks them out in both images (no error there) and says
// so. Returns the lines to print.
std::vector<std::string> handleNonFinite(Image& test, const std::string& testName, Image& reference, const std::string& referenceName,
                                         bool ignore) {
    std::vector<std::string> notes;
    for (const auto& [image, name] : {std::pair{&test, &testName}, std::pair{&reference, &referenceName}}) {
        const NonFinitePixels found = findNonFinite(*image);
        if (found.count == 0) continue;
        if (!ignore) {
            throw InputError(*name + ": " + found.description() + ": every metric would be NaN (pass --ignore-nonfinite to score the "
                                     "other pixels, with these black in both images)");
        }
        notes.push_back(*name + ": " + found.description() + ", ignored: black in both images");
    }
    blackOutNonFinite(test, reference);
    return notes;
}

// One test image against the reference: where it came from, what it was taken as, its scores.
struct Compared {
    std::string path;
    std::string name;    // its column and --out folder: the file name without extension
    std::string space;
    MetricReport report;
};

// A score that --fail-above bounds: its name, how to read it, and which way is worse.
struct ScoreSpec {
    const char* name;
    double (*value)(const RegionMetrics&);
    bool higherIsBetter;
};

const std::vector<ScoreSpec>& boundedScores() {
    static const std::vector<ScoreSpec> scores = {
        {"ssim", [](const RegionMetrics& m) { return m.ssim; }, true},
        {"rmse", [](const RegionMetrics& m) { return m.error.rmse; }, false},
        {"psnr", [](const RegionMetrics& m) { return m.error.psnr; }, true},
        {"flip", [](const RegionMetrics& m) { return m.flip.mean; }, false},
        {"flip_hdr", [](const RegionMetrics& m) { return m.flipHdr.mean; }, false},
    };
    return scores;
}

struct ScoreBound {
    const ScoreSpec* score;
    double limit;
};

// "METRIC=VALUE", METRIC one of boundedScores().
ScoreBound parseBound(const std::string& text) {
    std::string names;
    for (const auto& s : boundedScores()) names += (names.empty() ? "" : ", ") + std::string(s.name);
    const std::size_t eq = text.find('=');
    const std::string name = text.substr(0, eq);
    for (const auto& s : boundedScores()) {
        if (eq == std::string::npos || name != s.name) continue;
        const std::string number = text.substr(eq + 1);
        std::size_t used = 0;
        double limit = 0.0;
        try {
            limit = std::stod(number, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used == 0 || used != number.size() || !std::isfinite(limit))
            throw InputError("--fail-above " + text + ": expected a finite number after '='");
        return {&s, limit};
    }
    throw InputError("--fail-above " + text + ": expected METRIC=VALUE with METRIC one of " + names);
}

// The bounds a test breaks: "ssr_fallback: flip 0.1234 is worse than 0.1".
std::vector<std::string> brokenBounds(const Compared& c, const std::vector<ScoreBound>& bounds) {
    std::vector<std::string> broken;
    for (const ScoreBound& b : bounds) {
        const double v = b.score->value(c.report.whole);
        const bool worse = b.score->higherIsBetter ? v < b.limit : v > b.limit;
        if (!worse) continue;
        char text[256];
        std::snprintf(text, sizeof text, "%s: %s %.6g is worse than %.6g (%s)", c.name.c_str(), b.score->name, v, b.limit,
                      b.score->higherIsBetter ? "below" : "above");
        broken.push_back(text);
    }
    return broken;
}

// Every metric, a row each, a column per test (and per test its mask column).
void printTable(const std::vector<Compared>& tests) {
    const bool masked = tests.front().report.masked.has_value();
    std::vector<std::pair<std::string, const RegionMetrics*>> columns;
    for (const Compared& c : tests) {
        const bool alone = tests.size() == 1;
        columns.push_back({alone ? "whole image" : c.name, &c.report.whole});
        if (masked) columns.push_back({alone ? "mask" : c.name + " (mask)", &*c.report.masked});
    }
    std::vector<int> widths;
    for (const auto& [title, m] : columns) widths.push_back(std::max(14, static_cast<int>(title.size()) + 2));
    std::printf("%-28s", "");
    for (std::size_t i = 0; i < columns.size(); ++i) std::printf("%*s", widths[i], columns[i].first.c_str());
    std::printf("\n");
    auto row = [&](const char* name, auto value, const char* format) {
        std::printf("%-28s", name);
        for (std::size_t i = 0; i < columns.size(); ++i) {
            char cell[64];
            std::snprintf(cell, sizeof cell, format, value(*columns[i].second));
            std::printf("%*s", widths[i], cell);
        }
        std::printf("\n");
    };
    row("pixels", [](const RegionMetrics& m) { return static_cast<double>(m.pixels); }, "%.0f");
    row("SSIM", [](const RegionMetrics& m) { return m.ssim; }, "%.6f");
    row("RMSE", [](const RegionMetrics& m) { return m.error.rmse; }, "%.6f");
    row("PSNR (dB)", [](const RegionMetrics& m) { return m.error.psnr; }, "%.3f");
    row("FLIP mean", [](const RegionMetrics& m) { return m.flip.mean; }, "%.6f");
    row("FLIP weighted median", [](const RegionMetrics& m) { return m.flip.weightedMedian; }, "%.6f");
    row("FLIP weighted 1st quartile", [](const RegionMetrics& m) { return m.flip.weightedFirstQuartile; }, "%.6f");
    row("FLIP weighted 3rd quartile", [](const RegionMetrics& m) { return m.flip.weightedThirdQuartile; }, "%.6f");
    row("HDR-FLIP mean", [](const RegionMetrics& m) { return m.flipHdr.mean; }, "%.6f");
    row("HDR-FLIP weighted median", [](const RegionMetrics& m) { return m.flipHdr.weightedMedian; }, "%.6f");
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// "wall ms (cpu ms)", medians over `repeats` runs of `f`. The processor time (all threads) says
// what a metric costs when the machine is shared and wall times wander.
template <typename F>
std::string medianMilliseconds(int repeats, F&& f) {
    std::vector<double> wall, cpu;
    for (int i = 0; i < repeats; ++i) {
        const auto start = WallClock::now();
        const std::clock_t cpuStart = std::clock();
        f();
        cpu.push_back(1e3 * static_cast<double>(std::clock() - cpuStart) / CLOCKS_PER_SEC);
        wall.push_back(millisecondsSince(start));
    }
    std::ostringstream text;
    text << std::fixed << std::setprecision(2) << std::setw(9) << median(wall) << " ms  (cpu " << std::setw(8) << median(cpu) << " ms)";
    return text.str();
}

// Each metric alone, on the same inputs as the report.
void printTiming(const Image& test, const Image& reference, const MetricOptions& options) {
    constexpr int kRepeats = 5;
    const cv::Mat3f t = metricRgb(test, ValueSpace::Display), r = metricRgb(reference, ValueSpace::Display);
    std::printf("timing, median of %d (%dx%d, %d threads):\n", kRepeats, test.width(), test.height(), cv::getNumThreads());
    std::printf("  %-34s%s\n", "display conversion (both images)",
                medianMilliseconds(kRepeats, [&] {
                    metricRgb(test, ValueSpace::Display);
                    metricRgb(reference, ValueSpace::Display);
                }).c_str());
    std::printf("  %-34s%s\n", "SSIM (map and mean)",
                medianMilliseconds(kRepeats, [&] { ssimMean(ssimMap(t, r, options.ssimChannels), nullptr); }).c_str());
    std::printf("  %-34s%s\n", "RMSE and PSNR", medianMilliseconds(kRepeats, [&] { errorStats(t, r, nullptr); }).c_str());
    std::printf("  %-34s%s\n", "FLIP (map and pooling)",
                medianMilliseconds(kRepeats, [&] { flipStats(flipMap(t, r, options.pixelsPerDegree), nullptr); }).c_str());
    std::printf("  %-34s%s\n", "all metrics and maps",
                medianMilliseconds(kRepeats, [&] { computeMetrics(test, reference, options); }).c_str());
}

// Names that tell the tests apart, each also a folder name inside --out: the file names without
// extension, or, where two share one (a/t.exr and b/t.exr, or one test given twice), that name
// and the test's place on the command line (t-1, t-2).
void nameTests(std::vector<Compared>& tests) {
    std::map<std::string, int> count;
    for (Compared& c : tests) ++count[c.name = fs::path(c.path).stem().string()];
    for (std::size_t i = 0; i < tests.size(); ++i)
        if (count[tests[i].name] > 1) tests[i].name += "-" + std::to_string(i + 1);
}

void run(const CompareOptions& o) {
    // Every check of the input comes before any output.
    if (!o.out.empty() && fs::exists(o.out) && !fs::is_directory(o.out)) {
        throw InputError("--out " + o.out + ": exists and is not a folder");
    }
    std::vector<ScoreBound> bounds;
    for (const std::string& b : o.failAbove) bounds.push_back(parseBound(b));
    // PNGs are decoded to linear as their colour-space metadata says (a linear PNG, as POV-Ray
    // writes with File_Gamma=1.0, stays linear; none: sRGB), so that every input is what a
    // technique renders; the metrics then see the display values again.
    const std::string referencePath = o.images.back();
    std::string referenceSpace;
    const Image reference = readImage(referencePath, ColorEncoding::Tagged, &referenceSpace);
    std::vector<Compared> tests(o.images.size() - 1);
    std::vector<Image> testImages, references;
    std::vector<std::string> nonFiniteNotes;
    for (std::size_t i = 0; i + 1 < o.images.size(); ++i) {
        tests[i].path = o.images[i];
        testImages.push_back(readImage(tests[i].path, ColorEncoding::Tagged, &tests[i].space));
        requireSameSize(testImages.back(), tests[i].path, reference, referencePath);
        // Each test against its own copy: another test's non-finite pixels do not black out this one's.
        references.push_back(reference);
        for (std::string& note : handleNonFinite(testImages.back(), tests[i].path, references.back(), referencePath, o.ignoreNonFinite))
            if (std::find(nonFiniteNotes.begin(), nonFiniteNotes.end(), note) == nonFiniteNotes.end()) nonFiniteNotes.push_back(std::move(note));
    }
    nameTests(tests);
    std::optional<PixelMask> mask;
    if (!o.mask.empty()) {
        mask = PixelMask::fromImage(readImage(o.mask));
        requireUsableMask(*mask, o.mask, reference.width(), reference.height());
    }
    MetricOptions options;
    options.errorSpace = o.linear ? ValueSpace::Linear : ValueSpace::Display;
    options.ssimChannels = o.perChannel ? SsimChannels::PerChannel : SsimChannels::Luma;
    options.pixelsPerDegree = o.pixelsPerDegree;
    double largest = 0.0;
    for (std::size_t i = 0; i < tests.size(); ++i) {
        tests[i].report = computeMetrics(testImages[i], references[i], options, mask ? &*mask : nullptr);
        largest = std::max(largest, largestDifference(tests[i].report));
    }
    // One difference scale for every test, so that their maps compare.
    const double range = o.range > 0.0 ? o.range : largest;
    std::vector<std::string> broken;
    for (const Compared& c : tests)
        for (std::string& b : brokenBounds(c, bounds)) broken.push_back(std::move(b));

    auto sources = [&](const Compared& c) {
        return ReportSources{c.path, referencePath, mask ? std::optional<std::string>(o.mask) : std::nullopt};
    };
    auto mapsDir = [&](const Compared& c) { return tests.size() == 1 ? fs::path(o.out) : fs::path(o.out) / c.name; };
    if (!o.out.empty())
        for (const Compared& c : tests) writeReportFiles(mapsDir(c), c.report, sources(c), range);

    if (o.json) {
        nlohmann::json j = {{"reference", referencePath}, {"tests", nlohmann::json::array()}, {"difference_range", {0.0, range > 0.0 ? range : 1.0}},
                            {"failed", broken}};
        for (const Compared& c : tests) {
            nlohmann::json t = reportJson(c.report, sources(c), range);
            t["name"] = c.name;
            t["taken_as"] = c.space;
            if (!o.out.empty()) t["maps_folder"] = mapsDir(c).string();
            j["tests"].push_back(t);
        }
        std::printf("%s\n", j.dump(1).c_str());
    } else {
        for (const Compared& c : tests) std::printf("test       %s  [%s]\n", c.path.c_str(), c.space.c_str());
        std::printf("reference  %s  [%s]\n", referencePath.c_str(), referenceSpace.c_str());
        if (mask) std::printf("mask       %s\n", o.mask.c_str());
        for (const std::string& note : nonFiniteNotes) std::printf("note: %s\n", note.c_str());
        const MetricReport& first = tests.front().report;
        std::printf("%dx%d; SSIM on %s; RMSE and PSNR on %s values; FLIP at %g pixels per degree\n", first.width, first.height,
                    o.perChannel ? "R, G, B (mean)" : "luma", valueSpaceName(options.errorSpace), options.pixelsPerDegree);
        printTable(tests);
        if (o.timing) printTiming(testImages.front(), references.front(), options);
        if (!o.out.empty()) {
            std::string folders;
            for (std::size_t i = 0; i < tests.size(); ++i)
                folders += (i == 0 ? "" : i + 1 == tests.size() ? " and " : ", ") + mapsDir(tests[i]).string();
            std::printf("wrote diff.png (|T-R| on 0 to %.4g), ssim.png, flip.png, flip_hdr.png and metrics.json in %s\n", range > 0.0 ? range : 1.0,
                        folders.c_str());
        }
        for (const std::string& b : broken) std::printf("fail: %s\n", b.c_str());
    }
    if (!broken.empty()) throw CommandExit{1};
}

}  // namespace

void addCompareCommand(CLI::App& app) {
    auto o = std::make_shared<CompareOptions>();
    auto* cmd = app.add_subcommand("compare", "SSIM, RMSE, PSNR, FLIP and HDR-FLIP of one or more test images against a reference, "
                                              "and their error maps");
    cmd->add_option("images", o->images,
                    "TEST... REFERENCE: test images, then the reference of the same size (EXR, PNG, JPEG, HDR, TIFF, PFM, ...: "
                    "8/16-bit channels decoded as their colour-space metadata says)")
        ->required()
        ->expected(2, CLI::detail::expected_max_vector_size);
    cmd->add_option("--mask", o->mask, "Mask image: also report the metrics over the pixels whose R, G or B is above 0.5");
    cmd->add_option("--out", o->out,
                    "Folder for diff.png, ssim.png, flip.png, flip_hdr.png (heat maps with legends) and metrics.json; with several "
                    "tests, a folder a test inside it, named as the test's file");
    cmd->add_option("--range", o->range, "The difference map's scale, 0 to R (default: the largest difference of all the tests)")
        ->check(numberIn(1e-12, 1e12));
    cmd->add_option("--fail-above", o->failAbove,
                    "METRIC=VALUE (repeatable; METRIC ssim, rmse, psnr, flip or flip_hdr, on the whole image): exit status 1 when a "
                    "test's score is worse than VALUE (above it for rmse, flip and flip_hdr; below it for ssim and psnr)");
    cmd->add_flag("--json", o->json, "Print {reference, tests: [metrics.json's fields, name, taken_as], difference_range, failed} as JSON");
    cmd->add_flag("--linear", o->linear, "RMSE, PSNR and the difference map on linear HDR values instead of display values");
    cmd->add_flag("--channels", o->perChannel, "SSIM of R, G and B separately (averaged) instead of luma");
    cmd->add_option("--ppd", o->pixelsPerDegree, "FLIP viewing condition, pixels per degree of visual angle (FLIP's filters grow with it: a desktop display "
                    "is about 67, a phone held close 200-300)")
        ->check(numberIn(kSmallestPixelsPerDegree, kLargestPixelsPerDegree))
        ->capture_default_str();
    cmd->add_flag("--timing", o->timing, "Also time each metric on the first test (median of 5 runs)");
    cmd->add_flag("--ignore-nonfinite", o->ignoreNonFinite,
                  "Score images holding NaN or infinite pixels: those pixels are made black in both images (and named); "
                  "without it they are refused (exit status 2)");
    cmd->callback([o] { run(*o); });
}

}  // namespace hybridlab::cli
