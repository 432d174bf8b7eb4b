// `hybridlab report DIR [--out DIR]`: the report of a result set, drawn by report/report.py
// (matplotlib), which reads only results.json; written here first for a set whose runner was
// killed before it wrote it.
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
        if (const auto written = writeMissingResults(*dir))
            std::printf("%s: its runner stopped before writing results.json and results.csv; wrote them from its %zu records\n",
                        dir->c_str(), *written);
        if (!fs::exists(fs::path(*dir) / "results.json")) throw InputError(*dir + ": no results.json (not a result folder of `hybridlab run`)");
        const std::string target = out->empty() ? (fs::path(*dir) / "report").string() : *out;
        std::vector<std::string> args = {*dir, "--out", target};
        if (!baseline->empty()) args.insert(args.end(), {"--baseline", *baseline});
        const int status = runReportScript("report.py", args);
        // report.py exits with 2 on a bad result set (an unreadable image), having said which.
        if (status == 2) throw InputError(*dir + ": not a complete result set (report/report.py's message above)");
        if (status != 0) throw std::runtime_error("report/report.py failed (exit status " + std::to_string(status) + ")");
    });
}

}  // namespace hybridlab::cli
