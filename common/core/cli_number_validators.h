#pragma once
// Command-line numbers through the same checks as TOML and glTF numbers (common/core/number_check.h):
// CLI11's Range lets NaN through (every comparison with it is false), and its message differs.
// Messages echo the text as written: a number too large for its type is what the user typed, not
// the value the conversion saturated to.
#include <charconv>
#include <string>

#include <CLI/CLI.hpp>

#include "common/core/number_check.h"

namespace hybridlab::cli {

// A finite number in [min, max].
inline CLI::Validator numberIn(double min, double max) {
    return CLI::Validator(
        [min, max](std::string& text) -> std::string {
            double v = 0.0;
            if (!CLI::detail::lexical_cast(text, v)) return "expected a number, got '" + text + "'";
            return numberProblem(v, min, max, text);
        },
        "NUMBER", "numberIn");
}

// An integer in [min, max] (text that is not one, or would not fit, is refused, never wrapped).
inline CLI::Validator integerIn(long long min, long long max) {
    return CLI::Validator(
        [min, max](std::string& text) -> std::string {
            long long v = 0;
            const char* end = text.data() + text.size();
            const auto [stop, error] = std::from_chars(text.data() + (!text.empty() && text[0] == '+'), end, v);
            const std::string expected = "expected an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "], got ";
            // Digits beyond a long long's range: a whole number, out of range.
            if (error == std::errc::result_out_of_range && stop == end) return expected + text;
            if (error != std::errc() || stop != end) return expected + "'" + text + "'";
            return integerProblem(v, min, max, text);
        },
        "INT", "integerIn");
}

// Text that must not be empty (a name, a folder): "expected `what`, got ''".
inline CLI::Validator nonEmpty(const std::string& what) {
    return CLI::Validator([what](std::string& text) { return text.empty() ? "expected " + what + ", got ''" : std::string(); }, "TEXT",
                          "nonEmpty");
}

}  // namespace hybridlab::cli
