// `hybridlab compare TEST REFERENCE`: every metric of a test image against its reference (SSIM,
// RMSE, PSNR, FLIP), over the whole image and over an optional mask, and the error maps.
#include <algorithm>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <iomanip>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

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
    std::string test;
    std::string reference;
    std::string mask;
    std::string out;
    bool linear = false;
    bool perChannel = false;
    double pixelsPerDegree = kDefaultPixelsPerDegree;
    bool timing = false;
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

void printReport(const MetricReport& r) {
    const bool masked = r.masked.has_value();
    auto row = [&](const char* name, auto value, const char* format) {
        std::printf("%-28s", name);
        std::printf(format, value(r.whole));
        if (masked) std::printf(format, value(*r.masked));
        std::printf("\n");
    };
    std::printf("%-28s%14s%s\n", "", "whole image", masked ? "          mask" : "");
    row("pixels", [](const RegionMetrics& m) { return static_cast<double>(m.pixels); }, "%14.0f");
    row("SSIM", [](const RegionMetrics& m) { return m.ssim; }, "%14.6f");
    row("RMSE", [](const RegionMetrics& m) { return m.error.rmse; }, "%14.6f");
    row("PSNR (dB)", [](const RegionMetrics& m) { return m.error.psnr; }, "%14.3f");
    row("FLIP mean", [](const RegionMetrics& m) { return m.flip.mean; }, "%14.6f");
    row("FLIP weighted median", [](const RegionMetrics& m) { return m.flip.weightedMedian; }, "%14.6f");
    row("FLIP weighted 1st quartile", [](const RegionMetrics& m) { return m.flip.weightedFirstQuartile; }, "%14.6f");
    row("FLIP weighted 3rd quartile", [](const RegionMetrics& m) { return m.flip.weightedThirdQuartile; }, "%14.6f");
    row("HDR-FLIP mean", [](const RegionMetrics& m) { return m.flipHdr.mean; }, "%14.6f");
    row("HDR-FLIP weighted median", [](const RegionMetrics& m) { return m.flipHdr.weightedMedian; }, "%14.6f");
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

void run(const CompareOptions& o) {
    // Every check of the input comes before any output.
    if (!o.out.empty() && fs::exists(o.out) && !fs::is_directory(o.out)) {
        throw InputError("--out " + o.out + ": exists and is not a folder");
    }
    // PNGs are decoded to linear as their colour-space metadata says (a linear PNG, as POV-Ray
    // writes with File_Gamma=1.0, stays linear; none: sRGB), so that every input is what a
    // technique renders; the metrics then see the display values again.
    std::string testSpace, referenceSpace;
    Image test = readImage(o.test, ColorEncoding::Tagged, &testSpace);
    Image reference = readImage(o.reference, ColorEncoding::Tagged, &referenceSpace);
    requireSameSize(test, o.test, reference, o.reference);
    const std::vector<std::string> nonFiniteNotes = handleNonFinite(test, o.test, reference, o.reference, o.ignoreNonFinite);
    std::optional<PixelMask> mask;
    if (!o.mask.empty()) {
        mask = PixelMask::fromImage(readImage(o.mask));
        requireUsableMask(*mask, o.mask, test.width(), test.height());
    }
    MetricOptions options;
    options.errorSpace = o.linear ? ValueSpace::Linear : ValueSpace::Display;
    options.ssimChannels = o.perChannel ? SsimChannels::PerChannel : SsimChannels::Luma;
    options.pixelsPerDegree = o.pixelsPerDegree;
    const MetricReport report = computeMetrics(test, reference, options, mask ? &*mask : nullptr);

    std::printf("test       %s  [%s]\nreference  %s  [%s]\n", o.test.c_str(), testSpace.c_str(), o.reference.c_str(),
                referenceSpace.c_str());
    if (mask) std::printf("mask       %s\n", o.mask.c_str());
    for (const std::string& note : nonFiniteNotes) std::printf("note: %s\n", note.c_str());
    std::printf("%dx%d; SSIM on %s; RMSE and PSNR on %s values; FLIP at %g pixels per degree\n", report.width, report.height,
                o.perChannel ? "R, G, B (mean)" : "luma", valueSpaceName(options.errorSpace), options.pixelsPerDegree);
    printReport(report);
    if (o.timing) printTiming(test, reference, options);
    if (!o.out.empty()) {
        writeReportFiles(o.out, report, {o.test, o.reference, mask ? std::optional<std::string>(o.mask) : std::nullopt});
        std::printf("wrote diff.png, ssim.png, flip.png and metrics.json in %s\n", o.out.c_str());
    }
}

}  // namespace

void addCompareCommand(CLI::App& app) {
    auto o = std::make_shared<CompareOptions>();
    auto* cmd = app.add_subcommand("compare", "SSIM, RMSE, PSNR and FLIP of a test image against a reference, and the error maps");
    cmd->add_option("test", o->test, "Test image (.exr linear, or .png display sRGB)")->required();
    cmd->add_option("reference", o->reference, "Reference image of the same size")->required();
    cmd->add_option("--mask", o->mask, "Mask image: also report the metrics over the pixels whose R, G or B is above 0.5");
    cmd->add_option("--out", o->out, "Folder for diff.png, ssim.png, flip.png (heat maps with legends) and metrics.json");
    cmd->add_flag("--linear", o->linear, "RMSE, PSNR and the difference map on linear HDR values instead of display values");
    cmd->add_flag("--channels", o->perChannel, "SSIM of R, G and B separately (averaged) instead of luma");
    cmd->add_option("--ppd", o->pixelsPerDegree, "FLIP viewing condition, pixels per degree of visual angle")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    cmd->add_flag("--timing", o->timing, "Also time each metric (median of 5 runs)");
    cmd->add_flag("--ignore-nonfinite", o->ignoreNonFinite,
                  "Score images holding NaN or infinite pixels: those pixels are made black in both images (and named); "
                  "without it they are refused (exit status 2)");
    cmd->callback([o] { run(*o); });
}

}  // namespace hybridlab::cli
