// Running the heightpack binary under test, for test programs whose target defines HEIGHTPACK_EXE (and,
// for the independent KTX2/DDS reader, HEIGHTPACK_NPM_DIR and HEIGHTPACK_READER_MJS): see
// tests/CMakeLists.txt. Header-only because the path is a per-target definition.
#pragma once

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "support/test_support.hpp"

namespace heightpack::test {

inline ProcessResult heightpackRun(const std::vector<std::string>& args) {
    std::vector<std::string> argv = {HEIGHTPACK_EXE};
    argv.insert(argv.end(), args.begin(), args.end());
    return runProcess(argv);
}

// heightpack COMMAND -q ARGS..., which must succeed (a fixture's step: fails the test with its stderr).
inline void heightpackMustRun(const std::string& command, std::vector<std::string> args) {
    args.insert(args.begin(), {command, "-q"});
    const ProcessResult r = heightpackRun(args);
    ASSERT_EQ(r.code, 0) << command << ": " << r.err;
}

// The error contract: exactly one line on stderr, prefixed, naming path (unless empty), nothing on stdout.
inline void expectOneLineError(const ProcessResult& run, const std::string& path) {
    EXPECT_EQ(run.err.rfind("heightpack: error: ", 0), 0u) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    if (!path.empty()) {
        EXPECT_NE(run.err.find(path), std::string::npos) << run.err;
    }
    EXPECT_TRUE(run.out.empty()) << run.out;
}

#ifdef HEIGHTPACK_READER_MJS
// Whether scripts/test.sh installed ktx-parse into the build folder (a bare cmake build has no npm step).
inline bool independentReaderInstalled() {
    return std::filesystem::exists(std::string(HEIGHTPACK_NPM_DIR) + "/node_modules/ktx-parse/package.json");
}

// The independent reader's view of a KTX2 or DDS file (tests/io/read_container.mjs), as JSON.
inline nlohmann::json readIndependently(const std::string& path) {
    const ProcessResult r = runProcess({"node", HEIGHTPACK_READER_MJS, path, HEIGHTPACK_NPM_DIR});
    EXPECT_EQ(r.code, 0) << r.err;
    return r.code == 0 ? nlohmann::json::parse(r.out) : nlohmann::json();
}
#endif

}  // namespace heightpack::test
