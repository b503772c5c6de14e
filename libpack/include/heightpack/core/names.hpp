// One table per enum: the name a user types and sees, and a line that describes it. Every printed name,
// every parse of a name (command line, manifest, material.json, file headers, the viewer) and every list
// of choices goes through the enum's table, so a name is written once.
//
// Each enum declares its table next to itself by specialising NameTable:
//
//     template <> struct NameTable<Wrap> {
//         static constexpr EnumName<Wrap> entries[] = {{Wrap::Periodic, "periodic", "..."}, ...};
//     };
//
// The order of the entries is the order allNames lists them in (help texts and error messages).
#pragma once

#include <algorithm>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace heightpack {

template <class E>
struct EnumName {
    E value;
    const char* name;         // lower case, as typed on a command line or written in a file
    const char* description;  // one short line for help texts
};

// Specialised next to each enum (see above); the primary template has no entries on purpose.
template <class E>
struct NameTable;

// The enum's name; "" for a value its table does not list (such as ChannelSelect::Auto).
template <class E>
constexpr const char* nameOf(E value) {
    for (const EnumName<E>& e : NameTable<E>::entries)
        if (e.value == value) return e.name;
    return "";
}

// The value with this exact name (case-sensitive); nullopt for anything else.
template <class E>
constexpr std::optional<E> parseName(std::string_view name) {
    for (const EnumName<E>& e : NameTable<E>::entries)
        if (name == e.name) return e.value;
    return std::nullopt;
}

// Every name in table order: CLI choices, manifest checks, error messages.
template <class E>
std::vector<std::string> allNames() {
    std::vector<std::string> names;
    for (const EnumName<E>& e : NameTable<E>::entries) names.emplace_back(e.name);
    return names;
}

// Every name in table order joined by separator: "periodic, clamp".
template <class E>
std::string joinedNames(std::string_view separator = ", ") {
    std::string text;
    for (const EnumName<E>& e : NameTable<E>::entries) {
        if (!text.empty()) text += separator;
        text += e.name;
    }
    return text;
}

// The value's one-line description; "" for a value its table does not list.
template <class E>
constexpr const char* describe(E value) {
    for (const EnumName<E>& e : NameTable<E>::entries)
        if (e.value == value) return e.description;
    return "";
}

// How many one-letter edits (insert, delete, replace, or swap two neighbours) turn a into b: how far a
// typo is from the word it meant ("tilesize" is 1 from "tile-size", "filtr" 1 from "filter", "chekc" 1
// from "check"). Every "did you mean" (manifest keys, command-line commands and options) asks this.
inline size_t editDistance(std::string_view a, std::string_view b) {
    // Rows i-2, i-1 and i of the table d[i][j] = distance(a[0, i), b[0, j)).
    std::vector<size_t> before(b.size() + 1), above(b.size() + 1), row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) above[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            row[j] = std::min({above[j] + 1, row[j - 1] + 1, above[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) row[j] = std::min(row[j], before[j - 2] + 1);
        }
        std::swap(before, above);
        std::swap(above, row);
    }
    return above[b.size()];
}

// The candidates nearest to word, if within maxDistance edits (editDistance), in the order given: one
// name, or several equally near ("spreadings" is one edit from both "spreading" and "spreading-s");
// empty when none is that near.
inline std::vector<std::string> nearestNames(std::string_view word, const std::vector<std::string>& candidates,
                                             size_t maxDistance = 2) {
    std::vector<std::string> nearest;
    size_t best = maxDistance;
    for (const std::string& candidate : candidates) {
        const size_t d = editDistance(word, candidate);
        if (d > best) continue;
        if (d < best) nearest.clear(), best = d;
        if (std::find(nearest.begin(), nearest.end(), candidate) == nearest.end()) nearest.push_back(candidate);
    }
    return nearest;
}

}  // namespace heightpack
