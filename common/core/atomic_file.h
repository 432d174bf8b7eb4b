#pragma once
// Every file the program writes goes through here: written to a temporary name beside the target
// (".tmp-PID-NAME", unique to this process; created exclusively, so a process of the same PID on
// another machine sharing the folder gets ".tmp-PID-N-NAME"), every step checked (open, each
// write, close), then renamed over the target. So a file under its final name is either absent,
// the old one, or complete; a process killed mid-write leaves only a ".tmp-PID-*" behind, which
// removeStaleTemporaries() collects. Failures throw IoError naming the target and the OS reason.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace hybridlab {

// Writes `bytes` as the complete file at `path`.
void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes);

// For a writer that must be given a path (an encoder that writes the file itself): `write` writes
// the complete file at the temporary path it is given and throws on failure; the file it leaves
// must exist and be a regular file, else the target is not touched.
void writeAtomically(const std::filesystem::path& path, const std::function<void(const std::filesystem::path&)>& write);

// Files that appear together or not at all (a scene file and the images it names): each is
// written whole under its temporary name as writeFileAtomically writes one (a failure names the
// file, not its temporary), and commit() renames them all into place; whatever is not committed
// is removed.
class FileGroup {
public:
    FileGroup() = default;
    ~FileGroup();
    FileGroup(const FileGroup&) = delete;
    FileGroup& operator=(const FileGroup&) = delete;

    void write(const std::filesystem::path& path, std::string_view bytes);
    // The files, in the order written.
    std::vector<std::filesystem::path> commit();

private:
    std::vector<std::pair<std::filesystem::path, std::filesystem::path>> staged_;  // (temporary, file)
};

// A folder that appears complete or not at all (a merged result set, a bundle): `fill` fills the
// temporary folder it is given beside `dir` (".tmp-PID-NAME"), which is then renamed to `dir`;
// whatever `fill` throws, the temporary is removed and `dir` is not touched (an IoError's message
// names the file under `dir`, not under the temporary). `dir` must not exist, or be an empty
// folder (the rename replaces it). A temporary of `dir` that a killed process left is removed first.
void writeFolderAtomically(const std::filesystem::path& dir, const std::function<void(const std::filesystem::path&)>& fill);

// fs::create_directories, failing with IoError naming `dir` and the reason.
void createDirectories(const std::filesystem::path& dir);

// The temporary name writeFileAtomically uses for `path` in this process (unless it exists).
std::filesystem::path temporaryPathFor(const std::filesystem::path& path);

// Removes the ".tmp-PID-*" files under `dir` (recursively) whose process PID no longer runs on
// this machine; returns how many it removed.
std::size_t removeStaleTemporaries(const std::filesystem::path& dir);

// Tests only: HYBRIDLAB_TEST_WRITE_LIMIT=N makes the process's writes fail with ENOSPC ("No space
// left on device") once N bytes in all have been written, as a full disk would (the bytes up to
// the limit are written first). Unset, there is no limit.

}  // namespace hybridlab
