#include "command_line.hpp"

#include <cctype>
#include <map>

#include "heightpack/core/names.hpp"
#include "heightpack/version.hpp"

#include "exit_codes.hpp"

namespace heightpack::cli {

std::unique_ptr<CommandLine> makeCommandLine() {
    auto line = std::make_unique<CommandLine>();
    CLI::App& app = line->app;
    app.description("heightpack: water height maps to tileable, mip-chained, 4-neighbour packed RGBA32F textures");
    app.name("heightpack");  // the usage lines say heightpack, not the path it was run by
    app.set_version_flag("--version", std::string("heightpack ") + kVersion);
    app.add_flag("--verbose")->description("with --version: the formats heightpack decodes itself, and where its OpenImageIO module is");
    app.require_subcommand(1);
    app.footer(
        "Examples:\n"
        "  heightpack pack examples/maps/swell.png -o out/swell.exr\n"
        "  heightpack normal examples/maps/ripple.png --tile-size 8m --height 0.15m -o out/ripple_n.exr\n"
        "  heightpack fresnel --ior 1.333 -o out/fresnel.exr\n"
        "  heightpack check examples/maps/painted_not_tileable.png --preview out/painted_check.png\n"
        "  heightpack tile examples/maps/painted_not_tileable.png -o out/painted_tiled.png\n"
        "  heightpack info out/swell.exr\n"
        "  heightpack build examples/ocean.toml -o out/ocean\n"
        "Run 'heightpack <command> --help' for a command's options.\n" +
        exitCodesLine() + "\n");
    line->commands.push_back(makePackCommand());
    line->commands.push_back(makeNormalCommand());
    line->commands.push_back(makeFresnelCommand());
    line->commands.push_back(makeCheckCommand());
    line->commands.push_back(makeTileCommand());
    line->commands.push_back(makeSynthCommand());
    line->commands.push_back(makeBuildCommand());
    line->commands.push_back(makeInfoCommand());
    for (auto& command : line->commands) line->subcommands.push_back(command->attach(app));
    return line;
}

namespace {

Error usage(const std::string& what, const std::string& hint) { return {ErrorKind::Internal, {}, what, hint}; }

// The names word was likely meant to be: the nearest within two edits (nearestNames: one, or several
// equally near), else the only one that word extends at a hyphen ("wind-speed": wind) or that extends
// word at one ("tile": tile-size).
std::vector<std::string> meantNames(const std::string& word, const std::vector<std::string>& names) {
    if (std::vector<std::string> nearest = nearestNames(word, names); !nearest.empty()) return nearest;
    std::vector<std::string> meant;
    for (const std::string& n : names) {
        const std::string& shorter = n.size() < word.size() ? n : word;
        const std::string& longer = n.size() < word.size() ? word : n;
        if (longer.size() > shorter.size() && longer.compare(0, shorter.size(), shorter) == 0 && longer[shorter.size()] == '-')
            meant.push_back(n);
    }
    if (meant.size() > 1) meant.clear();  // "foam" would start three options: no better than the list in --help
    return meant;
}

// "did you mean X? " or "did you mean X or Y? " when names hold what word was likely meant to be (each
// quoted between before and after), else "".
std::string suggestion(const std::string& word, const std::vector<std::string>& names, const std::string& before,
                       const std::string& after = "") {
    const std::vector<std::string> meant = meantNames(word, names);
    if (meant.empty()) return {};
    std::string text = "did you mean ";
    for (size_t i = 0; i < meant.size(); ++i)
        text += (i == 0 ? "" : i + 1 == meant.size() ? " or " : ", ") + before + meant[i] + after;
    return text + "? ";
}

// The long names of app's options ("tile-size", without the dashes), in the order they were declared.
std::vector<std::string> longNames(const CLI::App& app) {
    std::vector<std::string> names;
    for (const CLI::Option* o : app.get_options())
        for (const std::string& n : o->get_lnames()) names.push_back(n);
    return names;
}

// The name a message gives an option: its first long name, else its short one.
std::string optionName(const CLI::Option& o) {
    return o.get_lnames().empty() ? "-" + o.get_snames().front() : "--" + o.get_lnames().front();
}

// Judges the option words of args[from, end) against app, CLI11's way of telling an option from a value
// (split_long, split_short; "-2.5" is a value unless app has an option -2): the first unknown one, or
// the second use of an option that takes one value.
std::optional<Error> judgeOptions(const CLI::App& app, const std::vector<std::string>& args, size_t from,
                                  const std::string& where) {
    const std::string help = "see '" + where + " --help'";
    std::map<const CLI::Option*, std::string> given;  // each single-valued option's value so far
    for (size_t i = from; i < args.size(); ++i) {
        const std::string& word = args[i];
        if (word == "--") return std::nullopt;  // the rest are positionals
        std::string name, value;
        std::string typed;  // the option as typed, dashes included
        if (CLI::detail::split_long(word, name, value)) {
            typed = "--" + name;
        } else if (CLI::detail::split_short(word, name, value)) {
            typed = "-" + name;
            if (std::isdigit(static_cast<unsigned char>(name[0])) && !app.get_option_no_throw(typed)) continue;
        } else {
            continue;  // a value or a positional
        }
        const CLI::Option* option = app.get_option_no_throw(typed);
        if (!option) {
            const std::string meant = typed.size() > 2 ? suggestion(name, longNames(app), "--") : std::string();
            // A short option as the whole word: "-.5" is not the option "-.".
            return usage("unknown option " + (typed.size() == 2 ? word : typed), meant + help);
        }
        const bool single = option->get_multi_option_policy() == CLI::MultiOptionPolicy::Throw &&
                            option->get_items_expected_max() == 1 && option->get_items_expected_min() == 1;
        if (!single) continue;
        if (value.empty() && i + 1 < args.size()) value = args[i + 1];
        if (const auto first = given.find(option); first != given.end())
            return usage(optionName(*option) + " was given twice (" + first->second + ", then " + value + ")",
                         "give it once; " + help);
        given.emplace(option, value);
    }
    return std::nullopt;
}

}  // namespace

std::optional<Error> unknownWord(const CommandLine& line, const std::vector<std::string>& args) {
    // The words before the command are heightpack's own options (--help, --version).
    size_t i = 0;
    while (i < args.size() && !args[i].empty() && args[i][0] == '-') ++i;
    if (auto e = judgeOptions(line.app, std::vector<std::string>(args.begin(), args.begin() + i), 0, "heightpack")) return e;
    if (i == args.size()) return std::nullopt;  // no command: CLI11 says one is required, or prints the help
    std::vector<std::string> names;
    for (size_t c = 0; c < line.subcommands.size(); ++c) {
        names.push_back(line.subcommands[c]->get_name());
        if (names.back() == args[i]) return judgeOptions(*line.subcommands[c], args, i + 1, "heightpack " + args[i]);
    }
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
    const std::string meant = suggestion(args[i], names, "'", "'");
    return usage("unknown command '" + args[i] + "'",
                 (meant.empty() ? "the commands are " + list + "; " : meant) + "see 'heightpack --help'");
}

Error usageError(const CommandLine& line, const CLI::ParseError& e) {
    std::string where = "heightpack";
    for (const CLI::App* sub : line.subcommands)
        if (sub->parsed()) where += " " + sub->get_name();
    return usage(e.what(), "see '" + where + " --help'");
}

}  // namespace heightpack::cli
