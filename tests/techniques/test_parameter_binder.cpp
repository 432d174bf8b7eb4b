// Parameters declared once (techniques/parameter_binder.h): a struct's fields bound to their specs
// give the declarations in binding order and are filled from resolved values, groups included; a
// field bound twice, a name declared twice, a field left unbound or a spec of the wrong type for
// its field is refused; and every registered technique's binding passes those checks.
#include <gtest/gtest.h>

#include <set>
#include <stdexcept>

#include "techniques/make_technique_info.h"
#include "techniques/parameter_binder.h"
#include "techniques/technique.h"

namespace hybridlab {
namespace {

enum class Mode { Near, Far, Both };

struct Group {
    int count{};
    bool on{};
};

struct Params {
    float level{};
    Mode mode{};
    Group group;
    long long big{};
    double fine{};
};

ParameterBinder<Group> groupBinder() {
    ParameterBinder<Group> b;
    b.bind(&Group::count, ParamSpec::integer("count", 3, 0, 10, "a count"));
    b.bind(&Group::on, ParamSpec::choice("on", "yes", {"no", "yes"}, "a switch as a choice"), {false, true});
    return b;
}

ParameterBinder<Params> paramsBinder() {
    ParameterBinder<Params> b;
    b.bind(&Params::level, ParamSpec::real("level", 0.25, 0.0, 1.0, "a level"));
    b.bind(&Params::mode, ParamSpec::choice("mode", "far", {"near", "far", "both"}, "a mode"), {Mode::Near, Mode::Far, Mode::Both});
    b.bind(&Params::group, groupBinder());
    b.bind(&Params::big, ParamSpec::integer("big", 7, 0, 1000000000000LL, "a big integer"));
    b.bind(&Params::fine, ParamSpec::real("fine", 0.125, 0.0, 1.0, "a fine number"));
    return b;
}

TEST(ParameterBinder, SpecsComeInBindingOrderWithGroupsInTheirPlace) {
    const ParameterBinder<Params> b = paramsBinder();
    std::vector<std::string> names;
    for (const ParamSpec& s : b.specs()) names.push_back(s.name);
    EXPECT_EQ(names, (std::vector<std::string>{"level", "mode", "count", "on", "big", "fine"}));
    EXPECT_NO_THROW(b.checkEveryFieldBound("test"));
}

TEST(ParameterBinder, FillsEveryFieldFromTheResolvedValues) {
    const ParameterBinder<Params> b = paramsBinder();
    {
        SCOPED_TRACE("defaults");
        const Params p = b.fill(resolveParameters(b.specs(), {}, "test"));
        EXPECT_EQ(p.level, 0.25f);
        EXPECT_EQ(p.mode, Mode::Far);
        EXPECT_EQ(p.group.count, 3);
        EXPECT_TRUE(p.group.on);
        EXPECT_EQ(p.big, 7);
        EXPECT_EQ(p.fine, 0.125);
    }
    {
        SCOPED_TRACE("given, as command-line text");
        const Params p = b.fill(resolveParameters(b.specs(),
                                                  {{"level", std::string("0.75")},
                                                   {"mode", std::string("both")},
                                                   {"count", std::string("9")},
                                                   {"on", std::string("no")},
                                                   {"big", std::string("123456789012")},
                                                   {"fine", std::string("0.5")}},
                                                  "test"));
        EXPECT_EQ(p.level, 0.75f);
        EXPECT_EQ(p.mode, Mode::Both);
        EXPECT_EQ(p.group.count, 9);
        EXPECT_FALSE(p.group.on);
        EXPECT_EQ(p.big, 123456789012LL);
        EXPECT_EQ(p.fine, 0.5);
    }
}

TEST(ParameterBinder, RefusesAFieldBoundTwiceANameDeclaredTwiceAndAFieldLeftUnbound) {
    {
        SCOPED_TRACE("a field bound twice");
        ParameterBinder<Group> b;
        b.bind(&Group::count, ParamSpec::integer("count", 3, 0, 10, ""));
        EXPECT_THROW(b.bind(&Group::count, ParamSpec::integer("other", 3, 0, 10, "")), std::logic_error);
    }
    {
        SCOPED_TRACE("a name declared twice");
        ParameterBinder<Group> b;
        b.bind(&Group::count, ParamSpec::integer("count", 3, 0, 10, ""));
        EXPECT_THROW(b.bind(&Group::on, ParamSpec::boolean("count", true, "")), std::logic_error);
    }
    {
        SCOPED_TRACE("a name declared twice, once in a group");
        ParameterBinder<Params> b;
        b.bind(&Params::big, ParamSpec::integer("count", 3, 0, 10, ""));
        EXPECT_THROW(b.bind(&Params::group, groupBinder()), std::logic_error);
    }
    {
        SCOPED_TRACE("a field left unbound");
        ParameterBinder<Group> b;
        b.bind(&Group::count, ParamSpec::integer("count", 3, 0, 10, ""));
        EXPECT_THROW(b.checkEveryFieldBound("test"), std::logic_error);
        ParameterBinder<Params> outer;
        EXPECT_THROW(outer.bind(&Params::group, b), std::logic_error);  // an incomplete group
        EXPECT_THROW(makeTechniqueInfo("test", "", b, [](const Group&) -> std::unique_ptr<Technique> { return nullptr; }),
                     std::logic_error);
    }
}

TEST(ParameterBinder, RefusesASpecOfAnotherTypeThanItsField) {
    ParameterBinder<Params> b;
    EXPECT_THROW(b.bind(&Params::level, ParamSpec::integer("level", 1, 0, 2, "")), std::logic_error);
    EXPECT_THROW(b.bind(&Params::big, ParamSpec::real("big", 1, 0, 2, "")), std::logic_error);
    EXPECT_THROW(b.bind(&Params::mode, ParamSpec::choice("mode", "near", {"near", "far", "both"}, ""), {Mode::Near, Mode::Far}),
                 std::logic_error);  // a value for each choice
    EXPECT_THROW(b.bind(&Params::mode, ParamSpec::real("mode", 1, 0, 2, ""), {Mode::Near}), std::logic_error);
}

TEST(ParameterBinder, EveryRegisteredTechniqueBindsEachParameterToOneField) {
    // Building the registry runs every technique's binding checks (they throw std::logic_error).
    ASSERT_NO_THROW(registeredTechniques());
    for (const TechniqueInfo& info : registeredTechniques()) {
        SCOPED_TRACE(info.name);
        std::set<std::string> names;
        for (const ParamSpec& s : info.parameters) EXPECT_TRUE(names.insert(s.name).second) << s.name;
        EXPECT_NO_THROW(createTechnique(info.name, {}));
    }
}

}  // namespace
}  // namespace hybridlab
