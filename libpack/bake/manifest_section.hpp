// Internal: one table of a manifest as the parser reads it (manifest.cpp): typed getters that remember
// every key asked for, range checks, and errors that name file:line and the key's full path.
#pragma once

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "heightpack/core/names.hpp"
#include "heightpack/core/result.hpp"

#include "manifest_keys.hpp"

namespace heightpack::detail {

// The library's neutral words for Fix::ManifestReference; each shell names where the reference is.
inline constexpr const char* kHint = "see manifest.md in heightpack's documentation for every key";

// An error in a manifest's key or value, pointing at the reference: first is what to do before reading
// it ("did you mean 'source'?"), or empty.
inline Error referenced(const std::string& where, const std::string& what, const std::string& first = {}) {
    return withFix(badInput(where, what, first.empty() ? kHint : first + " " + kHint), Fix::ManifestReference, {first});
}

// A key or value as quoted in a message: long ones are cut, so an error stays one readable line.
inline std::string shorten(const std::string& text) {
    constexpr size_t kMax = 64;
    return text.size() <= kMax ? text : text.substr(0, kMax) + "... (" + std::to_string(text.size()) + " characters)";
}

inline int lineOf(const toml::node& node) { return static_cast<int>(node.source().begin.line); }

// One table of the manifest, of a kind that takes the keys keysOf(kind) lists. Every key read is
// remembered, so finish() can reject the ones nobody asked for; every error names file:line and the
// key's full path.
class Section {
public:
    Section(const toml::table& table, std::string prefix, const std::string& file, ManifestTable kind)
        : table_(table), prefix_(std::move(prefix)), file_(file), kind_(kind) {}

    int line() const { return std::max(1, lineOf(table_)); }
    const std::string& prefix() const { return prefix_; }
    ManifestTable kind() const { return kind_; }
    std::string key(const std::string& k) const { return shorten(prefix_.empty() ? k : prefix_ + "." + k); }

    // The error at line: with a hint of its own, or without one pointing at the reference.
    Error error(int line, const std::string& what, const std::string& hint = {}) const {
        const std::string where = file_ + ":" + std::to_string(line);
        return hint.empty() ? referenced(where, what) : badInput(where, what, hint);
    }
    Error error(const std::string& k, const std::string& what, const std::string& hint = {}) const {
        const toml::node* n = table_.get(k);
        return error(n ? lineOf(*n) : line(), "key '" + key(k) + "' " + what, hint);
    }
    // A key that must be there and is not (first: what to do, before the reference).
    Error missing(const std::string& k, const std::string& first = {}) const {
        return referenced(file_ + ":" + std::to_string(line()), "missing key '" + key(k) + "'", first);
    }

    const toml::node* find(const std::string& k) {
        // A key the parser reads must be one its table takes (manifest_keys.cpp), or rejectUnknownKeys
        // would refuse it before the parser ever saw it: a bug to report, whatever the manifest.
        const auto& keys = keysOf(kind_);
        if (std::find(keys.begin(), keys.end(), k) == keys.end())
            throw std::logic_error("the manifest parser reads '" + key(k) + "', which keysOf does not list");
        known_.insert(k);
        return table_.get(k);
    }
    // Unknown keys were rejected before any table was read (rejectUnknownKeys), so a key missing here
    // is not a misspelling's doing.
    const toml::node& require(const std::string& k) {
        const toml::node* n = find(k);
        if (n) return *n;
        throw missing(k);
    }

    double number(const std::string& k, std::optional<double> fallback, double lo, double hi, bool openLow = false) {
        const toml::node* n = fallback ? find(k) : &require(k);
        if (!n) return *fallback;
        if (!n->is_number()) throw error(k, "must be a number, not " + typeName(*n));
        const double v = n->value<double>().value_or(NAN);
        if (!std::isfinite(v) || v < lo || v > hi || (openLow && v == lo))
            throw error(k, "is " + formatNumber(v) + ", but must be " + rangeText(lo, hi, openLow));
        return v;
    }
    int integer(const std::string& k, int fallback, int lo, int hi) {
        const toml::node* n = find(k);
        if (!n) return fallback;
        if (!n->is_integer()) throw error(k, "must be a whole number, not " + typeName(*n));
        const long long v = n->value<long long>().value_or(0);
        if (v < lo || v > hi)
            throw error(k, "is " + std::to_string(v) + ", but must be " + std::to_string(lo) + " to " + std::to_string(hi));
        return static_cast<int>(v);
    }
    std::optional<std::string> text(const std::string& k) {
        const toml::node* n = find(k);
        if (!n) return std::nullopt;
        if (!n->is_string()) throw error(k, "must be a string, not " + typeName(*n));
        return n->value<std::string>().value_or("");
    }
    std::string requiredText(const std::string& k) {
        require(k);
        return *text(k);
    }
    std::optional<bool> boolean(const std::string& k) {
        const toml::node* n = find(k);
        if (!n) return std::nullopt;
        if (!n->is_boolean()) throw error(k, "must be true or false, not " + typeName(*n));
        return n->value<bool>().value_or(false);
    }
    // One of the names in E's table.
    template <class E>
    E choice(const std::string& k, E fallback) {
        const std::optional<std::string> v = text(k);
        if (!v) return fallback;
        if (const std::optional<E> e = parseName<E>(*v)) return *e;
        throw error(k, "is '" + shorten(*v) + "', but must be one of: " + joinedNames<E>());
    }
    std::vector<double> numbers(const std::string& k, std::vector<double> fallback, size_t count, double lo, double hi) {
        const toml::node* n = find(k);
        if (!n) return fallback;
        const toml::array* a = n->as_array();
        if (!a || a->size() != count) throw error(k, "must be an array of " + std::to_string(count) + " numbers");
        std::vector<double> out;
        for (const toml::node& e : *a) {
            const double v = e.is_number() ? e.value<double>().value_or(NAN) : NAN;
            if (!std::isfinite(v) || v < lo || v > hi)
                throw error(k, "must hold " + std::to_string(count) + " numbers, each " + rangeText(lo, hi, false));
            out.push_back(v);
        }
        return out;
    }
    const toml::table* table(const std::string& k) {
        const toml::node* n = find(k);
        if (!n) return nullptr;
        if (!n->is_table()) throw error(k, "must be a table [" + key(k) + "], not " + typeName(*n));
        return n->as_table();
    }
    // Rejects any key that was never asked for (a key the table takes that this parse left unread is
    // a bug, as rejectUnknownKeys has let it through), suggesting the nearest one that was.
    void finish() const {
        for (auto&& [k, node] : table_) {
            const std::string name(k.str());
            if (!known_.count(name)) throw unknownKey(name, node, {known_.begin(), known_.end()});
        }
    }
    // The line and error of this table's first key (in file order) that its kind does not take.
    std::optional<std::pair<int, Error>> firstUnknownKey() const {
        std::optional<std::pair<int, Error>> first;
        const auto& keys = keysOf(kind_);
        for (auto&& [k, node] : table_) {
            const std::string name(k.str());
            if (std::find(keys.begin(), keys.end(), name) != keys.end()) continue;
            if (!first || lineOf(node) < first->first)
                first.emplace(lineOf(node), unknownKey(name, node, {keys.begin(), keys.end()}));
        }
        return first;
    }

    static std::string typeName(const toml::node& n) {
        switch (n.type()) {
            case toml::node_type::string: return "a string";
            case toml::node_type::integer:
            case toml::node_type::floating_point: return "a number";
            case toml::node_type::boolean: return "true/false";
            case toml::node_type::array: return "an array";
            case toml::node_type::table: return "a table";
            default: return "a date or time";
        }
    }
    static std::string formatNumber(double v) {
        char text[32];
        std::snprintf(text, sizeof text, "%g", v);
        return text;
    }
    static std::string rangeText(double lo, double hi, bool openLow) {
        if (std::isinf(hi)) return std::string(openLow ? "greater than " : "at least ") + formatNumber(lo);
        return std::string(openLow ? "greater than " : "from ") + formatNumber(lo) + (openLow ? " and at most " : " to ") +
               formatNumber(hi);
    }

private:
    // The error for key name, at node, suggesting the nearest of candidates (within two edits).
    Error unknownKey(const std::string& name, const toml::node& node, const std::vector<std::string>& candidates) const {
        const std::vector<std::string> near = nearestNames(name, candidates);  // heightpack/core/names.hpp
        const std::string best = near.empty() ? std::string() : near.front();
        const std::string where = prefix_.empty() ? "at the top level" : "in [" + prefix_ + "]";
        return referenced(file_ + ":" + std::to_string(lineOf(node)), "unknown key '" + key(name) + "' " + where,
                          best.empty() ? "" : "did you mean '" + best + "'?");
    }

    const toml::table& table_;
    std::string prefix_;
    const std::string& file_;
    ManifestTable kind_;
    std::set<std::string> known_;
};

}  // namespace heightpack::detail
