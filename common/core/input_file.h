#pragma once
// Files named by outside input (scene files, configs, models, images): what is wrong with a path,
// said the same way by every reader, with the operating system's reason where it gives one. The
// filesystem library's throwing calls would end the program with an internal error on a path it
// cannot even look at (a loop of symbolic links: "Too many levels of symbolic links").
#include <filesystem>
#include <string>

namespace hybridlab {

enum class InputPathKind { RegularFile, Missing, Directory, Special, Unreadable };

// What `path` is; `reason` receives the operating system's words when it is Unreadable.
InputPathKind inputPathKind(const std::filesystem::path& path, std::string* reason = nullptr);

// Throws InputError "PATH: ..." unless `path` is a regular file: "file not found", "is a directory,
// expected WHAT", "is not a regular file (a device or a pipe), expected WHAT", "cannot be read
// (REASON)". `what` names what was expected ("a TOML file", "an image file").
void requireInputFile(const std::filesystem::path& path, const std::string& what);

// Whether `path` is a folder (false where nothing is there); throws InputError "PATH: is not a
// folder, expected WHAT" or "PATH: cannot be read (REASON)" otherwise.
bool inputFolderPresent(const std::filesystem::path& path, const std::string& what);

// The whole file, after requireInputFile's checks; a file that cannot be opened or read throws
// InputError "PATH: cannot be read (REASON)".
std::string readInputFile(const std::filesystem::path& path, const std::string& what);

}  // namespace hybridlab
