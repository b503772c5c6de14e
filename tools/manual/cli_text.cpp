#include "cli_text.hpp"

#include <cctype>
#include <sstream>

namespace heightpack::manual {

namespace {

// A validator's description that is one capitalised word ("LENGTH") names the kind of value it reads.
bool isValueName(const std::string& word) {
    if (word.empty()) return false;
    for (char c : word) {
        const auto u = static_cast<unsigned char>(c);
        if (!std::isupper(u) && !std::isdigit(u) && c != '_') return false;
    }
    return true;
}

// CLI11's full type name is the type, then each validator's description after a colon:
// "TEXT:{periodic,clamp}", "INT:INT in [0 - 1024]". A description in braces lists the accepted names.
void readTypeName(const std::string& full, OptionText& option) {
    size_t from = 0;
    for (bool first = true;; first = false) {
        const size_t colon = full.find(':', from);
        const std::string part = full.substr(from, colon == std::string::npos ? std::string::npos : colon - from);
        if (first) {
            option.value = part;
        } else if (part.size() > 2 && part.front() == '{' && part.back() == '}') {
            std::stringstream names(part.substr(1, part.size() - 2));
            for (std::string name; std::getline(names, name, ',');) option.choices.push_back(name);
        } else if (isValueName(part) && option.value == "TEXT") {
            option.value = part;  // a validator that names what it reads: "LENGTH", "CHANNEL"
        } else if (!part.empty()) {
            option.accepts += (option.accepts.empty() ? "" : "; ") + part;
        }
        if (colon == std::string::npos) return;
        from = colon + 1;
    }
}

OptionText readOption(const CLI::Option& o) {
    OptionText option;
    option.positional = !o.nonpositional();
    if (option.positional) option.names.push_back(o.get_name(true, false));
    for (const std::string& s : o.get_snames()) option.names.push_back("-" + s);
    for (const std::string& l : o.get_lnames()) option.names.push_back("--" + l);
    if (o.get_items_expected_max() > 0) readTypeName(o.get_type_name(), option);
    option.defaultValue = o.get_default_str();
    option.description = o.get_description();
    option.required = o.get_required();
    option.list = o.get_delimiter() == ',';
    option.many = option.positional && o.get_items_expected_max() > 1;
    return option;
}

// "command   (a comment)" or "command   # a comment": the command ends where a run of spaces begins.
Example readExample(const std::string& line) {
    const size_t gap = line.find("  ");
    if (gap == std::string::npos || line.find_first_not_of(' ', gap) == std::string::npos)
        return {line.substr(0, gap), {}};
    std::string comment = line.substr(line.find_first_not_of(' ', gap));
    if (comment.rfind("# ", 0) == 0) comment.erase(0, 2);
    if (comment.size() > 2 && comment.front() == '(' && comment.back() == ')')
        comment = comment.substr(1, comment.size() - 2);
    return {line.substr(0, gap), comment};
}

// Whether a footer line ends its paragraph ("... timestamps).", "Exit codes:") or goes on in the next.
bool endsSentence(const std::string& line) {
    size_t end = line.find_last_not_of(" )'\"");
    return end != std::string::npos && (line[end] == '.' || line[end] == ':' || line[end] == '?' || line[end] == '!');
}

}  // namespace

std::vector<const CLI::App*> subcommandsOf(const CLI::App& app) {
    return app.get_subcommands([](const CLI::App*) { return true; });
}

CommandText describe(const CLI::App& app, const std::string& invocation, const std::string& page,
                     const std::string& omitted) {
    CommandText text{invocation, page, app.get_description(), {}, {}, {}};
    for (const CLI::Option* o : app.get_options())
        if (!o->nonpositional()) text.options.push_back(readOption(*o));
    for (const CLI::Option* o : app.get_options())
        if (o->nonpositional()) text.options.push_back(readOption(*o));

    std::string footer = app.get_footer();
    if (const size_t at = omitted.empty() ? std::string::npos : footer.find(omitted); at != std::string::npos)
        footer.erase(at, omitted.size());
    std::stringstream lines(footer);
    bool examples = false;
    for (std::string line; std::getline(lines, line);) {
        // An example broken with a backslash goes on in the next line.
        for (std::string more; line.size() > 1 && line.back() == '\\' && std::getline(lines, more);) {
            const size_t text = more.find_first_not_of(' ');
            line = line.substr(0, line.size() - 1) + (text == std::string::npos ? std::string() : more.substr(text));
        }
        if (line.empty()) continue;
        if (line == "Examples:") {
            examples = true;
        } else if (examples && line.size() > 2 && line.compare(0, 2, "  ") == 0 && line[2] != ' ') {
            text.examples.push_back(readExample(line.substr(2)));
        } else if (!text.notes.empty() && !endsSentence(text.notes.back()) && !examples) {
            text.notes.back() += " " + line;  // a paragraph the footer wrapped by hand
        } else {
            examples = false;
            text.notes.push_back(line);
        }
    }
    return text;
}

}  // namespace heightpack::manual
