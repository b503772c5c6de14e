#include "heightpack/bake/action_plan.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>

#include "heightpack/bake/build_materials.hpp"
#include "heightpack/bake/build_report.hpp"

#include "build_plan.hpp"

namespace heightpack {

namespace {

namespace fs = std::filesystem;

// A path in a Ninja build line: '$', ' ' and ':' escaped with '$'.
std::string ninjaPath(const std::string& path) {
    std::string out;
    for (char c : path) {
        if (c == '$' || c == ' ' || c == ':') out += '$';
        out += c;
    }
    return out;
}

// A command for /bin/sh as Ninja runs it: each word single-quoted, then '$' doubled for Ninja.
std::string ninjaCommand(const std::vector<std::string>& argv) {
    std::string out;
    for (const std::string& word : argv) {
        if (!out.empty()) out += ' ';
        out += '\'';
        for (char c : word) {
            if (c == '\'') out.append("'\\''");
            else if (c == '$') out.append("$$");
            else out.push_back(c);
        }
        out += '\'';
    }
    return out;
}

}  // namespace

std::vector<BuildAction> planActions(const std::vector<Manifest>& manifests, const std::string& output,
                                     const std::string& executable, const std::string& version) {
    std::vector<BuildAction> actions;
    for (const Manifest& m : manifests) {
        const std::string folder = materialOutputDir(output, m, manifests.size());
        BuildAction last;
        last.manifest = m.path;
        last.folder = folder;
        last.only = kMaterialFile;
        last.inputs = {executable, m.path};
        last.outputs = {(fs::path(folder) / kMaterialFile).string(), (fs::path(folder) / kBuildStateFile).string()};
        last.description = std::string("describe ").append(m.name).append(": ").append(kMaterialFile);
        for (const detail::Step& s : detail::planSteps(m, version)) {
            BuildAction a;
            a.manifest = m.path;
            a.folder = folder;
            a.only = s.report.output;
            a.inputs = {executable, m.path};
            if (!s.report.input.empty()) a.inputs.push_back(s.report.input);
            a.outputs = {(fs::path(folder) / s.report.output).string()};
            a.description = std::string("bake ").append(m.name).append(": ").append(s.report.output);
            last.inputs.push_back(a.outputs.front());
            actions.push_back(std::move(a));
        }
        actions.push_back(std::move(last));
    }
    return actions;
}

std::string ninjaFile(const std::vector<BuildAction>& actions) {
    std::string text =
        "# heightpack build, as actions: run `ninja -f THIS_FILE -j N` from the folder the plan was made in.\n"
        "ninja_required_version = 1.3\n\n"
        "rule heightpack\n"
        "  command = $cmd\n"
        "  description = $desc\n";
    for (const BuildAction& a : actions) {
        text += "\nbuild";
        for (const std::string& o : a.outputs) text.append(" ").append(ninjaPath(o));
        text.append(": heightpack");
        for (const std::string& i : a.inputs) text.append(" ").append(ninjaPath(i));
        text.append("\n  cmd = ").append(ninjaCommand(a.command)).append("\n  desc = ");
        for (char c : a.description) {
            if (c == '$') text.push_back('$');
            text.push_back(c);
        }
        text.push_back('\n');
    }
    return text;
}

std::string actionsJson(const std::vector<BuildAction>& actions) {
    nlohmann::json all = nlohmann::json::array();
    for (const BuildAction& a : actions)
        all.push_back({{"command", a.command}, {"inputs", a.inputs}, {"outputs", a.outputs}, {"description", a.description}});
    return nlohmann::json{{"actions", all}}.dump(2) + "\n";
}

}  // namespace heightpack
