#include "tests/support/report_checks.h"
#include "tests/support/test_support.h"

#include <cstdio>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>

namespace hybridlab::test {

namespace fs = std::filesystem;

std::string formatNumber(const char* spec, double v) {
    char text[64];
    std::snprintf(text, sizeof text, spec, v);
    return text;
}

std::string reportVariant(const nlohmann::json& record) {
    const std::string params = record.at("parameters_text");
    return record.at("label").get<std::string>() + (params.empty() ? "" : " [" + params + "]");
}

std::string readReportPage(const fs::path& reportDir) { return readTextFile(reportDir / "index.html"); }

std::size_t expectReportLinksResolve(const fs::path& reportDir) {
    const std::string page = readReportPage(reportDir);
    std::size_t links = 0;
    for (const std::string attr : {"href=\"", "src=\""}) {
        for (std::size_t at = page.find(attr); at != std::string::npos; at = page.find(attr, at + 1)) {
            const std::size_t start = at + attr.size(), end = page.find('"', start);
            const std::string link = page.substr(start, end - start), target = link.substr(0, link.find('#'));
            // A link within the page ("#failures") names no file, nor does an inline one ("data:,").
            if (!target.empty() && target.rfind("data:", 0) != 0) {
                EXPECT_TRUE(fs::exists(reportDir / target)) << link;
            }
            ++links;
        }
    }
    return links;
}

std::size_t expectFiguresHaveContent(const fs::path& reportDir, const std::string& prefix) {
    std::size_t figures = 0;
    for (const auto& f : fs::directory_iterator(reportDir / "figures")) {
        if (f.path().filename().string().rfind(prefix, 0) != 0) continue;
        ++figures;
        EXPECT_GT(fs::file_size(f.path()), 2000u) << f.path();
    }
    return figures;
}

}  // namespace hybridlab::test
