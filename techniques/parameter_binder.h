#pragma once
// Parameters declared once. A technique's parameters (or a group several techniques share,
// techniques/shared/*_parameters.h) are the fields of an aggregate struct; a ParameterBinder binds
// each field to its spec (name, type, default, range or choices, description) in one list. The
// binder gives both the specs a technique declares (TechniqueInfo::parameters, in binding order)
// and the struct filled from the resolved values, so a name is written once and the technique's
// constructor reads typed fields. Binding checks, when the registry is built, that every spec is
// bound to exactly one field and every field to one spec (or one group).
#include <cstddef>
#include <functional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "techniques/parameters.h"

namespace hybridlab {

namespace parameter_binding {

// Converts to any field type; only named in unevaluated contexts (fieldCount).
struct AnyField {
    template <class T>
    operator T() const;
};

template <class T, std::size_t... I>
constexpr bool initializableWith(std::index_sequence<I...>) {
    return requires { T{(void(I), AnyField{})...}; };
}

// The number of an aggregate's fields: the largest n for which T{x_1, ..., x_n} compiles (a
// nested struct is one field; as Boost.PFR counts them).
template <class T, std::size_t N = 0>
constexpr std::size_t fieldCount() {
    if constexpr (initializableWith<T>(std::make_index_sequence<N + 1>{})) return fieldCount<T, N + 1>();
    else return N;
}

template <class T>
constexpr bool isRealField = std::is_floating_point_v<T>;
template <class T>
constexpr bool isIntegerField = std::is_integral_v<T> && !std::is_same_v<T, bool>;

}  // namespace parameter_binding

template <class Params>
class ParameterBinder {
    static_assert(std::is_aggregate_v<Params> && std::is_default_constructible_v<Params>,
                  "a parameters struct is an aggregate of its fields");

public:
    // A Bool, Int or Float spec bound to a field of that kind (bool, an integer, a floating-point type).
    template <class Field>
    ParameterBinder& bind(Field Params::*field, ParamSpec spec) {
        using namespace parameter_binding;
        static_assert(std::is_same_v<Field, bool> || isIntegerField<Field> || isRealField<Field>,
                      "a Choice is bound with its values: bind(field, spec, {value per choice})");
        constexpr ParamSpec::Type expected =
            std::is_same_v<Field, bool> ? ParamSpec::Type::Bool : isIntegerField<Field> ? ParamSpec::Type::Int : ParamSpec::Type::Float;
        if (spec.type != expected)
            throw std::logic_error("parameter '" + spec.name + "': its field's type does not match the spec's (" + spec.typeDescription() + ")");
        const std::string name = spec.name;
        add(field, {std::move(spec)}, [field, name](Params& p, const ParameterSet& values) {
            if constexpr (std::is_same_v<Field, bool>) p.*field = values.getBool(name);
            else if constexpr (isIntegerField<Field>) p.*field = static_cast<Field>(values.getInt(name));
            else p.*field = static_cast<Field>(values.getFloat(name));
        });
        return *this;
    }

    // A Choice spec bound to a field that takes values[i] for spec.choices[i] (an enum, a bool).
    template <class Field>
    ParameterBinder& bind(Field Params::*field, ParamSpec spec, std::type_identity_t<std::vector<Field>> values) {
        if (spec.type != ParamSpec::Type::Choice || values.size() != spec.choices.size())
            throw std::logic_error("parameter '" + spec.name + "': a choice binds one value for each of its " +
                                   std::to_string(spec.choices.size()) + " choices, got " + std::to_string(values.size()));
        const std::string name = spec.name;
        std::vector<std::string> choices = spec.choices;
        add(field, {std::move(spec)}, [field, name, choices = std::move(choices), values = std::move(values)](Params& p, const ParameterSet& set) {
            const std::string& chosen = set.getChoice(name);
            for (std::size_t i = 0; i < choices.size(); ++i)
                if (choices[i] == chosen) p.*field = values[i];
        });
        return *this;
    }

    // A group's parameters (its own binder, complete) bound to a field of the group's struct; its
    // specs take their place in this list.
    template <class Group>
    ParameterBinder& bind(Group Params::*field, const ParameterBinder<Group>& group) {
        group.checkEveryFieldBound("a parameter group");
        add(field, group.specs(), [field, group](Params& p, const ParameterSet& values) { p.*field = group.fill(values); });
        return *this;
    }

    // In binding order.
    const std::vector<ParamSpec>& specs() const { return specs_; }

    // The struct from resolved values (resolveParameters against specs(): every name present).
    Params fill(const ParameterSet& values) const {
        Params p{};
        for (const auto& f : fillers_) f(p, values);
        return p;
    }

    // Throws std::logic_error naming `owner` unless every field of Params is bound (once: a field
    // bound twice throws at bind()).
    void checkEveryFieldBound(const std::string& owner) const {
        constexpr std::size_t fields = parameter_binding::fieldCount<Params>();
        if (fields != fieldRanges_.size())
            throw std::logic_error(owner + ": its parameters struct has " + std::to_string(fields) + " fields, " +
                                   std::to_string(fieldRanges_.size()) + " bound to parameters");
    }

private:
    struct ByteRange {
        std::ptrdiff_t begin, end;
    };

    template <class Field>
    void add(Field Params::*field, const std::vector<ParamSpec>& specs, std::function<void(Params&, const ParameterSet&)> filler) {
        const Params probe{};
        const auto* base = reinterpret_cast<const char*>(&probe);
        const auto* at = reinterpret_cast<const char*>(&(probe.*field));
        const ByteRange range{at - base, at - base + static_cast<std::ptrdiff_t>(sizeof(Field))};
        for (const ByteRange& r : fieldRanges_)
            if (range.begin < r.end && r.begin < range.end)
                throw std::logic_error("parameter '" + (specs.empty() ? std::string("?") : specs.front().name) +
                                       "': its field is already bound to another parameter");
        for (const ParamSpec& s : specs)
            for (const ParamSpec& known : specs_)
                if (known.name == s.name) throw std::logic_error("parameter '" + s.name + "' is declared twice");
        fieldRanges_.push_back(range);
        specs_.insert(specs_.end(), specs.begin(), specs.end());
        fillers_.push_back(std::move(filler));
    }

    std::vector<ParamSpec> specs_;
    std::vector<ByteRange> fieldRanges_;  // per bound field, in Params
    std::vector<std::function<void(Params&, const ParameterSet&)>> fillers_;
};

}  // namespace hybridlab
