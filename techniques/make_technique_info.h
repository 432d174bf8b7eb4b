#pragma once
// The registry entry of a technique whose parameters are a struct bound by a ParameterBinder
// (parameter_binder.h): the declarations come from the binder, and the factory fills the struct
// from the resolved values and hands it to the technique.
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "techniques/parameter_binder.h"
#include "techniques/technique.h"

namespace hybridlab {

// `create` receives the filled struct (e.g. [](const P& p) { return std::make_unique<T>(p); }).
// Throws std::logic_error when a field of the struct is bound to no parameter.
template <class Params, class Create>
TechniqueInfo makeTechniqueInfo(std::string name, std::string description, ParameterBinder<Params> parameters, Create create,
                                double relativeCost = 1.0) {
    parameters.checkEveryFieldBound("technique " + name);
    std::vector<ParamSpec> specs = parameters.specs();
    return {std::move(name), std::move(description), std::move(specs),
            [parameters = std::move(parameters), create = std::move(create)](const ParameterSet& p) -> std::unique_ptr<Technique> {
                return create(parameters.fill(p));
            },
            relativeCost, std::nullopt, /*searchSpace=*/{}};
}

}  // namespace hybridlab
