#include "bash_completion.hpp"

#include <map>

namespace heightpack::manual {

namespace {

std::string joined(const std::vector<std::string>& words, const std::string& separator) {
    std::string text;
    for (const std::string& w : words) text += (text.empty() ? "" : separator) + w;
    return text;
}

// What completes an option's value: "@choices:a b" or "@list:a b" (several, comma-separated) where the
// names are known; "@file" for text or a path; "@none" for a number or a value of its own kind (a
// LENGTH, a CHANNEL), which no file name is.
std::string valueRule(const OptionText& option) {
    if (!option.choices.empty()) return (option.list ? "@list:" : "@choices:") + joined(option.choices, " ");
    for (const char* path : {"TEXT", "FILE", "PATH", "DIR"})
        if (option.value == path) return "@file";
    return "@none";
}

// The body of one command's case: its options, and what follows each option that takes a value.
std::string commandCase(const std::string& pattern, const CommandText& command) {
    std::vector<std::string> names;
    std::map<std::string, std::vector<std::string>> rules;  // rule -> the options it follows
    for (const OptionText& option : command.options) {
        if (option.positional) continue;
        for (const std::string& n : option.names) names.push_back(n);
        if (!option.value.empty()) rules[valueRule(option)].push_back(joined(option.names, "|"));
    }
    std::string text = "        " + pattern + ")\n            options='" + joined(names, " ") + "'\n";
    if (!rules.empty()) {
        text += "            case \"$prev\" in\n";
        for (const auto& [rule, options] : rules)
            text += "                " + joined(options, "|") + ") value='" + rule + "' ;;\n";
        text += "            esac ;;\n";
    } else {
        text += "            ;;\n";
    }
    return text;
}

std::string functionName(const std::string& program) {
    std::string name = "_" + program;
    for (char& c : name)
        if (c == '-') c = '_';
    return name;
}

}  // namespace

std::string bashCompletion(const CommandText& program, const std::vector<CommandText>& subcommands) {
    const std::string name = program.invocation;
    const std::string fn = functionName(name);
    std::vector<std::string> commandNames;
    for (const CommandText& sub : subcommands) commandNames.push_back(sub.invocation.substr(sub.invocation.rfind(' ') + 1));
    std::string s = "# bash completion for " + name +
                    ", made at build time from its command line (tools/manual); edits are lost.\n"
                    "# shellcheck shell=bash\n" +
                    fn + "_files() {\n"
                    "    compopt -o filenames 2>/dev/null\n"
                    "    mapfile -t COMPREPLY < <(compgen -f -- \"$1\")\n"
                    "}\n\n" +
                    fn + "() {\n"
                    "    local cur=\"${COMP_WORDS[COMP_CWORD]}\" prev=\"\" command=\"\" options=\"\" value=\"\" i\n"
                    "    ((COMP_CWORD > 0)) && prev=\"${COMP_WORDS[COMP_CWORD - 1]}\"\n"
                    "    # --name=value arrives as three words (COMP_WORDBREAKS holds '=').\n"
                    "    if [[ $cur == \"=\" ]]; then\n"
                    "        cur=\"\"\n"
                    "    elif [[ $prev == \"=\" ]] && ((COMP_CWORD > 1)); then\n"
                    "        prev=\"${COMP_WORDS[COMP_CWORD - 2]}\"\n"
                    "    fi\n";
    if (!subcommands.empty()) {
        s += "    for ((i = 1; i < COMP_CWORD; i++)); do\n"
             "        case \"${COMP_WORDS[i]}\" in\n"
             "            " + joined(commandNames, "|") + ") command=\"${COMP_WORDS[i]}\"; break ;;\n"
             "        esac\n"
             "    done\n";
    }
    s += "    case \"$command\" in\n" + commandCase("\"\"", program);
    for (size_t i = 0; i < subcommands.size(); ++i) s += commandCase(commandNames[i], subcommands[i]);
    s += "    esac\n"
         "    COMPREPLY=()\n"
         "    case \"$value\" in\n"
         "        @none) return 0 ;;\n"
         "        @file) " + fn + "_files \"$cur\"; return 0 ;;\n"
         "        @choices:*) mapfile -t COMPREPLY < <(compgen -W \"${value#@choices:}\" -- \"$cur\"); return 0 ;;\n"
         "        @list:*)\n"
         "            local done_=\"\"\n"
         "            [[ $cur == *,* ]] && done_=\"${cur%,*},\"\n"
         "            mapfile -t COMPREPLY < <(compgen -P \"$done_\" -W \"${value#@list:}\" -- \"${cur##*,}\")\n"
         "            return 0 ;;\n"
         "    esac\n"
         "    if [[ $cur == -* ]]; then\n"
         "        mapfile -t COMPREPLY < <(compgen -W \"$options\" -- \"$cur\")\n";
    if (!subcommands.empty())
        s += "    elif [[ -z $command ]]; then\n"
             "        mapfile -t COMPREPLY < <(compgen -W '" + joined(commandNames, " ") + "' -- \"$cur\")\n";
    s += "    else\n"
         "        " + fn + "_files \"$cur\"\n"
         "    fi\n"
         "}\n"
         "complete -F " + fn + " " + name + "\n";
    return s;
}

}  // namespace heightpack::manual
