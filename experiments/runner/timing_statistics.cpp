#include "experiments/runner/timing_statistics.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace hybridlab {

namespace {

double medianOfSorted(const std::vector<double>& v) {
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

double median(std::vector<double> values) {
    if (values.empty()) throw std::invalid_argument("median of no values");
    std::sort(values.begin(), values.end());
    return medianOfSorted(values);
}

double MedianInterval::relativeHalfWidth() const {
    if (!hasInterval || median <= 0.0) return INFINITY;
    return std::max(median - low, high - median) / median;
}

MedianInterval medianInterval(std::vector<double> values, double confidence) {
    if (values.empty()) throw std::invalid_argument("medianInterval of no values");
    std::sort(values.begin(), values.end());
    MedianInterval m;
    m.n = values.size();
    m.median = medianOfSorted(values);
    m.low = values.front();
    m.high = values.back();
    const std::size_t l = intervalRank(m.n, confidence);
    if (l == 0) return m;  // no pair reaches the confidence: min and max stand, without an interval
    m.low = values[l - 1];
    m.high = values[m.n - l];
    m.hasInterval = true;
    return m;
}

std::size_t intervalRank(std::size_t n, double confidence) {
    // [x_(l), x_(n+1-l)] covers the median with probability 1 - 2 P(X <= l - 1), X ~ binomial(n,
    // 1/2): the largest l that keeps the coverage at the confidence. Each term C(n, i) / 2^n is
    // formed in log space (report/timing.py sums the same terms the same way, so both sides choose
    // the same ranks).
    std::size_t l = 0;
    double below = 0.0;  // P(X <= k - 1), accumulated as k grows
    double logTerm = -static_cast<double>(n) * std::log(2.0);
    for (std::size_t k = 1; k <= (n + 1) / 2; ++k) {
        below += std::exp(logTerm);
        logTerm += std::log(static_cast<double>(n - (k - 1))) - std::log(static_cast<double>(k));
        if (1.0 - 2.0 * below >= confidence) l = k;
        else break;
    }
    return l;
}

std::size_t minimumSamplesForInterval(double confidence) {
    std::size_t n = 1;
    while (intervalRank(n, confidence) == 0) ++n;
    return n;
}

MedianInterval pairedRatio(const std::vector<double>& numerator, const std::vector<double>& denominator, double confidence) {
    if (numerator.size() != denominator.size() || numerator.empty())
        throw std::invalid_argument("pairedRatio: the rounds of the two settings differ in number");
    std::vector<double> ratios(numerator.size());
    for (std::size_t k = 0; k < ratios.size(); ++k) ratios[k] = numerator[k] / denominator[k];
    return medianInterval(std::move(ratios), confidence);
}

std::vector<std::size_t> roundOrder(std::size_t count, std::size_t round, std::uint64_t seed) {
    if (count == 0) return {};
    // The settings relabelled: Fisher-Yates with splitmix64, the same permutation from the same
    // seed on every platform (std::shuffle's and the standard distributions' algorithms are the
    // library's choice).
    std::vector<std::size_t> label(count);
    std::iota(label.begin(), label.end(), std::size_t{0});
    std::uint64_t state = seed;
    const auto next = [&state] {
        std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    };
    for (std::size_t i = count; i > 1; --i) std::swap(label[i - 1], label[next() % i]);
    // Williams' first row 0, 1, n-1, 2, n-2, ...; row r adds r to every entry (mod n). Each
    // difference between neighbours occurs once in the row, so each ordered pair of neighbours
    // occurs once in the square; an odd n needs the square's rows reversed as well.
    const std::size_t period = count % 2 ? 2 * count : count;
    const std::size_t row = round % period;
    std::vector<std::size_t> order(count);
    for (std::size_t p = 0; p < count; ++p) {
        const std::size_t step = (p + 1) / 2;
        const std::size_t first = p % 2 ? step : (count - step) % count;
        order[p] = label[(first + row) % count];
    }
    if (row >= count) std::reverse(order.begin(), order.end());
    return order;
}

bool steadyTimes(const std::vector<double>& times, std::size_t frames, double tolerance) {
    if (frames == 0 || times.size() < frames) return false;
    std::vector<double> last(times.end() - static_cast<std::ptrdiff_t>(frames), times.end());
    std::sort(last.begin(), last.end());
    return last.back() - last.front() <= tolerance * medianOfSorted(last);
}

}  // namespace hybridlab
