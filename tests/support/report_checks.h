#pragma once
// Checks of a report folder written by `hybridlab report` (report/report.py): that every
// link of its page resolves to a file and that its figures have content.
#include <cstddef>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

namespace hybridlab::test {

// `v` formatted as printf's `spec` does (as Python's "%" operator the report scripts use).
std::string formatNumber(const char* spec, double v);

// A record's technique setting as the report names it: "label [parameters]" (the label alone
// without parameters).
std::string reportVariant(const nlohmann::json& record);

// index.html's text.
std::string readReportPage(const std::filesystem::path& reportDir);

// Expects every href and src of index.html to name an existing file (a viewer link's '#run=...'
// is dropped: the file is what must exist); returns how many links there are.
std::size_t expectReportLinksResolve(const std::filesystem::path& reportDir);

// Expects every file in figures/ whose name starts with `prefix` to be larger than an empty
// figure; returns how many there are.
std::size_t expectFiguresHaveContent(const std::filesystem::path& reportDir, const std::string& prefix = "");

}  // namespace hybridlab::test
