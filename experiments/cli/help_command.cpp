// `hybridlab help [COMMAND]`: what `hybridlab --help` or `hybridlab COMMAND --help` prints.
#include <cstdio>
#include <memory>
#include <string>

#include "common/core/input_error.h"
#include "experiments/cli/commands.h"

namespace hybridlab::cli {

void addHelpCommand(CLI::App& app) {
    auto command = std::make_shared<std::string>();
    auto* cmd = app.add_subcommand("help", "Print this help, or one command's (hybridlab help COMMAND)");
    cmd->add_option("command", *command, "A command's name");
    cmd->callback([&app, cmd, command] {
        // The formatter itself: App::help() would print the help of the command running, this one.
        if (cmd->count("command") == 0) {
            std::printf("%s", app.get_formatter()->make_help(&app, app.get_name(), CLI::AppFormatMode::Normal).c_str());
            return;
        }
        for (const auto* c : app.get_subcommands({})) {
            if (c->get_name() == *command) {
                std::printf("%s", c->get_formatter()->make_help(c, app.get_name() + " " + c->get_name(), CLI::AppFormatMode::Normal).c_str());
                return;
            }
        }
        std::string known;
        for (const auto* c : app.get_subcommands({})) known += (known.empty() ? "" : ", ") + c->get_name();
        throw InputError("help: unknown command '" + *command + "' (commands: " + known + ")");
    });
}

}  // namespace hybridlab::cli
