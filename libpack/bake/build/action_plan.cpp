#include "heightpack/bake/build/action_plan.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <set>

#include "heightpack/bake/build/build_materials.hpp"
#include "heightpack/bake/build/build_report.hpp"

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

// A command for /bin/sh as Ninja runs it: each word single-quoted, '$' doubled for Ninja.
std::string ninjaCommand(const std::vector<std::string>& argv) {
    std::string out;
    for (const std::string& word : argv) {
        if (!out.empty()) out += ' ';
        out += detail::quotedForExecutor(word);
    }
    return out;
}

}  // namespace

std::string detail::quotedForExecutor(const std::string& word) {
    std::string out = "'";
    for (char c : word) {
        if (c == '\'') out.append("'\\''");
        else if (c == '$') out.append("$$");
        else out.push_back(c);
    }
    return out + "'";
}

std::vector<BuildAction> planActions(const std::vector<Manifest>& manifests, const std::string& output,
                                     const std::string& executable, const std::string& version, bool sandboxed) {
    std::vector<BuildAction> actions;
    for (const Manifest& m : manifests) {
        const std::string folder = materialOutputDir(output, m, manifests.size());
        auto action = [&](const std::string& only, const char* verb) {
            BuildAction a;
            a.manifest = m.path;
            a.folder = folder;
            a.only = only;
            a.material = m.name;
            a.inputs = {executable, m.path};
            a.outputs = {(fs::path(folder) / only).string()};
            a.description = std::string(verb).append(" ").append(m.name).append(": ").append(only);
            return a;
        };
        BuildAction last = action(kMaterialFile, "describe");
        last.outputs.push_back((fs::path(folder) / kBuildStateFile).string());
        std::set<std::string> shared;  // inside the output folder
        if (sandboxed)
            for (const detail::Step& s : detail::planSharedSteps(m, version)) {
                shared.insert(s.report.output);
                actions.push_back(action(s.report.output, "prepare"));
            }
        const std::vector<detail::Step> steps = detail::planSteps(m, version);
        // A frame of a painted sequence reads one file, but every frame's must be there: which of them
        // are there decides how many frames the sequence has, so what each output is named.
        std::map<std::string, std::vector<std::string>> sequences;  // kind and name -> every frame's file
        for (const detail::Step& s : steps)
            if (sandboxed && s.report.frame >= 0 && !s.report.input.empty())
                sequences[s.report.kind + "/" + s.report.name].push_back(s.report.input);
        // The last action hashes every source too (the state records its key): each once.
        std::set<std::string> sources;
        for (const detail::Step& s : steps) {
            BuildAction a = action(s.report.output, "bake");
            const auto sequence = sequences.find(s.report.kind + "/" + s.report.name);
            if (sequence != sequences.end()) a.inputs.insert(a.inputs.end(), sequence->second.begin(), sequence->second.end());
            else if (!s.report.input.empty()) a.inputs.push_back(s.report.input);
            for (const std::string& file : s.intermediates)
                if (shared.count(file)) a.inputs.push_back((fs::path(folder) / file).string());
            if (!s.report.input.empty() && sources.insert(s.report.input).second) last.inputs.push_back(s.report.input);
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
