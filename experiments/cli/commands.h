#pragma once
// Subcommands of `hybridlab`; each adds itself to the app. Bad input is thrown as InputError and
// becomes exit status 2 in main().
#include <CLI/CLI.hpp>

namespace hybridlab::cli {

void addScenesCommand(CLI::App& app);
void addSceneInfoCommand(CLI::App& app);
void addRenderCommand(CLI::App& app);
void addTechniquesCommand(CLI::App& app);
void addBenchCommand(CLI::App& app);
void addBenchRasterCommand(CLI::App& app);
void addRunCommand(CLI::App& app);
void addReportCommand(CLI::App& app);
void addExportPovCommand(CLI::App& app);
void addCompareCommand(CLI::App& app);
// The bake commands of the techniques that have one (TechniqueInfo::bakeCommand): `bake-em`.
void addBakeCommands(CLI::App& app);
void addBundleCommand(CLI::App& app);
void addViewCommand(CLI::App& app);
void addTuneCommand(CLI::App& app);
// `hybridlab help [COMMAND]`: the program's help, or one command's; added last, so that it knows them all.
void addHelpCommand(CLI::App& app);

// A command's verdict that is neither bad input nor a failure of the program (say, a score worse
// than `compare --fail-above` allows): main() exits with `status` after the command's output.
struct CommandExit {
    int status;
};

}  // namespace hybridlab::cli
