#include "common/core/number_check.h"

#include <cmath>
#include <sstream>

namespace hybridlab {

std::string numberProblem(double v, double min, double max, std::string_view written) {
    if (std::isfinite(v) && v >= min && v <= max) return {};
    std::ostringstream s;
    s << "expected a" << (std::isfinite(v) ? "" : " finite") << " number in [" << min << ", " << max << "], got ";
    if (written.empty()) s << v;
    else s << written;
    return s.str();
}

std::string formatNumber(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

std::string integerProblem(long long v, long long min, long long max, std::string_view written) {
    if (v >= min && v <= max) return {};
    return "expected an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "], got " +
           (written.empty() ? std::to_string(v) : std::string(written));
}

}  // namespace hybridlab
