// Shared by the fuzz harnesses: a scratch folder per process, and writing the fuzz bytes to a file there
// (every reader under test takes a path, as heightpack's commands give it one).
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace heightpack::fuzz {

// A folder of this process's own under TMPDIR (or /tmp), made on first use and removed at exit.
inline const std::filesystem::path& scratch() {
    static const std::filesystem::path dir = [] {
        const char* tmp = std::getenv("TMPDIR");
        std::filesystem::path d = std::filesystem::path(tmp && *tmp ? tmp : "/tmp") /
                                  ("heightpack-fuzz-" + std::to_string(::getpid()));
        std::filesystem::create_directories(d);
        std::atexit([] {
            std::error_code ec;
            std::filesystem::remove_all(scratch(), ec);
        });
        return d;
    }();
    return dir;
}

// Writes size bytes to name inside scratch() and returns the file's path; aborts if it cannot (a broken
// harness must not pass for a robust reader).
inline std::string writeInput(const std::string& name, const uint8_t* data, size_t size) {
    const std::string path = (scratch() / name).string();
    FILE* f = std::fopen(path.c_str(), "wb");
    if (!f || (size > 0 && std::fwrite(data, 1, size, f) != size) || std::fclose(f) != 0) {
        std::fprintf(stderr, "fuzz harness: cannot write %s\n", path.c_str());
        std::abort();
    }
    return path;
}

}  // namespace heightpack::fuzz
