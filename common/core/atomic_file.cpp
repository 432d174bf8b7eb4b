#include "common/core/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <limits>
#include <string>
#include <system_error>

#include "common/core/io_error.h"

namespace hybridlab {
namespace fs = std::filesystem;

namespace {

constexpr std::string_view kTemporaryPrefix = ".tmp-";

// The bytes this process may still write under HYBRIDLAB_TEST_WRITE_LIMIT (see the header).
std::atomic<long long>& writeBudget() {
    static std::atomic<long long> budget = [] {
        const char* limit = std::getenv("HYBRIDLAB_TEST_WRITE_LIMIT");
        return limit && *limit ? std::atoll(limit) : std::numeric_limits<long long>::max();
    }();
    return budget;
}

// write(2) all of `bytes`; false with errno set on failure.
bool writeAll(int fd, std::string_view bytes) {
    while (!bytes.empty()) {
        std::size_t chunk = bytes.size();
        const long long left = writeBudget().fetch_sub(static_cast<long long>(chunk));
        if (left < static_cast<long long>(chunk)) {
            chunk = static_cast<std::size_t>(std::max(0LL, left));
            if (chunk == 0) {
                errno = ENOSPC;
                return false;
            }
        }
        const ssize_t n = ::write(fd, bytes.data(), chunk);
        if (n < 0) {
            if (errno == EINTR) continue;
            return false;
        }
        bytes.remove_prefix(static_cast<std::size_t>(n));
    }
    return true;
}

// The target must be a file name we may replace: not a folder (rename would fail with a
// confusing reason, or succeed on an empty one).
void checkTarget(const fs::path& path) {
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw IoError(path.string() + ": cannot write (it is a directory)");
}

void renameOver(const fs::path& tmp, const fs::path& path) {
    if (::rename(tmp.c_str(), path.c_str()) != 0) {
        const int error = errno;
        ::unlink(tmp.c_str());
        throw IoError::fromErrno(path, "write", error);
    }
}

// The PID of a temporary file's name, or 0 when the name is not one of ours.
pid_t temporaryOwner(const std::string& name) {
    if (name.rfind(kTemporaryPrefix, 0) != 0) return 0;
    std::size_t i = kTemporaryPrefix.size();
    long long pid = 0;
    for (; i < name.size() && name[i] >= '0' && name[i] <= '9' && pid < (1LL << 31); ++i) pid = pid * 10 + (name[i] - '0');
    if (i == kTemporaryPrefix.size() || i >= name.size() || name[i] != '-' || pid <= 0 || pid >= (1LL << 31)) return 0;
    return static_cast<pid_t>(pid);
}

// Creates the temporary file for `path` exclusively and returns its descriptor, or -1 with errno.
// Exclusively: a process of the same PID on another machine may be writing the same file into a
// shared folder (two cluster nodes filling one reference cache), so a name that exists is left to
// its owner and ".tmp-PID-N-NAME" tried instead.
int createTemporary(const fs::path& path, fs::path& tmp) {
    for (int attempt = 0; attempt < 100; ++attempt) {
        tmp = attempt == 0 ? temporaryPathFor(path)
                           : path.parent_path() / (std::string(kTemporaryPrefix) + std::to_string(::getpid()) + "-" + std::to_string(attempt) +
                                                   "-" + path.filename().string());
        const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
        if (fd >= 0 || errno != EEXIST) return fd;
    }
    errno = EEXIST;
    return -1;
}

}  // namespace

fs::path temporaryPathFor(const fs::path& path) {
    return path.parent_path() / (std::string(kTemporaryPrefix) + std::to_string(::getpid()) + "-" + path.filename().string());
}

namespace {

// `bytes` written whole under `path`'s temporary name, which is returned; failures name `path`.
fs::path writeTemporary(const fs::path& path, std::string_view bytes) {
    checkTarget(path);
    fs::path tmp;
    const int fd = createTemporary(path, tmp);
    if (fd < 0) throw IoError::fromErrno(path, "write", errno);
    const bool written = writeAll(fd, bytes);
    int error = written ? 0 : errno;
    // close() reports what a write-back cache deferred (NFS, quotas).
    if (::close(fd) != 0 && written) error = errno;
    if (error != 0) {
        ::unlink(tmp.c_str());
        throw IoError::fromErrno(path, "write", error);
    }
    return tmp;
}

}  // namespace

void writeFileAtomically(const fs::path& path, std::string_view bytes) { renameOver(writeTemporary(path, bytes), path); }

FileGroup::~FileGroup() {
    for (const auto& [tmp, path] : staged_) ::unlink(tmp.c_str());
}

void FileGroup::write(const fs::path& path, std::string_view bytes) { staged_.emplace_back(writeTemporary(path, bytes), path); }

std::vector<fs::path> FileGroup::commit() {
    std::vector<fs::path> files;
    for (const auto& [tmp, path] : staged_) {
        renameOver(tmp, path);
        files.push_back(path);
    }
    staged_.clear();
    return files;
}

void writeAtomically(const fs::path& path, const std::function<void(const fs::path&)>& write) {
    checkTarget(path);
    fs::path tmp;
    const int fd = createTemporary(path, tmp);  // the name reserved; the writer writes over it
    if (fd < 0) throw IoError::fromErrno(path, "write", errno);
    ::close(fd);
    try {
        write(tmp);
    } catch (...) {
        ::unlink(tmp.c_str());
        throw;
    }
    struct stat st {};
    if (::stat(tmp.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) {
        const int error = errno ? errno : EIO;
        ::unlink(tmp.c_str());
        throw IoError::fromErrno(path, "write", error);
    }
    renameOver(tmp, path);
}

namespace {

// Whether the process that named a temporary `pid` has gone: not this one, and kill(pid, 0) fails
// with ESRCH (no such process; EPERM means one runs under another user).
bool ownerIsGone(pid_t pid) { return pid != ::getpid() && ::kill(pid, 0) != 0 && errno == ESRCH; }

// The staging folders of `target` that a killed process left beside it.
void removeStaleStagingOf(const fs::path& target) {
    const fs::path parent = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    const std::string suffix = "-" + target.filename().string();
    std::error_code ec;
    for (fs::directory_iterator it(parent, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        const pid_t pid = temporaryOwner(name);
        if (pid == 0 || name != std::string(kTemporaryPrefix) + std::to_string(pid) + suffix) continue;
        std::error_code removeError;
        if (it->is_directory(removeError) && ownerIsGone(pid)) fs::remove_all(it->path(), removeError);
    }
}

}  // namespace

void writeFolderAtomically(const fs::path& dir, const std::function<void(const fs::path&)>& fill) {
    const fs::path target = dir.has_filename() ? dir : dir.parent_path();  // "out/" is "out"
    removeStaleStagingOf(target);
    const fs::path staging = temporaryPathFor(target);
    createDirectories(staging);
    try {
        fill(staging);
        std::error_code ec;
        fs::rename(staging, target, ec);
        if (ec) throw IoError::fromErrno(target, "create", ec.value());
    } catch (const IoError& e) {
        std::error_code ignored;
        fs::remove_all(staging, ignored);
        // Named as the user will look for it: under `dir`, not the temporary.
        std::string message = e.what();
        for (std::size_t at = message.find(staging.string()); at != std::string::npos; at = message.find(staging.string(), at))
            message.replace(at, staging.string().size(), target.string());
        throw IoError(message);
    } catch (...) {
        std::error_code ignored;
        fs::remove_all(staging, ignored);
        throw;
    }
}

void createDirectories(const fs::path& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw IoError(dir.string() + ": cannot create folder (" + ec.message() + ")");
}

std::size_t removeStaleTemporaries(const fs::path& dir) {
    std::size_t removed = 0;
    std::error_code ec;
    for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const pid_t pid = temporaryOwner(it->path().filename().string());
        if (pid == 0 || !it->is_regular_file() || !ownerIsGone(pid)) continue;  // ours or a live process's: not stale
        std::error_code removeError;
        if (fs::remove(it->path(), removeError)) ++removed;
    }
    return removed;
}

}  // namespace hybridlab
