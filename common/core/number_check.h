#pragma once
// Numbers that come from outside (command line, TOML, glTF) are checked here, so that every reader
// says the same thing about the same mistake: finite, within [min, max], and within the type the
// value is stored in (a 2^32 that would wrap to 0 in an int is out of range, not 0). The callers
// add the position (file:line:column, or the option's name).
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>

namespace hybridlab {

// The range a number is checked against (numberProblem's min and max).
struct NumberRange {
    double min = -std::numeric_limits<double>::infinity();
    double max = std::numeric_limits<double>::infinity();
};

// Empty when `v` is finite and in [min, max]; else "expected a number in [min, max], got v", with
// v as `written` when given (the text the user wrote: "1e400", not the "inf" it became).
std::string numberProblem(double v, double min, double max, std::string_view written = {});

// Empty when `v` is in [min, max]; else "expected an integer in [min, max], got v" (v as `written`
// when given).
std::string integerProblem(long long v, long long min, long long max, std::string_view written = {});

// `v` as messages print numbers (shortest of %g's forms: 1e+06, 0.5, 30).
std::string formatNumber(double v);

// The bounds of values that drive memory or time, named so that messages and tests agree.
namespace limits {
inline constexpr int kImageSide = 16384;            // pixels a side (width, height, resolutions)
inline constexpr double kSceneTime = 1e6;           // |seconds| of scene time (--time)
inline constexpr int kTessellation = 4096;          // slices or stacks of a sphere or cylinder
inline constexpr long long kPrimitiveVertices = 4'000'000;  // one tessellated primitive's vertices
inline constexpr int kFrame = 10'000'000;           // a frame number on a camera path
inline constexpr float kSceneCoordinate = 1e12f;    // |world coordinate| of a vertex (as far as a camera's far plane)
// A camera's lens, from a scene file's [camera] or a glTF camera.
inline constexpr NumberRange kFovYDegrees{1e-3, 179.0};
inline constexpr NumberRange kOrthoHeight{1e-6, 1e9};  // the view's height, in world units
inline constexpr NumberRange kNearPlane{1e-6, 1e9};
inline constexpr NumberRange kFarPlane{1e-6, 1e12};
}  // namespace limits

}  // namespace hybridlab
