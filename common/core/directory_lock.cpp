#include "common/core/directory_lock.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <fstream>
#include <sstream>

#include "common/core/input_error.h"
#include "common/core/io_error.h"

namespace hybridlab {
namespace fs = std::filesystem;

namespace {

std::string hostName() {
    char name[256] = {};
    if (::gethostname(name, sizeof name - 1) != 0) return "unknown-host";
    return name;
}

struct LockOwner {
    long pid = 0;
    std::string host;
};

LockOwner readOwner(const fs::path& file) {
    LockOwner owner;
    std::ifstream in(file);
    in >> owner.pid >> owner.host;
    return owner;
}

// On this host and no longer running (or a file that names no process: a half-written lock).
bool isStale(const LockOwner& owner) {
    if (owner.pid <= 0) return true;
    if (owner.host != hostName()) return false;  // another machine's process: we cannot tell
    return ::kill(static_cast<pid_t>(owner.pid), 0) != 0 && errno == ESRCH;
}

}  // namespace

DirectoryLock::DirectoryLock(const fs::path& dir) : file_(dir / kFileName) {
    const std::string me = std::to_string(::getpid()) + " " + hostName() + "\n";
    // Two tries: the second after removing a stale lock.
    for (int attempt = 0; attempt < 2; ++attempt) {
        const int fd = ::open(file_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
        if (fd >= 0) {
            const bool ok = ::write(fd, me.data(), me.size()) == static_cast<ssize_t>(me.size());
            const int error = errno;
            if (::close(fd) != 0 || !ok) {
                ::unlink(file_.c_str());
                throw IoError::fromErrno(file_, "write", ok ? errno : error);
            }
            return;
        }
        if (errno != EEXIST) throw IoError::fromErrno(file_, "create", errno);
        const LockOwner owner = readOwner(file_);
        if (attempt == 0 && isStale(owner)) {
            ::unlink(file_.c_str());
            tookOver_ = true;
            continue;
        }
        throw InputError(dir.string() + ": in use by process " + std::to_string(owner.pid) + " on " + owner.host + " (lock file " +
                         file_.string() + "); wait for it to finish, or delete the lock file if that process is gone");
    }
}

DirectoryLock::~DirectoryLock() { ::unlink(file_.c_str()); }

}  // namespace hybridlab
