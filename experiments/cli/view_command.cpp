// `hybridlab view RESULTS [--report DIR] [--port N]`: serves a result set and its report to a
// browser on this machine (report/serve.py: 127.0.0.1 only), printing the addresses, until
// Ctrl-C. The viewer reads the set's own images, which a page opened from the file system may not.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "common/core/input_error.h"
#include "experiments/cli/commands.h"
#include "experiments/cli/python_script.h"

namespace hybridlab::cli {

namespace fs = std::filesystem;

void addViewCommand(CLI::App& app) {
    auto dir = std::make_shared<std::string>();
    auto report = std::make_shared<std::string>();
    auto port = std::make_shared<int>(8765);
    auto* cmd = app.add_subcommand("view", "Serve a result set and its report on 127.0.0.1 for the viewer; prints the address, Ctrl-C stops");
    cmd->add_option("results", *dir, "Result folder written by `hybridlab run` or `merge`, with its report")->required();
    cmd->add_option("--report", *report, "Report folder (default: RESULTS/report)");
    cmd->add_option("--port", *port, "Port on 127.0.0.1 (0: any free one)")->check(CLI::Range(0, 65535));
    cmd->callback([dir, report, port] {
        if (!fs::is_regular_file(fs::path(*dir) / "results.json"))
            throw InputError(*dir + ": no results.json (not a result folder of `hybridlab run`)");
        const fs::path page = report->empty() ? fs::path(*dir) / "report" : fs::path(*report);
        if (!fs::is_regular_file(page / "viewer.html"))
            throw InputError(page.string() + ": no viewer.html (write the report first: hybridlab report " + *dir +
                             (report->empty() ? "" : " --out " + *report) + ")");
        std::vector<std::string> args = {*dir, "--port", std::to_string(*port)};
        if (!report->empty()) args.insert(args.end(), {"--report", *report});
        // serve.py says what is wrong on one line itself: bad input (exit status 2) or a port it
        // cannot listen on (3).
        runReportScriptSayingItsErrors("serve.py", args, Interrupt::ScriptOnly);
    });
}

}  // namespace hybridlab::cli
