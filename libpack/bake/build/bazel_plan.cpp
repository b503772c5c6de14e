#include <cctype>
#include <cstring>
#include <filesystem>

#include "heightpack/bake/build/action_plan.hpp"
#include "heightpack/bake/build/build_report.hpp"

#include "build_plan.hpp"

namespace heightpack {

namespace {

namespace fs = std::filesystem;

// Characters that a Bazel label takes and a shell reads as they are: a word of them needs no quoting in
// a genrule's command, a path of them is a label as it is.
bool plain(const std::string& text) {
    if (text.empty()) return false;
    for (char c : text)
        if (!std::isalnum(static_cast<unsigned char>(c)) && !std::strchr("._-+=,~/", c)) return false;
    return true;
}

// path as a label of the package in the folder the plan is made in: normalised, relative, inside it.
Result<std::string> label(const std::string& path) {
    const fs::path normal = fs::path(path).lexically_normal();
    const std::string text = normal.generic_string();
    if (normal.is_absolute() || text.empty() || *normal.begin() == ".." || text.back() == '/' || !plain(text))
        return Error{ErrorKind::InconsistentOptions, path, "cannot be a file of the Bazel package the plan is made for",
                     "make the plan in the folder that holds the manifest and its maps (and no other Bazel package), "
                     "naming them and the output folder by relative paths of letters, digits and ._-+=,~"};
    return text;
}

// text as a Starlark string literal.
std::string starlark(const std::string& text) {
    std::string out = "\"";
    for (char c : text) {
        if (c == '"' || c == '\\') out += '\\';
        out += c;
    }
    return out + "\"";
}

// One word of a genrule's command: as it is when plain, else quoted for the shell and for Bazel's own
// expansion of $(...).
std::string commandWord(const std::string& word) { return plain(word) ? word : detail::quotedForExecutor(word); }

// A genrule's name: the material's and the output's, in the characters a target name takes.
std::string ruleName(const std::string& text) {
    std::string out;
    for (char c : text) out += std::isalnum(static_cast<unsigned char>(c)) || std::strchr("._-+=,~/", c) ? c : '_';
    return out;
}

std::string list(const std::vector<std::string>& labels) {
    std::string out = "[";
    if (labels.size() == 1) return out.append(starlark(labels.front())).append("]");
    out += '\n';
    for (const std::string& l : labels) out.append("        ").append(starlark(l)).append(",\n");
    return out + "    ]";
}

}  // namespace

Result<std::string> bazelBuildFile(const std::vector<BuildAction>& actions) {
    std::string text =
        "# heightpack build, as Bazel actions: with heightpack's WORKSPACE rule for Bazel, `bazel build //...`\n"
        "# makes every output under bazel-bin/.\n";
    for (const BuildAction& a : actions) {
        std::vector<std::string> srcs, outs;
        for (size_t i = 1; i < a.inputs.size(); ++i) {  // the first, the program, is the tool
            auto l = label(a.inputs[i]);
            if (!l) return l.error();
            srcs.push_back(*l);
        }
        for (const std::string& o : a.outputs) {
            auto l = label(o);
            if (!l) return l.error();
            outs.push_back(*l);
        }
        std::string cmd = std::string("$(location ") + kBazelTool + ")";
        for (size_t i = 1; i < a.command.size(); ++i) {
            const std::string& word = a.command[i];
            cmd += ' ';
            if (word == a.folder) cmd += "$(RULEDIR)/";
            cmd += commandWord(word);
        }
        // The last action is named after the material (bazel build //:NAME); the others after their output.
        const std::string name = ruleName(a.only == kMaterialFile ? a.material : a.material + "." + a.only);
        text.append("\ngenrule(\n    name = ").append(starlark(name)).append(",\n");
        text.append("    srcs = ").append(list(srcs)).append(",\n");
        text.append("    outs = ").append(list(outs)).append(",\n");
        text.append("    tools = [").append(starlark(kBazelTool)).append("],\n");
        text.append("    cmd = ").append(starlark(cmd)).append(",\n");
        text.append("    message = ").append(starlark(a.description)).append(",\n)\n");
    }
    return text;
}

std::string bazelWorkspace(const std::string& executable) {
    const fs::path program = fs::absolute(executable).lexically_normal();
    const std::string file = program.filename().string();
    // The tool's label is @heightpack//:heightpack whatever the program's file is called.
    std::string build = "exports_files([\"heightpack\"])";
    if (file != "heightpack")
        build = std::string("filegroup(name = \"heightpack\", srcs = [")
                    .append(starlark(file))
                    .append("], visibility = [\"//visibility:public\"])");
    return std::string("# heightpack, the tool of every action of heightpack's Bazel plans (") + kBazelTool + ")\n"
           "new_local_repository(\n"
           "    name = \"heightpack\",\n"
           "    path = " + starlark(program.parent_path().string()) + ",\n"
           "    build_file_content = " + starlark(build) + ",\n"
           ")\n";
}

}  // namespace heightpack
