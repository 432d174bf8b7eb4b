#include "common/core/directory_lock.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <ctime>
#include <fstream>
#include <optional>

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

std::string utcNow() {
    const std::time_t now = std::time(nullptr);
    std::tm t{};
    ::gmtime_r(&now, &t);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &t);
    return text;
}

// The lock file's one line: who holds the folder.
struct LockHolder {
    long pid = 0;
    std::string host;
    std::string since;  // UTC; empty in a lock written before the time was recorded

    bool operator==(const LockHolder&) const = default;
    std::string line() const { return std::to_string(pid) + " " + host + " " + since + "\n"; }
    std::string description() const {
        return "process " + std::to_string(pid) + " on " + host + (since.empty() ? "" : " since " + since);
    }
};

// Nothing when the file is gone (its holder finished in the meantime).
std::optional<LockHolder> readHolder(const fs::path& file) {
    std::ifstream in(file);
    if (!in) return std::nullopt;
    LockHolder holder;
    in >> holder.pid >> holder.host >> holder.since;
    return holder;
}

// On this host and no longer running (or a file that names no process).
bool isStale(const LockHolder& holder) {
    if (holder.pid <= 0) return true;
    if (holder.host != hostName()) return false;  // another machine's process: we cannot tell
    return ::kill(static_cast<pid_t>(holder.pid), 0) != 0 && errno == ESRCH;
}

// Writes `holder`'s line whole under a name of this process's own beside the lock (a ".tmp-PID-"
// name, which removeStaleTemporaries collects if the process dies before removing it).
fs::path writeCandidate(const fs::path& file, const LockHolder& holder) {
    const fs::path candidate = file.parent_path() / (".tmp-" + std::to_string(holder.pid) + "-" + holder.host + file.filename().string());
    const int fd = ::open(candidate.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) throw IoError::fromErrno(file, "create", errno);
    const std::string line = holder.line();
    const bool ok = ::write(fd, line.data(), line.size()) == static_cast<ssize_t>(line.size());
    const int error = errno;
    if (::close(fd) != 0 || !ok) {
        ::unlink(candidate.c_str());
        throw IoError::fromErrno(file, "write", ok ? errno : error);
    }
    return candidate;
}

// Puts the candidate in place as the lock: true when it now is the lock, false when a lock exists.
// Where the file system has no hard links, an exclusive create of the lock holding the line.
bool placeLock(const fs::path& candidate, const fs::path& file, const LockHolder& holder) {
    if (::link(candidate.c_str(), file.c_str()) == 0) return true;
    const int error = errno;
    if (error == EEXIST) return false;
    // NFS may report a link that was made as failed: the candidate's link count says.
    struct stat st {};
    if (::stat(candidate.c_str(), &st) == 0 && st.st_nlink == 2) return true;
    if (error != EPERM && error != ENOTSUP && error != EOPNOTSUPP) throw IoError::fromErrno(file, "create", error);
    const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0) {
        if (errno == EEXIST) return false;
        throw IoError::fromErrno(file, "create", errno);
    }
    const std::string line = holder.line();
    const bool ok = ::write(fd, line.data(), line.size()) == static_cast<ssize_t>(line.size());
    if (::close(fd) != 0 || !ok) {
        ::unlink(file.c_str());
        throw IoError::fromErrno(file, "write", errno);
    }
    return true;
}

// Removes the lock of `dead` if it is still there: under an flock on the folder, so that of two
// processes taking over the same stale lock, the second finds the first's new lock and keeps it.
void removeStaleLock(const fs::path& file, const LockHolder& dead) {
    const int dirFd = ::open(file.parent_path().empty() ? "." : file.parent_path().c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dirFd >= 0) ::flock(dirFd, LOCK_EX);  // where flock is not supported: without it
    if (const std::optional<LockHolder> now = readHolder(file); now && *now == dead) ::unlink(file.c_str());
    if (dirFd >= 0) ::close(dirFd);  // releases the flock
}

}  // namespace

DirectoryLock::DirectoryLock(const fs::path& dir) : file_(dir / kFileName) {
    const LockHolder me{static_cast<long>(::getpid()), hostName(), utcNow()};
    const fs::path candidate = writeCandidate(file_, me);
    // A few tries: a holder may finish, or a stale lock be removed, between our tries.
    for (int attempt = 0; attempt < 8; ++attempt) {
        bool placed = false;
        try {
            placed = placeLock(candidate, file_, me);
        } catch (...) {
            ::unlink(candidate.c_str());
            throw;
        }
        if (placed) {
            ::unlink(candidate.c_str());
            return;
        }
        const std::optional<LockHolder> holder = readHolder(file_);
        if (!holder) continue;  // released meanwhile
        if (isStale(*holder)) {
            removeStaleLock(file_, *holder);
            continue;
        }
        ::unlink(candidate.c_str());
        throw InputError(dir.string() + ": in use by " + holder->description() + " (lock file " + file_.string() +
                         "); wait for it to finish, or delete the lock file if that process is gone");
    }
    ::unlink(candidate.c_str());
    throw IoError(file_.string() + ": cannot create (the lock changed hands 8 times while this process tried to take it)");
}

DirectoryLock::~DirectoryLock() { ::unlink(file_.c_str()); }

}  // namespace hybridlab
