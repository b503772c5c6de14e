#include "heightpack/bake/build/shared_cache.hpp"

#include <fcntl.h>
#include <linux/fs.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <vector>

#include "heightpack/bake/build/build_state.hpp"
#include "heightpack/io/files.hpp"

#include "cache_entry.hpp"

namespace heightpack {

namespace fs = std::filesystem;

namespace {

constexpr off_t kHeaderBytes = detail::kEntryHeaderBytes;

// A file descriptor closed when it goes out of scope.
struct Fd {
    int fd = -1;
    explicit Fd(int f) : fd(f) {}
    ~Fd() {
        if (fd >= 0) ::close(fd);
    }
    Fd(const Fd&) = delete;
    Fd& operator=(const Fd&) = delete;
};

// Copies from's bytes from fromAt to its end into to at toAt. A clone first (FICLONERANGE: the two files
// share blocks, nothing is copied) where the file system can; else read and written.
bool copyToEnd(int from, off_t fromAt, int to, off_t toAt) {
#ifdef FICLONERANGE
    file_clone_range clone{};
    clone.src_fd = from;
    clone.src_offset = static_cast<__u64>(fromAt);
    clone.src_length = 0;  // to the end
    clone.dest_offset = static_cast<__u64>(toAt);
    if (::ioctl(to, FICLONERANGE, &clone) == 0) return true;
#endif
    std::vector<char> buffer(1 << 20);
    for (;;) {
        const ssize_t n = ::pread(from, buffer.data(), buffer.size(), fromAt);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return false;
        if (n == 0) return true;
        for (ssize_t done = 0; done < n;) {
            const ssize_t w = ::pwrite(to, buffer.data() + done, static_cast<size_t>(n - done), toAt + done);
            if (w < 0 && errno == EINTR) continue;
            if (w <= 0) return false;
            done += w;
        }
        fromAt += n;
        toAt += n;
    }
}

}  // namespace

Status openCache(const std::string& folder) {
    const std::string hint = "give a folder this build can write, or no cache folder to build without one";
    if (folder.empty()) return cannotWrite("''", "the cache folder is empty", hint);
    std::error_code ec;
    if (fs::exists(folder, ec) && !fs::is_directory(folder, ec))
        return cannotWrite(folder, "is not a folder (a cache is a folder of entries)", hint);
    fs::create_directories(folder, ec);
    if (ec || !fs::is_directory(folder, ec)) return cannotWrite(folder, "cannot be created as a folder", hint);
    if (::access(folder.c_str(), W_OK | X_OK) != 0) return cannotWrite(folder, "is not a writable folder", hint);
    return Done{};
}

std::string cacheEntryPath(const std::string& folder, const std::string& key, const std::string& output) {
    return (fs::path(folder) / detail::entryName(key, output)).string();
}

Result<CacheLookup> restoreFromCache(const std::string& folder, const std::string& key, const std::string& output,
                                     const std::string& destination, bool markUsed) {
    const std::string path = cacheEntryPath(folder, key, output);
    CacheLookup lookup;
    const Fd entry(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
    struct stat st {};
    if (entry.fd < 0 || ::fstat(entry.fd, &st) != 0 || !S_ISREG(st.st_mode)) return lookup;  // not there: a miss
    std::string text(kHeaderBytes, '\0');
    const ssize_t got = ::pread(entry.fd, text.data(), text.size(), 0);
    text.resize(got > 0 ? static_cast<size_t>(got) : 0);
    std::uint64_t size = 0;
    std::string hash;
    lookup.rejected = detail::judgeEntryHeader(text, static_cast<std::uint64_t>(st.st_size), key, output, size, hash);
    if (!lookup.rejected.empty()) return lookup;

    TemporaryFile temp(destination);
    {
        const Fd out(::open(temp.path().c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666));
        if (out.fd < 0) return cannotWrite(destination, std::string("cannot be written: ") + std::strerror(errno));
        // A read that fails (an entry another builder evicted on a network share) is no hit; a write that
        // fails (a full disk) fails the bake that follows too, with its own error.
        if (!copyToEnd(entry.fd, kHeaderBytes, out.fd, 0)) {
            if (errno == ENOSPC || errno == EDQUOT)
                return cannotWrite(destination, std::string("cannot be written: ") + std::strerror(errno), "free some disk space");
            lookup.rejected = std::string("it could not be copied: ") + std::strerror(errno);
            return lookup;
        }
    }
    // What landed is judged, not what was read: a clone or a copy that went wrong is caught too.
    auto landed = hashFile(temp.path());
    std::error_code ec;
    if (!landed || *landed != hash || fs::file_size(temp.path(), ec) != size) {
        lookup.rejected = "its bytes do not match the hash in its header (altered)";
        return lookup;
    }
    if (Status s = temp.commit(); !s) return s.error();
    if (markUsed) ::utimensat(AT_FDCWD, path.c_str(), nullptr, 0);  // just used: the last to go (a read-only share keeps its time)
    lookup.hit = true;
    lookup.hash = hash;
    return lookup;
}

Status storeInCache(const std::string& folder, const std::string& key, const std::string& output,
                    const std::string& source, const std::string& hash) {
    const std::string path = cacheEntryPath(folder, key, output);
    std::error_code ec;
    fs::create_directories(fs::path(path).parent_path(), ec);
    const Fd in(::open(source.c_str(), O_RDONLY | O_CLOEXEC));
    struct stat st {};
    if (in.fd < 0 || ::fstat(in.fd, &st) != 0) return badInput(source, "cannot be read to store it in the cache");
    const std::string header = detail::entryHeader(key, output, static_cast<std::uint64_t>(st.st_size), hash);
    if (header.empty()) return cannotWrite(path, "the entry's header would not fit its 4096 bytes (a very long output name)");
    TemporaryFile temp(path, TemporaryScope::SharedFolder);
    {
        const Fd out(::open(temp.path().c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666));
        if (out.fd < 0 || ::pwrite(out.fd, header.data(), header.size(), 0) != kHeaderBytes ||
            !copyToEnd(in.fd, 0, out.fd, kHeaderBytes))
            return cannotWrite(path, std::string("could not be written: ") + std::strerror(errno), "check free space");
    }
    return temp.commit();
}

CacheTrim trimCache(const std::string& folder, std::uint64_t limit) {
    struct Entry {
        fs::file_time_type used;
        std::uint64_t bytes;
        fs::path path;
    };
    std::vector<Entry> entries;
    CacheTrim trim;
    const auto dayAgo = fs::file_time_type::clock::now() - std::chrono::hours(24);
    // Every step with an error code, never an exception: another builder may remove files (or a whole
    // subfolder's last entry) while this one looks.
    std::error_code ec;
    for (fs::directory_iterator sub(folder, ec), end; !ec && sub != end; sub.increment(ec)) {
        std::error_code subEc;
        if (!sub->is_directory(subEc)) continue;
        for (fs::directory_iterator file(sub->path(), subEc); !subEc && file != end; file.increment(subEc)) {
            std::error_code fileEc;
            const std::string name = file->path().filename().string();
            if (!file->is_regular_file(fileEc)) continue;
            const auto used = fs::last_write_time(file->path(), fileEc);
            if (fileEc) continue;
            const std::uint64_t bytes = file->file_size(fileEc);
            if (fileEc) continue;
            if (name.starts_with(".") && name.find(".hptmp-") != std::string::npos) {
                if (used < dayAgo) fs::remove(file->path(), fileEc);  // a killed writer's; a live one renames within the day
                continue;
            }
            if (file->path().extension() == ".bin") entries.push_back({used, bytes, file->path()});
        }
    }
    // Oldest first; the name breaks ties, so two builders trimming at once choose the same entries.
    std::sort(entries.begin(), entries.end(),
              [](const Entry& a, const Entry& b) { return a.used != b.used ? a.used < b.used : a.path < b.path; });
    for (const Entry& e : entries) trim.bytesLeft += e.bytes;
    for (const Entry& e : entries) {
        if (trim.bytesLeft <= limit) break;
        std::error_code removeEc;
        fs::remove(e.path, removeEc);  // gone already (another builder trimmed it): it is out of the total all the same
        trim.bytesLeft -= e.bytes;
        if (!removeEc) ++trim.removed;
    }
    return trim;
}

}  // namespace heightpack
