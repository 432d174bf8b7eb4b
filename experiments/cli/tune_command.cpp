// `hybridlab tune`: the fastest setting of a scene's techniques that reaches a quality target,
// searched by experiments/tune/tune.py, which renders and times each stage with this program's
// `run` (experiments/tune/search.py says how it searches).
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "experiments/cli/commands.h"
#include "experiments/cli/python_script.h"

namespace hybridlab::cli {

namespace fs = std::filesystem;

void addTuneCommand(CLI::App& app) {
    struct Options {
        std::string scene, target, region = "whole", size = "320x180", cache, out;
        std::vector<std::string> techniques;
        double budgetSeconds = 120.0;
        bool resume = false;
    };
    auto o = std::make_shared<Options>();
    auto* cmd = app.add_subcommand("tune", "Find the fastest setting of a scene's techniques that reaches a quality target (and the front "
                                           "of time against quality), without a full sweep; writes a result set and the config that reproduces it");
    cmd->add_option("--scene", o->scene, "A scenes/ name or a scene file (its camera)")->required();
    cmd->add_option("--target", o->target, "METRIC>=VALUE or METRIC<=VALUE: \"ssim>=0.97\", \"flip<=0.05\"")->required();
    cmd->add_option("--region", o->region, "whole (the image) or refl (its reflective and refractive pixels)")->capture_default_str();
    cmd->add_option("--technique", o->techniques, "A technique to search (repeatable; default: every technique that declares knobs)");
    cmd->add_option("--size", o->size, "WIDTHxHEIGHT")->capture_default_str();
    cmd->add_option("--budget-s", o->budgetSeconds, "Seconds the stages' renders may take in all")->capture_default_str();
    cmd->add_option("--cache", o->cache, "Reference cache folder (default: $HYBRIDLAB_CACHE or ~/.cache/hybridlab)");
    cmd->add_flag("--resume", o->resume, "Continue an interrupted search in --out (the same arguments)");
    cmd->add_option("--out", o->out, "The search's folder: result/ (the result set), tune.toml, tune.json, stages/")->required();
    cmd->callback([o] {
        std::vector<std::string> args = {"--program", fs::read_symlink("/proc/self/exe").string(), "--scene", o->scene, "--target", o->target,
                                         "--region", o->region, "--size", o->size, "--budget-s", std::to_string(o->budgetSeconds), "--out", o->out};
        for (const auto& t : o->techniques) args.insert(args.end(), {"--technique", t});
        if (!o->cache.empty()) args.insert(args.end(), {"--cache", o->cache});
        if (o->resume) args.push_back("--resume");
        // The script has said what went wrong (bad input: 2, I/O: 3); its status is the program's.
        if (const int status = runSourceScript("experiments/tune/tune.py", args); status != 0) throw CommandExit{status};
    });
}

}  // namespace hybridlab::cli
