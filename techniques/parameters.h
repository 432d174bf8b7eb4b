#pragma once
// Technique parameters: each technique declares its parameters (name, type, range or choices,
// default, description); values come from `--param key=value` on the command line or from an
// experiment config, and both go through resolveParameters, so they are checked the same way.
#include <map>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace hybridlab {

using ParamValue = std::variant<bool, long long, double, std::string>;

struct ParamSpec {
    enum class Type { Bool, Int, Float, Choice };

    std::string name;
    Type type = Type::Float;
    ParamValue defaultValue;
    std::string description;
    double min = -1e300, max = 1e300;   // Int and Float
    std::vector<std::string> choices;   // Choice

    static ParamSpec boolean(std::string name, bool def, std::string description);
    static ParamSpec integer(std::string name, long long def, long long min, long long max, std::string description);
    static ParamSpec real(std::string name, double def, double min, double max, std::string description);
    static ParamSpec choice(std::string name, std::string def, std::vector<std::string> choices, std::string description);

    // "int in [1, 16]", "one of: a, b", ...
    std::string typeDescription() const;
};

std::string formatParamValue(const ParamValue& v);

class ParameterSet {
public:
    bool getBool(const std::string& name) const { return std::get<bool>(at(name)); }
    long long getInt(const std::string& name) const { return std::get<long long>(at(name)); }
    double getFloat(const std::string& name) const { return std::get<double>(at(name)); }
    const std::string& getChoice(const std::string& name) const { return std::get<std::string>(at(name)); }

    const std::map<std::string, ParamValue>& values() const { return values_; }
    void set(const std::string& name, ParamValue v) { values_[name] = std::move(v); }

private:
    const ParamValue& at(const std::string& name) const;
    std::map<std::string, ParamValue> values_;
};

// Where given values come from: command-line text, each string converted to the declared type, or
// a typed file (an experiment config's TOML), whose values must have the declared type (a string
// "3" is not an integer; an integer is accepted for a Float).
enum class ParameterSource { Text, Typed };

// Checks `given` against `specs` (unknown names, types, ranges, choices) and fills in defaults.
// Throws InputError naming the parameter and what was expected; `owner` (e.g. "technique whitted")
// leads the message. `written`, when not empty, holds each given value as its file writes it
// (parallel to `given`), which the message quotes ("got 2.0", not the double's "2").
ParameterSet resolveParameters(const std::vector<ParamSpec>& specs, const std::vector<std::pair<std::string, ParamValue>>& given,
                               const std::string& owner, ParameterSource source = ParameterSource::Text,
                               const std::vector<std::string>& written = {});

// Splits "key=value" command-line text.
std::pair<std::string, ParamValue> parseParamAssignment(const std::string& text);

}  // namespace hybridlab
