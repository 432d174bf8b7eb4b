#pragma once
// A technique's capability to bake what its prepare() caches on disk (layered_em's environment
// maps) ahead of rendering: a subcommand of `hybridlab` whose options and output are the
// technique's own. The program adds one for each technique of the registry that has one
// (TechniqueInfo::bakeCommand), so that it reaches techniques only through the registry.
#include <functional>
#include <string>

namespace CLI {
class App;
}

namespace hybridlab {

struct CacheBakeCommand {
    std::string name;         // the subcommand: "bake-em"
    std::string description;  // one line, for `hybridlab help`
    // Adds the command's options to `command` (a subcommand named `name`) and the callback that bakes.
    std::function<void(CLI::App& command)> define;
};

}  // namespace hybridlab
