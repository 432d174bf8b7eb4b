// The bake commands of the techniques that cache per-scene work on disk (`hybridlab bake-em`), each
// the technique's own (TechniqueInfo::bakeCommand), found in the registry.
#include "experiments/cli/commands.h"
#include "techniques/technique.h"

namespace hybridlab::cli {

void addBakeCommands(CLI::App& app) {
    for (const TechniqueInfo& info : registeredTechniques()) {
        if (!info.bakeCommand) continue;
        info.bakeCommand->define(*app.add_subcommand(info.bakeCommand->name, info.bakeCommand->description));
    }
}

}  // namespace hybridlab::cli
