// `hybridlab bundle --out DIR [--config FILE...]`: this program as a relocatable folder for machines
// without its packages (experiments/runner/portable_bundle.h).
#include <cstdio>
#include <filesystem>
#include <vector>

#include "common/core/cli_number_validators.h"
#include "experiments/cli/commands.h"
#include "experiments/runner/portable_bundle.h"

namespace hybridlab::cli {

namespace fs = std::filesystem;

void addBundleCommand(CLI::App& app) {
    auto out = std::make_shared<std::string>();
    auto configs = std::make_shared<std::vector<std::string>>();
    auto* cmd = app.add_subcommand("bundle",
                                   "Write a relocatable folder that runs this program where its packages are not installed: the "
                                   "program, the shared libraries it loads but the base system's, the scenes, a launcher");
    cmd->add_option("--out", *out, "Bundle folder (new, or an empty folder)")->required()->check(nonEmpty("a folder"));
    cmd->add_option("--config", *configs,
                    "Experiment config whose scenes' models and textures the bundle carries, with the config (repeatable: several experiments)");
    cmd->callback([out, configs] {
        const fs::path binary = fs::read_symlink("/proc/self/exe");
        const BundleContents c = writeBundle(binary, *out, std::vector<fs::path>(configs->begin(), configs->end()));
        std::printf("bundle in %s: %zu libraries, %.0f MB in all; run %s/hybridlab (what a node must provide: %s/README.txt)\n",
                    out->c_str(), c.libraries, static_cast<double>(c.bytes) / 1e6, out->c_str(), out->c_str());
    });
}

}  // namespace hybridlab::cli
