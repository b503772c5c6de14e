#include "man_page.hpp"

#include <cctype>

namespace heightpack::manual {

namespace {

// Text as roff reads it: a backslash is \e, a hyphen \- (so an option pasted from the page is one),
// and a line that would start with a control character starts with \& instead.
std::string roff(const std::string& text) {
    std::string out;
    for (char c : text) {
        if (c == '\\') out += "\\e";
        else if (c == '-') out += "\\-";
        else if (c == '\n') out += "\n\\&";
        else out += c;
    }
    return "\\&" + out;
}

std::string bold(const std::string& text) { return "\\fB" + roff(text) + "\\fR"; }
std::string italic(const std::string& text) { return "\\fI" + roff(text) + "\\fR"; }

// "pack a height map" from "heightpack: pack a height map" (the program's own description), as a
// sentence when asked: capital first, full stop at the end.
std::string summary(const std::string& description, const std::string& program, bool sentence) {
    std::string text = description.rfind(program + ": ", 0) == 0 ? description.substr(program.size() + 2) : description;
    if (sentence && !text.empty()) {
        text[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(text[0])));
        if (text.back() != '.') text += '.';
    }
    return text;
}

std::string upper(std::string text) {
    for (char& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return text;
}

// "-o, --output TEXT" as the option's tag: names bold, what it takes italic.
std::string tag(const OptionText& option) {
    if (option.positional) return italic(option.names.front());
    std::string text;
    for (const std::string& name : option.names) text += (text.empty() ? "" : ", ") + bold(name);
    if (!option.value.empty()) text += " " + italic(option.value) + (option.list ? "[,...]" : "");
    return text;
}

// A command as lines of at most `width` characters where it has spaces to break at, each but the last
// ending in a backslash as a shell continues it, the rest indented.
std::string brokenCommand(const std::string& command, size_t width) {
    std::string text, line;
    size_t from = 0;
    while (from < command.size()) {
        size_t end = command.find(' ', from);
        if (end == std::string::npos) end = command.size();
        const std::string word = command.substr(from, end - from);
        if (!line.empty() && line.size() + 1 + word.size() + 2 > width) {
            text += line + " \\\n";
            line = "    " + word;
        } else {
            line += (line.empty() ? "" : " ") + word;
        }
        from = end + 1;
    }
    return text + line;
}

std::string synopsis(const CommandText& command, bool hasSubcommands) {
    std::string text = ".B " + roff(command.invocation) + "\n";
    text += hasSubcommands ? italic("COMMAND") + " [" + italic("OPTIONS") + "]" : "[" + italic("OPTIONS") + "]";
    for (const OptionText& option : command.options) {
        if (!option.required) continue;
        const std::string word = option.positional ? italic(option.names.front()) + (option.many ? "..." : "")
                                                   : bold(option.names.back()) + " " + italic(option.value);
        text += " " + word;
    }
    for (const OptionText& option : command.options)
        if (option.positional && !option.required)
            text += " [" + italic(option.names.front()) + (option.many ? "..." : "") + "]";
    return text + "\n";
}

std::string optionEntry(const OptionText& option) {
    std::string text = ".TP\n" + tag(option) + "\n" + roff(option.description) + "\n";
    std::string facts;
    if (option.required) facts += " Required.";
    if (!option.choices.empty()) {
        facts += option.list ? " Any of: " : " One of: ";
        for (size_t i = 0; i < option.choices.size(); ++i) facts += (i ? ", " : "") + bold(option.choices[i]);
        facts += ".";
    }
    if (!option.accepts.empty()) facts += " Accepts " + roff(option.accepts) + ".";
    if (!option.defaultValue.empty()) facts += " Default: " + bold(option.defaultValue) + ".";
    if (!facts.empty()) text += ".br\n" + facts.substr(1) + "\n";
    return text;
}

}  // namespace

std::string manPage(const CommandText& command, const std::vector<CommandText>& subcommands, const PageContext& context) {
    const std::string name = summary(command.description, context.program, false);
    std::string page = ".TH " + roff(upper(command.page)) + " 1 \"\" \"" + roff(context.version) + "\" \"User Commands\"\n";
    page += ".nh\n.ad l\n";  // option names are never hyphenated; ragged right, as most pages are
    page += ".SH NAME\n" + roff(command.page).substr(2) + " \\- " + roff(name).substr(2) + "\n";
    page += ".SH SYNOPSIS\n" + synopsis(command, !subcommands.empty());
    page += ".SH DESCRIPTION\n" + roff(summary(command.description, context.program, true)) + "\n";
    for (const std::string& note : command.notes) page += ".PP\n" + roff(note) + "\n";
    if (!subcommands.empty()) {
        page += ".SH COMMANDS\n";
        for (const CommandText& sub : subcommands) {
            page += ".TP\n" + bold(sub.invocation.substr(sub.invocation.rfind(' ') + 1)) + "\n";
            page += roff(summary(sub.description, context.program, true)) + " See\n.BR " + roff(sub.page) + " (1).\n";
        }
    }
    page += ".SH OPTIONS\n";
    for (const OptionText& option : command.options) page += optionEntry(option);
    if (!command.examples.empty()) {
        page += ".SH EXAMPLES\n";
        for (const Example& example : command.examples) {
            // What the footer says beside a command follows it as a shell comment, as in --help.
            const std::string comment = example.comment.empty() ? "" : "\n# " + example.comment;
            page += ".PP\n.nf\n.RS 4\n" + roff(brokenCommand(example.command, 68) + comment) + "\n.RE\n.fi\n";
        }
    }
    page += ".SH EXIT STATUS\n";
    for (const ExitStatus& exit : context.exits)
        page += ".TP\n.B " + std::to_string(exit.code) + "\n" + roff(summary(exit.meaning, context.program, true)) + "\n";
    if (!context.seeAlso.empty()) {
        page += ".SH SEE ALSO\n";
        for (size_t i = 0; i < context.seeAlso.size(); ++i) {
            const std::string& see = context.seeAlso[i];
            const size_t paren = see.find('(');
            const bool last = i + 1 == context.seeAlso.size();
            page += ".BR " + roff(see.substr(0, paren)) + " " + see.substr(paren) + (last ? "" : ",") + "\n";
        }
    }
    return page;
}

}  // namespace heightpack::manual
