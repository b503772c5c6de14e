// What a command line says of itself, read from its CLI::App: the words a man page and a completion
// script are made of, so both follow the options the program really parses.
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace heightpack::manual {

struct OptionText {
    std::vector<std::string> names;    // "-o", "--output"; a positional's name alone
    std::string value;                 // what it takes ("TEXT", "FLOAT"); empty for a flag
    std::vector<std::string> choices;  // the names a validator accepts ("{periodic,clamp}"), if it lists them
    std::string accepts;               // what the other validators say ("INT in [0 - 1024]")
    std::string defaultValue;
    std::string description;
    bool positional = false;
    bool required = false;
    bool list = false;                 // several values, separated by commas
    bool many = false;                 // a positional that takes several words
};

struct Example {
    std::string command;  // as typed
    std::string comment;  // what the footer said beside it, if anything
};

struct CommandText {
    std::string invocation;  // "heightpack pack"
    std::string page;        // "heightpack-pack": the man page's name
    std::string description;
    std::vector<OptionText> options;  // positionals first, in their order, then options as declared
    std::vector<Example> examples;    // the footer's lines under "Examples:"
    std::vector<std::string> notes;   // the footer's other lines
};

// app as the page and the completion see it. `omitted` is text of the footer said elsewhere in a page
// (the exit codes, which get their own section); it is left out of the notes.
CommandText describe(const CLI::App& app, const std::string& invocation, const std::string& page,
                     const std::string& omitted = "");

// Every subcommand of app, in the order they were added.
std::vector<const CLI::App*> subcommandsOf(const CLI::App& app);

}  // namespace heightpack::manual
