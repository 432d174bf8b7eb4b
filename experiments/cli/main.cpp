// hybridlab: render, compare and time hybrid rasterisation + ray-tracing techniques.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "common/core/input_error.h"
#include "common/core/io_error.h"
#include "common/core/program_version.h"
#include "common/raster/vulkan_error.h"
#include "experiments/cli/commands.h"
#include "experiments/runner/device_record.h"

namespace {

// One message, one line: a reason that spans lines (a parser's) is joined with "; ".
void printError(const char* kind, std::string message) {
    while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
    for (std::size_t at = message.find('\n'); at != std::string::npos; at = message.find('\n', at)) message.replace(at, 1, "; ");
    std::fprintf(stderr, "hybridlab: %s: %s\n", kind, message.c_str());
}

bool isCommand(CLI::App& app, const std::string& name) {
    for (const auto* c : app.get_subcommands({}))
        if (c->get_name() == name) return true;
    return false;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"hybridlab: a testbed comparing hybrid rasterization + ray-tracing reflection and refraction techniques"};
    app.require_subcommand(1);
    hybridlab::cli::addScenesCommand(app);
    hybridlab::cli::addSceneInfoCommand(app);
    hybridlab::cli::addRenderCommand(app);
    hybridlab::cli::addTechniquesCommand(app);
    hybridlab::cli::addBenchCommand(app);
    hybridlab::cli::addBenchRasterCommand(app);
    hybridlab::cli::addRunCommand(app);
    hybridlab::cli::addReportCommand(app);
    hybridlab::cli::addExportPovCommand(app);
    hybridlab::cli::addCompareCommand(app);
    hybridlab::cli::addBakeCommands(app);
    hybridlab::cli::addBundleCommand(app);
    hybridlab::cli::addViewCommand(app);
    hybridlab::cli::addTuneCommand(app);
    app.add_flag("--version")->description("Print the program version on one line, then exit; `--version --json`: this machine's device record "
                                           "as JSON, as result sets store it");
    const std::vector<std::string> arguments(argv + 1, argv + argc);
    if (arguments == std::vector<std::string>{"--version"}) {
        std::printf("hybridlab %s\n", hybridlab::programVersion().c_str());
        return 0;
    }
    if (arguments == std::vector<std::string>{"--version", "--json"} || arguments == std::vector<std::string>{"--json", "--version"}) {
        std::printf("%s\n", hybridlab::deviceRecord().dump(1).c_str());
        return 0;
    }
    hybridlab::cli::addHelpCommand(app);
    // CLI11 would only say "a subcommand is required" for a misspelt one: name it.
    if (argc > 1 && argv[1][0] != '-' && !isCommand(app, argv[1])) {
        std::string known;
        for (const auto* c : app.get_subcommands({})) known += (known.empty() ? "" : ", ") + c->get_name();
        printError("error", "unknown command '" + std::string(argv[1]) + "' (commands: " + known + "; hybridlab --help for usage)");
        return 2;
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const hybridlab::cli::CommandExit& e) {
        return e.status;
    } catch (const CLI::ParseError& e) {
        // Bad arguments are bad input: one message, exit status 2.
        printError("error", std::string(e.what()) + " (hybridlab --help for usage)");
        return 2;
    } catch (const hybridlab::InputError& e) {
        printError("error", e.what());
        return 2;
    } catch (const hybridlab::IoError& e) {
        // A file that could not be written or read: a full disk, a missing permission (exit 3).
        printError("error", e.what());
        return 3;
    } catch (const std::filesystem::filesystem_error& e) {
        // A path the file system refuses where no reader foresaw it (a name too long, a link
        // loop): still the machine's answer about a file, exit 3, with the path and the reason.
        std::string paths = e.path1().string();
        if (!e.path2().empty()) paths += ", " + e.path2().string();
        printError("error", (paths.empty() ? std::string("a file") : paths) + ": " + e.code().message());
        return 3;
    } catch (const hybridlab::VulkanError& e) {
        // No usable Vulkan device, a missing format, out of memory: the machine, not the program.
        printError("error", e.what());
        return 1;
    } catch (const std::exception& e) {
        printError("internal error", e.what());
        return 1;
    }
    return 0;
}
