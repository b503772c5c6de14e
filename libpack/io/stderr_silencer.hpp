// Internal: keeps third-party decoders from printing on the process's stderr.
#pragma once

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <mutex>

namespace heightpack::detail {

// Points fd 2 at /dev/null while alive (when enabled). Reference-counted, so overlapping loads on
// several threads restore the real stderr only when the last one ends.
class StderrSilencer {
public:
    explicit StderrSilencer(bool enabled) : enabled_(enabled) {
        if (!enabled_) return;
        std::lock_guard<std::mutex> lock(mutex());
        if (depth()++ == 0) {
            std::fflush(stderr);
            saved() = ::dup(STDERR_FILENO);
            const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
            if (null >= 0) {
                ::dup2(null, STDERR_FILENO);
                ::close(null);
            }
        }
    }
    ~StderrSilencer() {
        if (!enabled_) return;
        std::lock_guard<std::mutex> lock(mutex());
        if (--depth() == 0 && saved() >= 0) {
            std::fflush(stderr);
            ::dup2(saved(), STDERR_FILENO);
            ::close(saved());
            saved() = -1;
        }
    }
    StderrSilencer(const StderrSilencer&) = delete;
    StderrSilencer& operator=(const StderrSilencer&) = delete;

private:
    static std::mutex& mutex() { static std::mutex m; return m; }
    static int& depth() { static int d = 0; return d; }
    static int& saved() { static int fd = -1; return fd; }
    bool enabled_;
};

}  // namespace heightpack::detail
