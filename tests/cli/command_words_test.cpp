// Words a new user gets wrong (issue 35, items 5 and 7): a misspelt command or option is named as itself,
// with the one it was likely meant to be, before anything else is judged; an option given twice is said
// in plain words. The examples run the binary; the property over every option asks the command line
// the binary parses (tools/command_line.hpp), in process: thousands of misspellings in a few milliseconds.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include "command_line.hpp"

#include "support/heightpack_process.hpp"
#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

// The usage contract for a word heightpack does not know: exit 2, one line naming the word and, when
// meant is not empty, "did you mean <meant>?"; nothing about required options or unexpected words.
void expectUnknownWord(const ProcessResult& run, const std::string& word, const std::string& meant) {
    EXPECT_EQ(run.code, 2) << run.err;
    expectOneLineError(run, "");
    EXPECT_NE(run.err.find(word), std::string::npos) << run.err;
    if (!meant.empty()) {
        EXPECT_NE(run.err.find("did you mean " + meant + "?"), std::string::npos) << run.err;
    }
    for (const char* misleading : {"required", "not expected", "At Most"})
        EXPECT_EQ(run.err.find(misleading), std::string::npos) << run.err;
}

// Each word made from name by dropping one letter or swapping two neighbouring ones, except name itself.
std::set<std::string> typosOf(const std::string& name) {
    std::set<std::string> typos;
    for (size_t i = 0; i < name.size(); ++i) typos.insert(name.substr(0, i) + name.substr(i + 1));
    for (size_t i = 0; i + 1 < name.size(); ++i) {
        std::string swapped = name;
        std::swap(swapped[i], swapped[i + 1]);
        typos.insert(swapped);
    }
    typos.erase(name);
    return typos;
}

// The names a hint suggests: "did you mean --a? ..." or "did you mean --a or --b? ...".
std::vector<std::string> suggested(const std::string& hint) {
    const std::string start = "did you mean ";
    if (hint.rfind(start, 0) != 0) return {};
    std::string list = hint.substr(start.size(), hint.find("? ") - start.size());
    for (size_t at = list.find(" or "); at != std::string::npos; at = list.find(" or ")) list.replace(at, 4, ", ");
    std::vector<std::string> names;
    for (size_t from = 0;;) {
        const size_t comma = list.find(", ", from);
        names.push_back(list.substr(from, comma - from));
        if (comma == std::string::npos) return names;
        from = comma + 2;
    }
}

}  // namespace

TEST(CommandWords, TheIssuesFourExamplesNameTheWordTyped) {
    ScratchDir dir;
    writeImage(dir.file("map.png"), makeImage(32, 32, smoothWave), OIIO::TypeDesc::UINT8);
    const std::string map = dir.file("map.png");
    expectUnknownWord(heightpackRun({"normal", map, "--tilesize", "8m", "--height", "0.2m", "-o", dir.file("n.exr")}),
                      "unknown option --tilesize", "--tile-size");
    expectUnknownWord(heightpackRun({"synth", "--wind-speed", "12", "-o", dir.file("s.exr")}), "unknown option --wind-speed",
                      "--wind");
    const ProcessResult filtr = heightpackRun({"pack", map, "--filtr", "lanczos3", "-o", dir.file("p.exr")});
    expectUnknownWord(filtr, "unknown option --filtr", "--filter");
    EXPECT_EQ(filtr.err.find("lanczos3"), std::string::npos) << "the value is not a second unknown word: " << filtr.err;
    expectUnknownWord(heightpackRun({"chek", map}), "unknown command 'chek'", "'check'");
    // Nothing was written by any of them.
    EXPECT_EQ(dir.listing(), std::vector<std::string>{"map.png"});
}

TEST(CommandWords, AWordNearNothingListsWhatThereIs) {
    const ProcessResult command = heightpackRun({"squash", "map.png"});
    expectUnknownWord(command, "unknown command 'squash'", "");
    EXPECT_EQ(command.err.find("did you mean"), std::string::npos) << command.err;
    for (const char* name : {"pack", "normal", "fresnel", "check", "tile", "synth", "build", "info"})
        EXPECT_NE(command.err.find(name), std::string::npos) << name << " not listed: " << command.err;
    const ProcessResult option = heightpackRun({"pack", "map.png", "--squash", "-o", "p.exr"});
    expectUnknownWord(option, "unknown option --squash", "");
    EXPECT_NE(option.err.find("see 'heightpack pack --help'"), std::string::npos) << option.err;
    expectUnknownWord(heightpackRun({"--versoin"}), "unknown option --versoin", "--version");
}

TEST(CommandWords, AnOptionGivenTwiceIsSaidSo) {
    ScratchDir dir;
    const ProcessResult size = heightpackRun({"synth", "--size", "64", "--size", "128", "--wind", "12", "--tile-size", "64m",
                                              "-o", dir.file("s.exr")});
    EXPECT_EQ(size.code, 2) << size.err;
    expectOneLineError(size, "");
    EXPECT_NE(size.err.find("--size was given twice (64, then 128)"), std::string::npos) << size.err;
    EXPECT_EQ(size.err.find("At Most"), std::string::npos) << size.err;
    // Under two of its names, and with the value after '=': still one option given twice.
    const ProcessResult output = heightpackRun({"synth", "--wind", "12", "--tile-size", "64m", "-o", dir.file("a.exr"),
                                                "--output=" + dir.file("b.exr")});
    EXPECT_EQ(output.code, 2) << output.err;
    expectOneLineError(output, "");
    EXPECT_NE(output.err.find("--output was given twice (" + dir.file("a.exr") + ", then " + dir.file("b.exr") + ")"),
              std::string::npos)
        << output.err;
    EXPECT_TRUE(dir.listing().empty());
    // A flag may be repeated (CLI11 takes the last), and so may an option that takes a list.
    EXPECT_NE(heightpackRun({"info", "no-such.exr", "--quiet", "-q", "--engine", "three", "--engine", "godot"}).code, 2);
}

// The property over every command's every long option: each with one letter dropped or two neighbours
// swapped is reported as unknown, naming that option; every option as spelt is known.
TEST(CommandWords, EveryOptionMisspeltSuggestsItself) {
    const auto line = cli::makeCommandLine();
    size_t options = 0, typos = 0, ties = 0;
    ASSERT_EQ(line->subcommands.size(), 8u);
    for (const CLI::App* command : line->subcommands) {
        const std::string name = command->get_name();
        std::set<std::string> longNames;
        for (const CLI::Option* o : command->get_options())
            for (const std::string& l : o->get_lnames()) longNames.insert(l);
        EXPECT_GT(longNames.size(), 4u) << name;  // --help, --json, --quiet, --threads and its own
        for (const std::string& option : longNames) {
            ++options;
            const auto known = cli::unknownWord(*line, {name, "--" + option});
            EXPECT_FALSE(known.has_value()) << name << " --" << option << ": " << known->what;
            for (const std::string& typo : typosOf(option)) {
                if (longNames.count(typo)) continue;  // another option's name: not a typo
                ++typos;
                const auto error = cli::unknownWord(*line, {name, "input.png", "--" + typo, "x"});
                ASSERT_TRUE(error.has_value()) << name << " --" << typo;
                EXPECT_EQ(error->what, "unknown option --" + typo);
                const std::vector<std::string> meant = suggested(error->hint);
                EXPECT_NE(std::find(meant.begin(), meant.end(), "--" + option), meant.end())
                    << name << " --" << typo << ": " << error->hint;
                // Two options at most, and two only where the typo is as near to each: "spreadings" is one
                // edit from --spreading and from --spreading-s.
                EXPECT_LE(meant.size(), 2u) << error->hint;
                if (meant.size() == 2) ++ties;
            }
        }
    }
    // The commands hold well over a hundred options between them, each with several misspellings.
    EXPECT_GT(options, 100u);
    EXPECT_GT(typos, 10 * options);
    EXPECT_LT(ties, typos / 100) << "a suggestion between two should be rare";
}

// The same over the commands' names.
TEST(CommandWords, EveryCommandMisspeltSuggestsItself) {
    const auto line = cli::makeCommandLine();
    for (const CLI::App* command : line->subcommands) {
        const std::string name = command->get_name();
        const auto known = cli::unknownWord(*line, {name});
        EXPECT_FALSE(known.has_value()) << name << ": " << known->what;
        for (const std::string& typo : typosOf(name)) {
            const auto error = cli::unknownWord(*line, {typo, "--tilesize"});
            ASSERT_TRUE(error.has_value()) << typo;
            EXPECT_EQ(error->what, "unknown command '" + typo + "'");
            EXPECT_EQ(error->hint.rfind("did you mean '" + name + "'? ", 0), 0u) << typo << ": " << error->hint;
        }
    }
}
