#include "common/core/input_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <system_error>

#include "common/core/input_error.h"

namespace hybridlab {
namespace fs = std::filesystem;

InputPathKind inputPathKind(const fs::path& path, std::string* reason) {
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    switch (status.type()) {
    case fs::file_type::regular: return InputPathKind::RegularFile;
    case fs::file_type::directory: return InputPathKind::Directory;
    case fs::file_type::not_found: return InputPathKind::Missing;
    case fs::file_type::none:
        if (reason) *reason = ec ? ec.message() : "unknown error";
        return InputPathKind::Unreadable;
    default: return InputPathKind::Special;
    }
}

void requireInputFile(const fs::path& path, const std::string& what) {
    std::string reason;
    switch (inputPathKind(path, &reason)) {
    case InputPathKind::RegularFile: return;
    case InputPathKind::Missing: throw InputError(path.string() + ": file not found");
    case InputPathKind::Directory: throw InputError(path.string() + ": is a directory, expected " + what);
    case InputPathKind::Special: throw InputError(path.string() + ": is not a regular file (a device or a pipe), expected " + what);
    case InputPathKind::Unreadable: throw InputError(path.string() + ": cannot be read (" + reason + ")");
    }
}

bool inputFolderPresent(const fs::path& path, const std::string& what) {
    std::string reason;
    switch (inputPathKind(path, &reason)) {
    case InputPathKind::Missing: return false;
    case InputPathKind::Directory: return true;
    case InputPathKind::Unreadable: throw InputError(path.string() + ": cannot be read (" + reason + ")");
    default: throw InputError(path.string() + ": is not a folder, expected " + what);
    }
}

std::string readInputFile(const fs::path& path, const std::string& what) {
    requireInputFile(path, what);
    const auto unreadable = [&](int error) { return InputError(path.string() + ": cannot be read (" + std::strerror(error) + ")"); };
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw unreadable(errno);
    std::string bytes;
    char buffer[1 << 16];
    for (;;) {
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n == 0) break;
        if (n < 0) {
            if (errno == EINTR) continue;
            const int error = errno;
            ::close(fd);
            throw unreadable(error);
        }
        bytes.append(buffer, static_cast<std::size_t>(n));
    }
    ::close(fd);
    return bytes;
}

}  // namespace hybridlab
