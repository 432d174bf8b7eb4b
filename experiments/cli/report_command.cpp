// `hybridlab report DIR [--out DIR]`: the report of a result set, drawn by report/report.py
// (matplotlib), which reads only results.json; written here first for a set whose runner was
// killed before it wrote it.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <vector>

#include "common/core/input_error.h"
#include "experiments/cli/commands.h"
#include "experiments/runner/results_store.h"

namespace hybridlab::cli {

namespace fs = std::filesystem;

namespace {

// Debian's python3 has the packages the set-up script installs (matplotlib); a python3 found
// first on the PATH (pyenv, a virtualenv) may not.
std::string python() { return fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3"; }

int runProgram(const std::vector<std::string>& args) {
    pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("cannot start " + args[0]);
    if (pid == 0) {
        std::vector<char*> argv;
        for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        execvp(argv[0], argv.data());
        std::perror(args[0].c_str());
        _exit(127);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace

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
        const fs::path script = fs::path(HYBRIDLAB_SOURCE_DIR) / "report" / "report.py";
        std::vector<std::string> args = {python(), script.string(), *dir, "--out", target};
        if (!baseline->empty()) args.insert(args.end(), {"--baseline", *baseline});
        const int status = runProgram(args);
        // report.py exits with 2 on a bad result set (an unreadable image), having said which.
        if (status == 2) throw InputError(*dir + ": not a complete result set (report/report.py's message above)");
        if (status != 0) throw std::runtime_error("report/report.py failed (exit status " + std::to_string(status) + ")");
    });
}

}  // namespace hybridlab::cli
