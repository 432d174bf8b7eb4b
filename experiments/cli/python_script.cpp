#include "experiments/cli/python_script.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace hybridlab::cli {

namespace fs = std::filesystem;

std::string reportScript(const std::string& name) { return (fs::path(HYBRIDLAB_SOURCE_DIR) / "report" / name).string(); }

int runPython(const std::string& script, const std::vector<std::string>& args, std::string* output) {
    std::vector<std::string> command = {fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3", script};
    command.insert(command.end(), args.begin(), args.end());
    int pipeEnds[2] = {-1, -1};
    if (output && ::pipe(pipeEnds) != 0) throw std::runtime_error("cannot make a pipe for " + script);
    std::fflush(stdout);
    const pid_t pid = ::fork();
    if (pid < 0) throw std::runtime_error("cannot start " + command[0]);
    if (pid == 0) {
        if (output) {
            ::dup2(pipeEnds[1], STDOUT_FILENO);
            ::close(pipeEnds[0]);
            ::close(pipeEnds[1]);
        }
        std::vector<char*> argv;
        for (const auto& a : command) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        ::execvp(argv[0], argv.data());
        std::perror(command[0].c_str());
        ::_exit(127);
    }
    if (output) {
        ::close(pipeEnds[1]);
        char chunk[4096];
        for (ssize_t n; (n = ::read(pipeEnds[0], chunk, sizeof chunk)) > 0;) output->append(chunk, static_cast<std::size_t>(n));
        ::close(pipeEnds[0]);
    }
    int status = 0;
    ::waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace hybridlab::cli
