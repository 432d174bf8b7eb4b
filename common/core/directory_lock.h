#pragma once
// One writer per output folder: a lock file (".lock", holding "PID HOST") created exclusively in
// the folder and removed when the lock is dropped. A second process asking for the same folder is
// refused with the owner's PID and host; a lock left by a process that no longer runs on this
// host (killed) is taken over.
#include <filesystem>
#include <string>

namespace hybridlab {

class DirectoryLock {
public:
    // Throws InputError naming the owner when another live process holds `dir`, IoError when the
    // lock file cannot be written. `dir` must exist.
    explicit DirectoryLock(const std::filesystem::path& dir);
    ~DirectoryLock();
    DirectoryLock(const DirectoryLock&) = delete;
    DirectoryLock& operator=(const DirectoryLock&) = delete;

    static constexpr const char* kFileName = ".lock";
    // Whether the lock was taken over from a process that had died holding it.
    bool tookOverStaleLock() const { return tookOver_; }

private:
    std::filesystem::path file_;
    bool tookOver_ = false;
};

}  // namespace hybridlab
