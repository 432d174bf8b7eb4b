#include "common/core/toml_reader.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string_view>

#include "common/core/input_error.h"
#include "common/core/input_file.h"
#include "common/core/number_check.h"

namespace hybridlab {
namespace fs = std::filesystem;

namespace {

const char* typeName(const toml::node& n) {
    switch (n.type()) {
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a number";
    case toml::node_type::boolean: return "a boolean";
    default: return "a date or time";
    }
}

}  // namespace

std::string commaSeparated(const std::vector<std::string>& items) {
    std::string s;
    for (std::size_t i = 0; i < items.size(); ++i) s += (i ? ", " : "") + items[i];
    return s;
}

TomlDocument::TomlDocument(const fs::path& file) : file_(file) {
    text_ = std::make_shared<const std::string>(readInputFile(file, "a TOML file"));
    try {
        table_ = std::make_shared<toml::table>(toml::parse(*text_, file.string()));
    } catch (const toml::parse_error& e) {
        throw InputError::at(file, static_cast<int>(e.source().begin.line), static_cast<int>(e.source().begin.column),
                             "TOML syntax error: " + std::string(e.description()));
    }
}

TomlTable TomlDocument::root() const { return TomlTable(*table_, "", file_, text_); }

TomlTable::TomlTable(const toml::table& table, std::string path, fs::path file, std::shared_ptr<const std::string> text)
    : table_(&table), path_(std::move(path)), file_(std::move(file)), text_(std::move(text)) {}

bool TomlTable::has(const std::string& key) const {
    asked_.insert(key);
    return table_->contains(key);
}

const toml::node* TomlTable::get(const std::string& key) const {
    used_.insert(key);
    return table_->get(key);
}

void TomlTable::fail(const std::string& key, const std::string& message) const {
    const toml::node* n = table_->get(key);
    const auto& src = n ? n->source() : table_->source();
    throw InputError::at(file_, static_cast<int>(src.begin.line), static_cast<int>(src.begin.column),
                         keyPath(key) + ": " + message);
}

void TomlTable::failHere(const std::string& message) const {
    const auto& src = table_->source();
    throw InputError::at(file_, static_cast<int>(src.begin.line), static_cast<int>(src.begin.column),
                         (path_.empty() ? std::string() : path_ + ": ") + message);
}

std::string TomlTable::string(const std::string& key, const std::string& fallback) const {
    const toml::node* n = get(key);
    if (!n) return fallback;
    if (!n->is_string()) fail(key, std::string("expected a string, got ") + typeName(*n));
    return n->as_string()->get();
}

std::string TomlTable::requiredString(const std::string& key) const {
    if (!has(key)) fail(key, "missing (expected a string)");
    return string(key, "");
}

std::string TomlTable::choice(const std::string& key, const std::string& fallback, const std::vector<std::string>& choices) const {
    std::string v = string(key, fallback);
    for (const auto& c : choices)
        if (c == v) return v;
    fail(key, "'" + v + "' is not one of: " + commaSeparated(choices));
}

double TomlTable::parseNumber(const std::string& key, const toml::node& n) const {
    double v;
    if (auto i = n.as_integer()) v = static_cast<double>(i->get());
    else if (auto f = n.as_floating_point()) v = f->get();
    else fail(key, std::string("expected a number, got ") + typeName(n));
    if (!std::isfinite(v)) fail(key, "expected a finite number, got " + written(n));
    return v;
}

float TomlTable::parseFloat(const std::string& key, const toml::node& n) const {
    const double v = parseNumber(key, n);
    constexpr double kMax = std::numeric_limits<float>::max();
    if (std::string problem = numberProblem(v, -kMax, kMax, written(n)); !problem.empty()) fail(key, problem + " (beyond a float's range)");
    return static_cast<float>(v);
}

double TomlTable::number(const std::string& key, double fallback, NumberRange range) const {
    const toml::node* n = get(key);
    if (!n) return fallback;
    double v = parseNumber(key, *n);
    if (std::string problem = numberProblem(v, range.min, range.max, written(*n)); !problem.empty()) fail(key, problem);
    return v;
}

double TomlTable::requiredNumber(const std::string& key, NumberRange range) const {
    if (!has(key)) fail(key, "missing (expected a number)");
    return number(key, 0.0, range);
}

int TomlTable::integer(const std::string& key, int fallback, int min, int max) const {
    const toml::node* n = get(key);
    return n ? integerValue(key, *n, min, max) : fallback;
}

int TomlTable::integerValue(const std::string& key, const toml::node& n, int min, int max) const {
    auto i = n.as_integer();
    if (!i) fail(key, std::string("expected an integer, got ") + typeName(n));
    if (std::string problem = integerProblem(i->get(), min, max, written(n)); !problem.empty()) fail(key, problem);
    return static_cast<int>(i->get());
}

bool TomlTable::boolean(const std::string& key, bool fallback) const {
    const toml::node* n = get(key);
    if (!n) return fallback;
    if (!n->is_boolean()) fail(key, std::string("expected true or false, got ") + typeName(*n));
    return n->as_boolean()->get();
}

glm::vec3 TomlTable::parseVec3(const std::string& key, const toml::node& n) const {
    auto a = n.as_array();
    if (!a || a->size() != 3) fail(key, std::string("expected an array of 3 numbers, got ") + (a ? "an array of " + std::to_string(a->size()) : typeName(n)));
    return {parseFloat(key, *a->get(0)), parseFloat(key, *a->get(1)), parseFloat(key, *a->get(2))};
}

glm::vec2 TomlTable::vec2(const std::string& key, glm::vec2 fallback) const {
    const toml::node* n = get(key);
    if (!n) return fallback;
    auto a = n->as_array();
    if (!a || a->size() != 2) fail(key, std::string("expected an array of 2 numbers, got ") + (a ? "an array of " + std::to_string(a->size()) : typeName(*n)));
    return {parseFloat(key, *a->get(0)), parseFloat(key, *a->get(1))};
}

glm::vec3 TomlTable::vec3(const std::string& key, glm::vec3 fallback) const {
    const toml::node* n = get(key);
    return n ? parseVec3(key, *n) : fallback;
}

glm::vec3 TomlTable::requiredVec3(const std::string& key) const {
    if (!has(key)) fail(key, "missing (expected an array of 3 numbers)");
    return vec3(key, glm::vec3(0.0f));
}

glm::vec3 TomlTable::scalarOrVec3(const std::string& key, glm::vec3 fallback) const {
    const toml::node* n = get(key);
    if (!n) return fallback;
    if (n->is_number()) return glm::vec3(parseFloat(key, *n));
    return parseVec3(key, *n);
}

std::vector<std::string> TomlTable::stringArray(const std::string& key) const {
    const toml::node* n = get(key);
    std::vector<std::string> out;
    if (!n) return out;
    auto a = n->as_array();
    if (!a) fail(key, std::string("expected an array of strings, got ") + typeName(*n));
    for (const auto& e : *a) {
        if (!e.is_string()) fail(key, std::string("expected an array of strings, found ") + typeName(e));
        out.push_back(e.as_string()->get());
    }
    return out;
}

std::vector<std::string> TomlTable::choiceArray(const std::string& key, const std::vector<std::string>& fallback,
                                                const std::vector<std::string>& choices) const {
    if (!has(key)) return fallback;
    std::vector<std::string> values = stringArray(key);
    for (const auto& v : values)
        if (std::find(choices.begin(), choices.end(), v) == choices.end()) fail(key, "'" + v + "' is not one of: " + commaSeparated(choices));
    return values;
}

std::optional<TomlTable> TomlTable::table(const std::string& key) const {
    const toml::node* n = get(key);
    if (!n) return std::nullopt;
    if (!n->is_table()) fail(key, std::string("expected a table, got ") + typeName(*n));
    return TomlTable(*n->as_table(), keyPath(key), file_, text_);
}

std::vector<TomlTable> TomlTable::tableArray(const std::string& key) const {
    const toml::node* n = get(key);
    std::vector<TomlTable> out;
    if (!n) return out;
    auto a = n->as_array();
    if (!a) fail(key, std::string("expected an array of tables, got ") + typeName(*n));
    for (std::size_t i = 0; i < a->size(); ++i) {
        const toml::node& e = *a->get(i);
        if (!e.is_table()) fail(key, "element " + std::to_string(i) + ": expected a table, got " + typeName(e));
        out.emplace_back(*e.as_table(), keyPath(key) + "[" + std::to_string(i) + "]", file_, text_);
    }
    return out;
}

std::vector<std::pair<std::string, TomlTable>> TomlTable::namedTables(const std::string& key) const {
    std::vector<std::pair<std::string, TomlTable>> out;
    auto t = table(key);
    if (!t) return out;
    for (auto&& [k, v] : *t->table_) {
        std::string name(k.str());
        t->used_.insert(name);
        if (!v.is_table()) t->fail(name, std::string("expected a table, got ") + typeName(v));
        out.emplace_back(name, TomlTable(*v.as_table(), t->keyPath(name), file_, text_));
    }
    // toml++ keeps keys sorted; order by position in the file instead.
    std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
        return a.second.table_->source().begin.line < b.second.table_->source().begin.line;
    });
    return out;
}

std::vector<std::string> TomlTable::keys() const {
    // (line, column): inline tables hold several keys on one line.
    std::vector<std::pair<std::pair<std::size_t, std::size_t>, std::string>> byLine;
    for (auto&& [k, v] : *table_) byLine.emplace_back(std::make_pair(k.source().begin.line, k.source().begin.column), std::string(k.str()));
    std::stable_sort(byLine.begin(), byLine.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<std::string> out;
    for (auto& [line, key] : byLine) {
        used_.insert(key);
        out.push_back(std::move(key));
    }
    return out;
}

const toml::node& TomlTable::node(const std::string& key) const {
    const toml::node* n = get(key);
    if (!n) fail(key, "missing");
    return *n;
}

std::string TomlTable::written(const toml::node& n) const {
    if (auto s = n.as_string()) return "\"" + s->get() + "\"";
    // The value's text from its first character to the next delimiter: numbers, booleans and dates
    // hold none of these. Columns count code points.
    const toml::source_position at = n.source().begin;
    std::size_t i = 0;
    for (std::size_t line = 1; line < at.line && i < text_->size(); ++i)
        if ((*text_)[i] == '\n') ++line;
    for (std::size_t column = 1; column < at.column && i < text_->size(); ++i)
        if ((static_cast<unsigned char>((*text_)[i]) & 0xC0) != 0x80) ++column;
    while (i < text_->size() && (static_cast<unsigned char>((*text_)[i]) & 0xC0) == 0x80) ++i;
    std::size_t end = i;
    while (end < text_->size() && std::string_view(" \t\r\n,]}#").find((*text_)[end]) == std::string_view::npos) ++end;
    if (at.line != 0 && end > i) return text_->substr(i, end - i);
    // A value without a position (none that the parser makes): as its type prints it.
    if (auto f = n.as_floating_point()) return formatNumber(f->get());
    if (auto k = n.as_integer()) return std::to_string(k->get());
    if (auto b = n.as_boolean()) return b->get() ? "true" : "false";
    return typeName(n);
}

void TomlTable::rejectUnknownKeys() const {
    for (auto&& [k, v] : *table_) {
        std::string name(k.str());
        if (used_.count(name)) continue;
        std::set<std::string> valid = used_;
        valid.insert(asked_.begin(), asked_.end());
        std::vector<std::string> known(valid.begin(), valid.end());
        const auto& src = k.source().begin.line ? k.source() : v.source();
        throw InputError::at(file_, static_cast<int>(src.begin.line), static_cast<int>(src.begin.column),
                             keyPath(name) + ": unknown key" + (known.empty() ? std::string() : " (expected one of: " + commaSeparated(known) + ")"));
    }
}

}  // namespace hybridlab
