#pragma once
// Checked reading of TOML input (scene files, experiment configs). Every error names the file,
// the line and column of the offending value (toml++ records them), the key's full path, and
// what was expected; keys nobody asked for are errors too (rejectUnknownKeys).
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <toml++/toml.h>

#include "common/core/number_check.h"

namespace hybridlab {

// "a, b, c": how the messages list choices and known keys.
std::string commaSeparated(const std::vector<std::string>& items);

class TomlTable;

// Parses a file (input_file.h's checks first); a syntax error becomes an InputError at its position.
class TomlDocument {
public:
    explicit TomlDocument(const std::filesystem::path& file);
    TomlTable root() const;
    const std::filesystem::path& file() const { return file_; }

private:
    std::filesystem::path file_;
    std::shared_ptr<const std::string> text_;  // the file as read: messages quote values as written
    std::shared_ptr<toml::table> table_;
};

class TomlTable {
public:
    TomlTable(const toml::table& table, std::string path, std::filesystem::path file, std::shared_ptr<const std::string> text);

    const std::string& path() const { return path_; }
    const std::filesystem::path& file() const { return file_; }
    bool has(const std::string& key) const;

    std::string string(const std::string& key, const std::string& fallback) const;
    std::string requiredString(const std::string& key) const;
    // One of `choices`; the error lists them.
    std::string choice(const std::string& key, const std::string& fallback, const std::vector<std::string>& choices) const;
    double number(const std::string& key, double fallback, NumberRange range = {}) const;
    double requiredNumber(const std::string& key, NumberRange range = {}) const;
    int integer(const std::string& key, int fallback, int min, int max) const;
    // `n`, a value at `key` (or an element of its array), as an integer in [min, max]; a value
    // outside is an error at `key`, never wrapped.
    int integerValue(const std::string& key, const toml::node& n, int min, int max) const;
    bool boolean(const std::string& key, bool fallback) const;
    glm::vec2 vec2(const std::string& key, glm::vec2 fallback) const;
    glm::vec3 vec3(const std::string& key, glm::vec3 fallback) const;
    glm::vec3 requiredVec3(const std::string& key) const;
    // A number s means (s, s, s); else an array of three.
    glm::vec3 scalarOrVec3(const std::string& key, glm::vec3 fallback) const;
    std::vector<std::string> stringArray(const std::string& key) const;
    // An array of strings, each one of `choices` (as `choice`); `fallback` when the key is absent.
    std::vector<std::string> choiceArray(const std::string& key, const std::vector<std::string>& fallback,
                                         const std::vector<std::string>& choices) const;

    std::optional<TomlTable> table(const std::string& key) const;
    // An array of tables ([[key]] or key = [{...}, ...]); empty when absent.
    std::vector<TomlTable> tableArray(const std::string& key) const;
    // The sub-tables of table `key` by name ([key.name] sections), in file order.
    std::vector<std::pair<std::string, TomlTable>> namedTables(const std::string& key) const;

    // Every key of this table, in file order (each counts as read), and a value by key, read as it
    // is (for callers that take lists or mixed types, e.g. experiment sweeps); node() fails
    // when the key is missing.
    std::vector<std::string> keys() const;
    const toml::node& node(const std::string& key) const;

    // Every key of this table that no getter asked for is an error.
    void rejectUnknownKeys() const;

    // A value as the file writes it ("2.0", "1e400", "\"3\""), for messages: a number converted to
    // a double would print 2, inf.
    std::string written(const toml::node& n) const;

    // An error at `key`'s value (or at the table when the key is absent).
    [[noreturn]] void fail(const std::string& key, const std::string& message) const;
    [[noreturn]] void failHere(const std::string& message) const;

private:
    const toml::node* get(const std::string& key) const;
    glm::vec3 parseVec3(const std::string& key, const toml::node& node) const;
    double parseNumber(const std::string& key, const toml::node& node) const;
    // parseNumber within a float's range (glm vectors are float: 1e39 would become inf).
    float parseFloat(const std::string& key, const toml::node& node) const;
    std::string keyPath(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

    const toml::table* table_;
    std::string path_;
    std::filesystem::path file_;
    std::shared_ptr<const std::string> text_;
    mutable std::set<std::string> used_;
    mutable std::set<std::string> asked_;  // keys has() checked: valid keys, listed in unknown-key errors
};

}  // namespace hybridlab
