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

}  // namespace heightpack
