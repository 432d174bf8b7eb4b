#pragma once
// One writer per output folder: a lock file (".lock", holding "PID HOST START": the holder's
// process, machine and the UTC time it took the lock) in the folder, removed when the lock is
// dropped. The file appears whole or not at all (written under a name of its own, then linked to
// ".lock", which fails if one exists), so a second process asking for the same folder, however
// close behind, reads who holds it and is refused naming that holder. A lock left by a process
// that no longer runs on this host (killed) is taken over; two processes taking over one stale lock
// do so one after the other (an flock on the folder), and only the one that still finds the dead
// holder's lock removes it.
#include <filesystem>
#include <string>

namespace hybridlab {

class DirectoryLock {
public:
    // Throws InputError naming the holder when another live process holds `dir`, IoError when the
    // lock file cannot be written. `dir` must exist.
    explicit DirectoryLock(const std::filesystem::path& dir);
    ~DirectoryLock();
    DirectoryLock(const DirectoryLock&) = delete;
    DirectoryLock& operator=(const DirectoryLock&) = delete;

    static constexpr const char* kFileName = ".lock";

private:
    std::filesystem::path file_;
};

}  // namespace hybridlab
