#include "common/core/content_hash.h"

#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <vector>

namespace hybridlab {

ContentHash& ContentHash::add(std::string_view bytes) {
    for (unsigned char c : bytes) {
        h_ ^= c;
        h_ *= 1099511628211ull;
    }
    // Separate consecutive fields: add("ab").add("c") != add("a").add("bc").
    h_ ^= 0xff;
    h_ *= 1099511628211ull;
    return *this;
}

ContentHash& ContentHash::add(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return add(std::string_view(buf));
}

ContentHash& ContentHash::add(std::int64_t v) { return add(std::to_string(v)); }

ContentHash& ContentHash::addFile(const std::filesystem::path& file) {
    add(file.filename().string());
    std::ifstream in(file, std::ios::binary);
    if (!in) throw std::runtime_error(file.string() + ": cannot read for hashing");
    std::vector<char> buf(1 << 20);
    while (in) {
        in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
        add(std::string_view(buf.data(), static_cast<std::size_t>(in.gcount())));
    }
    return *this;
}

std::string ContentHash::hex() const {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h_));
    return buf;
}

const std::string& programVersionHash() {
    static const std::string version = [] {
        std::error_code ec;
        auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
        return ec ? std::string("unknown") : ContentHash().addFile(exe).hex();
    }();
    return version;
}

}  // namespace hybridlab
