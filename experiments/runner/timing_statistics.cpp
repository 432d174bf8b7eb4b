#include "experiments/runner/timing_statistics.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace hybridlab {

namespace {

// P(X <= k) for X ~ binomial(n, 1/2).
double binomialHalfCdf(std::size_t n, std::size_t k) {
    double sum = 0.0, term = std::pow(0.5, static_cast<double>(n));  // C(n, 0) / 2^n
    for (std::size_t i = 0; i <= k && i <= n; ++i) {
        sum += term;
        term *= static_cast<double>(n - i) / static_cast<double>(i + 1);
    }
    return sum;
}

double medianOfSorted(const std::vector<double>& v) {
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

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
    // The interval [x_(l), x_(n+1-l)] covers the median with probability 1 - 2 P(X <= l - 1):
    // the largest l that keeps the coverage at the confidence.
    const std::size_t n = m.n;
    std::size_t l = 0;
    for (std::size_t k = 1; k <= (n + 1) / 2; ++k) {
        if (1.0 - 2.0 * binomialHalfCdf(n, k - 1) >= confidence) l = k;
        else break;
    }
    if (l == 0) return m;  // no pair reaches the confidence: min and max stand, without an interval
    m.low = values[l - 1];
    m.high = values[n - l];
    m.hasInterval = true;
    return m;
}

std::size_t minimumSamplesForInterval(double confidence) {
    std::size_t n = 1;
    while (1.0 - 2.0 * binomialHalfCdf(n, 0) < confidence) ++n;
    return n;
}

MedianInterval pairedRatio(const std::vector<double>& numerator, const std::vector<double>& denominator) {
    if (numerator.size() != denominator.size() || numerator.empty())
        throw std::invalid_argument("pairedRatio: the rounds of the two settings differ in number");
    std::vector<double> ratios(numerator.size());
    for (std::size_t k = 0; k < ratios.size(); ++k) ratios[k] = numerator[k] / denominator[k];
    return medianInterval(std::move(ratios));
}

TimeOrder compareTimes(const MedianInterval& ratio, double tolerance) {
    if (!ratio.hasInterval) return TimeOrder::Tied;
    if (ratio.high < 1.0 && ratio.median < 1.0 - tolerance) return TimeOrder::Faster;
    if (ratio.low > 1.0 && ratio.median > 1.0 + tolerance) return TimeOrder::Slower;
    return TimeOrder::Tied;
}

const char* timeOrderName(TimeOrder order) {
    switch (order) {
        case TimeOrder::Faster: return "faster";
        case TimeOrder::Slower: return "slower";
        case TimeOrder::Tied: return "tied";
    }
    return "?";
}

std::vector<std::size_t> roundOrder(std::size_t count, std::size_t round, std::uint64_t seed) {
    std::vector<std::size_t> base(count);
    std::iota(base.begin(), base.end(), std::size_t{0});
    // Fisher-Yates with splitmix64: the same permutation from the same seed on every platform
    // (std::shuffle's and the standard distributions' algorithms are the library's choice).
    std::uint64_t state = seed;
    const auto next = [&state] {
        std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    };
    for (std::size_t i = count; i > 1; --i) std::swap(base[i - 1], base[next() % i]);
    if (count > 0) std::rotate(base.begin(), base.begin() + static_cast<std::ptrdiff_t>(round % count), base.end());
    return base;
}

bool steadyTimes(const std::vector<double>& times, std::size_t frames, double tolerance) {
    if (frames == 0 || times.size() < frames) return false;
    std::vector<double> last(times.end() - static_cast<std::ptrdiff_t>(frames), times.end());
    std::sort(last.begin(), last.end());
    return last.back() - last.front() <= tolerance * medianOfSorted(last);
}

}  // namespace hybridlab
