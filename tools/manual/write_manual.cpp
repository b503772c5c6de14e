#include "write_manual.hpp"

#include <filesystem>
#include <fstream>
#include <iostream>

#include "bash_completion.hpp"

namespace heightpack::manual {

namespace {

bool writeFile(const std::filesystem::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
    out.close();
    if (out) return true;
    std::cerr << "heightpack manual: error: cannot write " << path.string() << "\n";
    return false;
}

}  // namespace

int writeManual(const std::string& folder, const CommandText& program, const std::vector<CommandText>& subcommands,
                const PageContext& context) {
    namespace fs = std::filesystem;
    std::error_code ec;
    // Rewritten whole, so a command that is gone leaves no page behind.
    fs::remove_all(folder, ec);
    fs::create_directories(fs::path(folder) / "man1", ec);
    fs::create_directories(fs::path(folder) / "completions", ec);
    // The program's page points at every command's, each command's at the program's.
    PageContext programContext = context;
    for (size_t i = 0; i < subcommands.size(); ++i)
        programContext.seeAlso.insert(programContext.seeAlso.begin() + i, subcommands[i].page + "(1)");
    bool ok = writeFile(fs::path(folder) / "man1" / (program.page + ".1"), manPage(program, subcommands, programContext));
    for (const CommandText& sub : subcommands) {
        PageContext own = context;
        own.seeAlso.insert(own.seeAlso.begin(), program.page + "(1)");
        ok = writeFile(fs::path(folder) / "man1" / (sub.page + ".1"), manPage(sub, {}, own)) && ok;
    }
    ok = writeFile(fs::path(folder) / "completions" / program.invocation, bashCompletion(program, subcommands)) && ok;
    return ok ? 0 : 1;
}

}  // namespace heightpack::manual
