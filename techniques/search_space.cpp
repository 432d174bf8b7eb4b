#include "techniques/search_space.h"

#include <algorithm>
#include <stdexcept>

#include "common/core/input_error.h"

namespace hybridlab {

const char* searchScaleName(SearchDimension::Scale scale) {
    switch (scale) {
    case SearchDimension::Scale::Choice: return "choice";
    case SearchDimension::Scale::Linear: return "linear";
    case SearchDimension::Scale::Log: return "log";
    }
    return "choice";
}

namespace {

double numeric(const ParamValue& v) {
    if (const auto* i = std::get_if<long long>(&v)) return static_cast<double>(*i);
    if (const auto* d = std::get_if<double>(&v)) return *d;
    throw std::logic_error("not a number");
}

}  // namespace

void checkSearchSpace(const std::string& technique, const std::vector<ParamSpec>& parameters, const std::vector<SearchDimension>& space,
                      double pixels) {
    const std::string owner = "technique " + technique + " search space";
    for (const SearchDimension& d : space) {
        const auto spec = std::find_if(parameters.begin(), parameters.end(), [&](const ParamSpec& p) { return p.name == d.parameter; });
        if (spec == parameters.end()) throw std::logic_error(owner + ": no parameter '" + d.parameter + "'");
        if (d.values.empty()) throw std::logic_error(owner + ": '" + d.parameter + "' has no values");
        const bool isNumber = spec->type == ParamSpec::Type::Int || spec->type == ParamSpec::Type::Float;
        if (d.scale != SearchDimension::Scale::Choice && !isNumber)
            throw std::logic_error(owner + ": '" + d.parameter + "' is not numeric, so it cannot be refined");
        double previous = -1e300;
        for (ParamValue v : d.values) {
            if (d.perPixel) {
                const double scaled = numeric(v) * pixels;
                v = spec->type == ParamSpec::Type::Int ? ParamValue(static_cast<long long>(scaled)) : ParamValue(scaled);
            }
            try {
                resolveParameters(parameters, {{d.parameter, v}}, owner, ParameterSource::Typed);
            } catch (const InputError& e) {
                throw std::logic_error(e.what());
            }
            if (d.scale != SearchDimension::Scale::Choice) {
                const double x = numeric(v);
                if (x <= previous) throw std::logic_error(owner + ": '" + d.parameter + "' values are not increasing");
                if (d.scale == SearchDimension::Scale::Log && x <= 0.0)
                    throw std::logic_error(owner + ": '" + d.parameter + "' is searched on a log scale, so its values must be positive");
                previous = x;
            }
        }
    }
}

}  // namespace hybridlab
