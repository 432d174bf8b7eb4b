#include "common/scene/keyframes.h"

#include <algorithm>

namespace hybridlab {

KeySegment findSegment(std::span<const double> times, double t) {
    if (times.size() < 2 || t <= times.front()) return {0, 0.0f};
    if (t >= times.back()) return {times.size() - 2, 1.0f};
    auto it = std::upper_bound(times.begin(), times.end(), t);
    std::size_t i = static_cast<std::size_t>(it - times.begin()) - 1;
    return {i, static_cast<float>((t - times[i]) / (times[i + 1] - times[i]))};
}

glm::vec3 interpolate(std::span<const double> times, std::span<const glm::vec3> values, double t,
                      Interpolation mode) {
    if (values.size() == 1) return values[0];
    KeySegment s = findSegment(times, t);
    const std::size_t i = s.index, n = values.size();
    const glm::vec3 &p0 = values[i], &p1 = values[i + 1];
    if (mode == Interpolation::Linear) return p0 + (p1 - p0) * s.u;

    auto tangent = [&](std::size_t k) {  // dp/dt at key k
        std::size_t a = k == 0 ? 0 : k - 1, b = std::min(k + 1, n - 1);
        return (values[b] - values[a]) / static_cast<float>(times[b] - times[a]);
    };
    const float dt = static_cast<float>(times[i + 1] - times[i]);
    const glm::vec3 m0 = tangent(i) * dt, m1 = tangent(i + 1) * dt;
    const float u = s.u, u2 = u * u, u3 = u2 * u;
    return (2 * u3 - 3 * u2 + 1) * p0 + (u3 - 2 * u2 + u) * m0 + (-2 * u3 + 3 * u2) * p1 + (u3 - u2) * m1;
}

glm::quat interpolate(std::span<const double> times, std::span<const glm::quat> values, double t) {
    if (values.size() == 1) return values[0];
    KeySegment s = findSegment(times, t);
    return glm::normalize(glm::slerp(values[s.index], values[s.index + 1], s.u));
}

}  // namespace hybridlab
