#include "experiments/cli/python_script.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "experiments/cli/commands.h"

namespace hybridlab::cli {

namespace fs = std::filesystem;

namespace {

std::string python() { return fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3"; }

}  // namespace

int runReportScript(const std::string& script, const std::vector<std::string>& args, Interrupt interrupt, std::string* output) {
    return runSourceScript((fs::path("report") / script).string(), args, interrupt, output);
}

int runSourceScript(const std::string& path, const std::vector<std::string>& args, Interrupt interrupt, std::string* output) {
    const std::string script = fs::path(path).filename().string();
    std::vector<std::string> command = {python(), (fs::path(HYBRIDLAB_SOURCE_DIR) / path).string()};
    command.insert(command.end(), args.begin(), args.end());
    int pipeEnds[2] = {-1, -1};
    if (output && pipe(pipeEnds) != 0) throw std::runtime_error("cannot make a pipe for " + script);
    std::fflush(stdout);
    pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("cannot start " + command[0]);
    if (pid == 0) {
        if (output) {
            dup2(pipeEnds[1], STDOUT_FILENO);
            close(pipeEnds[0]);
            close(pipeEnds[1]);
        }
        std::vector<char*> argv;
        for (const auto& a : command) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        execvp(argv[0], argv.data());
        std::perror(command[0].c_str());
        _exit(127);
    }
    // Ctrl-C reaches both processes (one process group); ignored here, the script alone decides.
    auto previous = interrupt == Interrupt::ScriptOnly ? std::signal(SIGINT, SIG_IGN) : SIG_DFL;
    if (output) {
        close(pipeEnds[1]);
        char chunk[4096];
        for (ssize_t n; (n = read(pipeEnds[0], chunk, sizeof chunk)) != 0;) {
            if (n > 0) output->append(chunk, static_cast<std::size_t>(n));
            else if (errno != EINTR) break;
        }
        close(pipeEnds[0]);
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (interrupt == Interrupt::ScriptOnly) std::signal(SIGINT, previous);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

void runReportScriptSayingItsErrors(const std::string& script, const std::vector<std::string>& args, Interrupt interrupt) {
    const int status = runReportScript(script, args, interrupt);
    if (status == 2 || status == 3) throw CommandExit{status};
    if (status != 0) throw std::runtime_error("report/" + script + " failed (exit status " + std::to_string(status) + ")");
}

}  // namespace hybridlab::cli
