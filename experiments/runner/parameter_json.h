#pragma once
// A technique parameter's value as JSON (a number stays a number): the records' "parameters" and
// `hybridlab techniques --json` write it.
#include <string>
#include <variant>

#include <nlohmann/json.hpp>

#include "techniques/parameters.h"

namespace hybridlab {

inline nlohmann::json parameterJson(const ParamValue& v) {
    if (auto b = std::get_if<bool>(&v)) return *b;
    if (auto i = std::get_if<long long>(&v)) return *i;
    if (auto d = std::get_if<double>(&v)) return *d;
    return std::get<std::string>(v);
}

}  // namespace hybridlab
