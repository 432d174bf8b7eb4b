// `hybridlab report DIR [--out DIR]`: the report of a result set, drawn by report/report.py
// (matplotlib), which checks every file of the set it reads before it writes anything; results.json
// is written here first for a set whose runner was killed before it wrote it.
#include <cstdio>
#include <filesystem>
#include <vector>

#include "common/core/input_error.h"
#include "experiments/cli/commands.h"
#include "experiments/cli/python_script.h"
#include "experiments/runner/results_store.h"

namespace hybridlab::cli {

namespace fs = std::filesystem;

void addReportCommand(CLI::App& app) {
    auto dir = std::make_shared<std::string>();
    auto out = std::make_shared<std::string>();
    auto baseline = std::make_shared<std::string>();
    auto* cmd = app.add_subcommand("report", "Write the report of a result set: index.html, report.md, figures (SVG, PDF)");
    cmd->add_option("results", *dir, "Result folder written by `hybridlab run` or `merge`")->required();
    cmd->add_option("--out", *out, "Report folder (default: RESULTS/report)");
    cmd->add_option("--baseline", *baseline, "Scene whose camera path is the baseline of \"where methods fail\" (default: sponza-spheres)");
    cmd->callback([dir, out, baseline] {
        const std::string target = out->empty() ? (fs::path(*dir) / "report").string() : *out;
        std::vector<std::string> args = {*dir, "--out", target};
        if (!baseline->empty()) args.insert(args.end(), {"--baseline", *baseline});
        // report.py says what is wrong on one line itself: a malformed file of the set (exit status
        // 2, nothing written) or a report folder that cannot be written (3).
        const auto report = [](const std::vector<std::string>& a) { runReportScriptSayingItsErrors("report.py", a); };
        // A killed runner's records are checked before results.json is written from them.
        if (!fs::exists(fs::path(*dir) / "results.json") && fs::exists(fs::path(*dir) / "experiment.json")) {
            std::vector<std::string> check = args;
            check.push_back("--check-only");
            report(check);
        }
        if (const auto written = writeMissingResults(*dir))
            std::printf("%s: its runner stopped before writing results.json and results.csv; wrote them from its %zu records\n",
                        dir->c_str(), *written);
        if (!fs::exists(fs::path(*dir) / "results.json")) throw InputError(*dir + ": no results.json (not a result folder of `hybridlab run`)");
        report(args);
    });
}

}  // namespace hybridlab::cli
