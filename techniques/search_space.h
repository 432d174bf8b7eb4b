#pragma once
// The knobs `hybridlab tune` searches (experiments/tune/search.py): beside its parameters, a
// technique declares which of them trade its speed for its quality and the coarse grid the search
// starts from; the search refines the numeric ones between the grid's values. Parameters that
// change what is drawn rather than how well (debug images, backends, caches) are not searched.
#include <string>
#include <vector>

#include "techniques/parameters.h"

namespace hybridlab {

struct SearchDimension {
    // How the search steps between two values: not at all (a choice), half-way, or half-way on a
    // log scale (a count or a length whose effect is by ratio: march steps, a ray budget).
    enum class Scale { Choice, Linear, Log };

    std::string parameter;
    std::vector<ParamValue> values;  // the coarse grid, in increasing order for a numeric knob
    Scale scale = Scale::Choice;
    // The values count per pixel of the frame (a ray budget): the search multiplies them by the
    // frame's pixels, so that one grid serves every size.
    bool perPixel = false;
};

const char* searchScaleName(SearchDimension::Scale scale);  // "choice", "linear", "log"

// Throws std::logic_error where a dimension names no declared parameter, or a value (scaled by
// `pixels` where per pixel) is not one its parameter accepts, or a numeric grid is not increasing
// or (on a log scale) not positive: a declaration error, caught by the registry's tests.
void checkSearchSpace(const std::string& technique, const std::vector<ParamSpec>& parameters, const std::vector<SearchDimension>& space,
                      double pixels = 320.0 * 180.0);

}  // namespace hybridlab
