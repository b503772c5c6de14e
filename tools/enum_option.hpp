// An option bound straight to an enum field of an option struct: the names a user may type are the enum's
// name table (heightpack/core/names.hpp), or the part of it the command accepts, checked and converted in
// one step, so no command holds the choice as text or parses it a second time.
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "heightpack/core/names.hpp"

namespace heightpack::cli {

// Checks a name against `allowed` and turns it into the enum's underlying integer, which is how CLI11
// reads an enum field; a name outside them is a usage error in CLI11's words.
template <class E>
CLI::Validator enumNames(std::vector<E> allowed) {
    if (allowed.empty())
        for (const EnumName<E>& e : NameTable<E>::entries) allowed.push_back(e.value);
    std::string names;
    for (E value : allowed) names += (names.empty() ? "" : ",") + std::string(nameOf(value));
    return CLI::Validator(
        [allowed, names](std::string& text) -> std::string {
            for (E value : allowed)
                if (text == nameOf(value)) {
                    text = std::to_string(static_cast<long long>(value));
                    return {};
                }
            return text + " not in {" + names + "}";
        },
        "{" + names + "}", "name");
}

// --flag NAME, one of `allowed` (default: every name in E's table). The help lists the names and shows
// the field's value when attached as the default; a name outside them is a usage error (exit 2) in
// CLI11's words: "--wrap: foo not in {periodic,clamp}".
template <class E>
CLI::Option* addEnumOption(CLI::App& cmd, const std::string& flags, E& field, const std::string& description,
                           std::vector<E> allowed = {}) {
    return cmd.add_option(flags, field, description)->transform(enumNames<E>(std::move(allowed)))->type_name("TEXT")->default_str(nameOf(field));
}

// --flag NAME[,NAME...], repeatable: names of E's table, into a list in the order given.
template <class E>
CLI::Option* addEnumOption(CLI::App& cmd, const std::string& flags, std::vector<E>& field, const std::string& description) {
    return cmd.add_option(flags, field, description)->transform(enumNames<E>({}))->type_name("TEXT")->delimiter(',');
}

}  // namespace heightpack::cli
