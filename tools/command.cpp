#include "command.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "heightpack/io/files.hpp"
#include "heightpack/io/pixel_type.hpp"
#include "heightpack/io/read.hpp"

#include "hints.hpp"

namespace heightpack::cli {

ExitCode exitCodeFor(ErrorKind kind) {
    switch (kind) {
        case ErrorKind::BadInput: return ExitCode::BadInput;
        case ErrorKind::CannotWrite: return ExitCode::CannotWrite;
        case ErrorKind::InconsistentOptions: return ExitCode::Usage;
        case ErrorKind::Internal: return ExitCode::Internal;
    }
    return ExitCode::Internal;
}

void printError(const Error& error) {
    clearProgressLine();
    std::string line = "heightpack: error: ";
    if (!error.path.empty()) line += error.path + ": ";
    line += error.what;
    if (const std::string hint = cliHint(error); !hint.empty()) line += " (" + hint + ")";
    // One line, whatever a library put in its message.
    for (char& c : line)
        if (c == '\n' || c == '\r') c = ' ';
    std::cerr << line << std::endl;
}

void Command::addCommonOptions(CLI::App& cmd) {
    name_ = cmd.get_name();
    cmd.add_flag("--json", common_.json, "print one JSON object on stdout instead of text");
    cmd.add_flag("-q,--quiet", common_.quiet, "print nothing but errors");
    cmd.add_option("--threads", common_.threads, "worker threads; 0 = all cores (output is identical either way)")
        ->check(CLI::Range(0, 1024));
}

ExitCode Command::fail(const Error& error) const {
    printError(error);
    return exitCodeFor(error.kind);
}

ExitCode Command::usage(const std::string& what) const {
    printError({ErrorKind::Internal, {}, what, "see 'heightpack " + name_ + " --help'"});
    return ExitCode::Usage;
}

ExitCode Command::checkOutputs(const std::vector<std::string>& inputs, const std::vector<OutputRule>& outputs) const {
    namespace fs = std::filesystem;
    const std::string help = "see 'heightpack " + name_ + " --help'";
    auto refuse = [&](const std::string& path, const std::string& what, const std::string& hint) {
        printError({ErrorKind::Internal, path, what, hint + "; " + help});
        return ExitCode::Usage;
    };
    for (size_t i = 0; i < outputs.size(); ++i) {
        const OutputRule& o = outputs[i];
        if (o.path.empty()) return refuse(o.option + " ''", "the output path is empty", "give an output file name");
        for (const std::string& input : inputs)
            if (sameFile(input, o.path))
                return refuse(o.path, "is the input" + (input == o.path ? std::string() : " " + input + " (the same file)") +
                                          ": writing it would destroy the input",
                              "give " + o.option + " another file name");
        if (o.staged)
            if (Status s = checkWritable(o.path); !s) return fail(s.error());
        const std::string ext = lowerExtension(o.path);
        if (std::find(o.extensions.begin(), o.extensions.end(), ext) == o.extensions.end()) {
            if (Status s = checkWritable(o.path); !s) return fail(s.error());  // a folder, a device: say so
            std::string list;
            for (const std::string& e : o.extensions) list += (list.empty() ? "" : ", ") + e;
            return refuse(o.path,
                          "'" + name_ + "' cannot write " + (ext.empty() ? "a file without an extension" : ext + " files") +
                              " faithfully",
                          o.option + " must end in " + list);
        }
        std::error_code ec;
        for (size_t j = 0; j < i; ++j)
            if (sameFile(outputs[j].path, o.path) ||
                fs::weakly_canonical(outputs[j].path, ec) == fs::weakly_canonical(o.path, ec))
                return refuse(o.path, "is also the " + outputs[j].option + " output", "give each output its own name");
    }
    return ExitCode::Ok;
}

void Command::printJson(const nlohmann::json& document) {
    clearProgressLine();
    std::cout << document.dump(2) << std::endl;
}

}  // namespace heightpack::cli
