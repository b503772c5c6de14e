// Running the heightpack binary under test, for test programs whose target defines HEIGHTPACK_EXE (and,
// for the independent KTX2/DDS reader, HEIGHTPACK_NPM_DIR and HEIGHTPACK_READER_MJS): see
// tests/CMakeLists.txt. Header-only because the path is a per-target definition.
#pragma once

#include <nlohmann/json.hpp>

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
