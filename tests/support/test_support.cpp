#include "tests/support/test_support.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "common/scene/scene_catalog.h"

namespace hybridlab::test {
namespace fs = std::filesystem;

TempDir::TempDir() {
    std::string templ = (fs::temp_directory_path() / "hybridlab-test-XXXXXX").string();
    if (!::mkdtemp(templ.data())) throw std::runtime_error("cannot create a temporary folder from " + templ);
    path_ = templ;
}

TempDir::~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
}

void writeTextFile(const fs::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
    if (!out) throw std::runtime_error("cannot write " + path.string());
}

void writeBinaryFile(const fs::path& path, const std::vector<std::uint8_t>& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (!out) throw std::runtime_error("cannot write " + path.string());
}

fs::path fixturesDir() { return fs::path(HYBRIDLAB_TEST_FIXTURES); }

fs::path sourceDir() { return fixturesDir().parent_path().parent_path(); }

std::string readTextFile(const fs::path& path) {
    std::ifstream in(path);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

std::vector<std::string> textLines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
}

std::vector<std::string> fileTree(const fs::path& dir) {
    std::vector<std::string> out;
    if (!fs::exists(dir)) return out;
    for (const auto& e : fs::recursive_directory_iterator(dir)) out.push_back(fs::relative(e.path(), dir).string());
    std::sort(out.begin(), out.end());
    return out;
}

fs::path builtinSceneFile(const std::string& name) { return scenesDirectory() / (name + ".toml"); }

namespace {

template <typename V>
std::string str(const V& v) {
    std::ostringstream s;
    s.precision(9);
    s << "(";
    for (int i = 0; i < V::length(); ++i) s << (i ? ", " : "") << v[i];
    s << ")";
    return s.str();
}

template <typename V>
::testing::AssertionResult near(const V& actual, const V& expected, float tolerance) {
    for (int i = 0; i < V::length(); ++i) {
        // Written so that NaN fails.
        if (!(std::abs(actual[i] - expected[i]) <= tolerance)) {
            return ::testing::AssertionFailure() << "actual " << str(actual) << " differs from expected " << str(expected)
                                                 << " in component " << i << " by more than " << tolerance;
        }
    }
    return ::testing::AssertionSuccess();
}

}  // namespace

::testing::AssertionResult vecNear(glm::vec2 a, glm::vec2 e, float tol) { return near(a, e, tol); }
::testing::AssertionResult vecNear(glm::vec3 a, glm::vec3 e, float tol) { return near(a, e, tol); }
::testing::AssertionResult vecNear(glm::vec4 a, glm::vec4 e, float tol) { return near(a, e, tol); }

::testing::AssertionResult contains(const std::string& text, const std::string& fragment) {
    if (text.find(fragment) != std::string::npos) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "expected to find\n  \"" << fragment << "\"\nin\n  \"" << text << "\"";
}

}  // namespace hybridlab::test
