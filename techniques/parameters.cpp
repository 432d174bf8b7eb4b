#include "techniques/parameters.h"

#include <charconv>
#include <cmath>
#include <sstream>

#include "common/core/input_error.h"

namespace hybridlab {

ParamSpec ParamSpec::boolean(std::string name, bool def, std::string description) {
    return {std::move(name), Type::Bool, def, std::move(description), 0, 1, {}};
}
ParamSpec ParamSpec::integer(std::string name, long long def, long long min, long long max, std::string description) {
    return {std::move(name), Type::Int, def, std::move(description), static_cast<double>(min), static_cast<double>(max), {}};
}
ParamSpec ParamSpec::real(std::string name, double def, double min, double max, std::string description) {
    return {std::move(name), Type::Float, def, std::move(description), min, max, {}};
}
ParamSpec ParamSpec::choice(std::string name, std::string def, std::vector<std::string> choices, std::string description) {
    return {std::move(name), Type::Choice, std::move(def), std::move(description), 0, 0, std::move(choices)};
}

namespace {
std::string number(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}
}  // namespace

std::string ParamSpec::typeDescription() const {
    switch (type) {
    case Type::Bool: return "true or false";
    case Type::Int: return "an integer in [" + number(min) + ", " + number(max) + "]";
    case Type::Float: return "a number in [" + number(min) + ", " + number(max) + "]";
    case Type::Choice: {
        std::string s = "one of: ";
        for (std::size_t i = 0; i < choices.size(); ++i) s += (i ? ", " : "") + choices[i];
        return s;
    }
    }
    return "";
}

std::string formatParamValue(const ParamValue& v) {
    if (auto b = std::get_if<bool>(&v)) return *b ? "true" : "false";
    if (auto i = std::get_if<long long>(&v)) return std::to_string(*i);
    if (auto d = std::get_if<double>(&v)) return number(*d);
    return std::get<std::string>(v);
}

const ParamValue& ParameterSet::at(const std::string& name) const {
    auto it = values_.find(name);
    if (it == values_.end()) throw std::logic_error("parameter '" + name + "' was not declared");
    return it->second;
}

namespace {

// The given value as a message quotes it: as written when known, strings in quotes.
std::string quoted(const ParamValue& value, const std::string& written) {
    if (!written.empty()) return written;
    if (auto text = std::get_if<std::string>(&value)) return "'" + *text + "'";
    return formatParamValue(value);
}

ParamValue coerce(const ParamSpec& spec, const ParamValue& value, const std::string& owner, ParameterSource source,
                  const std::string& written) {
    auto fail = [&]() -> ParamValue {
        const bool typedString = source == ParameterSource::Typed && std::holds_alternative<std::string>(value) &&
                                 spec.type != ParamSpec::Type::Choice;
        throw InputError(owner + ": parameter '" + spec.name + "': expected " + spec.typeDescription() + ", got " +
                         (typedString ? "the string " : "") + quoted(value, written));
    };
    // Command-line text converts; a typed file's string is a string.
    const std::string* text = source == ParameterSource::Text || spec.type == ParamSpec::Type::Choice ? std::get_if<std::string>(&value) : nullptr;
    switch (spec.type) {
    case ParamSpec::Type::Bool:
        if (auto b = std::get_if<bool>(&value)) return *b;
        if (text && (*text == "true" || *text == "1")) return true;
        if (text && (*text == "false" || *text == "0")) return false;
        return fail();
    case ParamSpec::Type::Int: {
        long long v;
        if (auto i = std::get_if<long long>(&value)) {
            v = *i;
        } else if (text) {
            auto [p, ec] = std::from_chars(text->data(), text->data() + text->size(), v);
            if (ec != std::errc() || p != text->data() + text->size()) return fail();
        } else {
            return fail();
        }
        if (v < spec.min || v > spec.max) return fail();
        return v;
    }
    case ParamSpec::Type::Float: {
        double v;
        if (auto d = std::get_if<double>(&value)) {
            v = *d;
        } else if (auto i = std::get_if<long long>(&value)) {
            v = static_cast<double>(*i);
        } else if (text) {
            std::size_t used = 0;
            try {
                v = std::stod(*text, &used);
            } catch (const std::exception&) {
                return fail();
            }
            if (used != text->size()) return fail();
        } else {
            return fail();
        }
        if (!std::isfinite(v) || v < spec.min || v > spec.max) return fail();
        return v;
    }
    case ParamSpec::Type::Choice:
        if (text) {
            for (const auto& c : spec.choices)
                if (c == *text) return *text;
        }
        return fail();
    }
    return value;
}

}  // namespace

ParameterSet resolveParameters(const std::vector<ParamSpec>& specs, const std::vector<std::pair<std::string, ParamValue>>& given,
                               const std::string& owner, ParameterSource source, const std::vector<std::string>& written) {
    ParameterSet set;
    for (const auto& s : specs) set.set(s.name, s.defaultValue);
    for (std::size_t k = 0; k < given.size(); ++k) {
        const auto& [name, value] = given[k];
        const ParamSpec* spec = nullptr;
        for (const auto& s : specs)
            if (s.name == name) spec = &s;
        if (!spec) {
            std::string known;
            for (const auto& s : specs) known += (known.empty() ? "" : ", ") + s.name;
            throw InputError(owner + ": unknown parameter '" + name + "'" + (known.empty() ? " (it has no parameters)" : " (parameters: " + known + ")"));
        }
        set.set(name, coerce(*spec, value, owner, source, k < written.size() ? written[k] : std::string()));
    }
    return set;
}

std::pair<std::string, ParamValue> parseParamAssignment(const std::string& text) {
    auto eq = text.find('=');
    if (eq == std::string::npos || eq == 0) throw InputError("--param '" + text + "': expected key=value");
    return {text.substr(0, eq), text.substr(eq + 1)};
}

}  // namespace hybridlab
