#include "heightpack/io/files.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <string_view>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>


namespace heightpack {

namespace fs = std::filesystem;

namespace {

// Paths of temporary files being written, kept in plain arrays so a signal handler can unlink them
// without allocating or locking.
constexpr int kMaxPending = 256;  // a staged sequence holds one per frame and layer until it commits
constexpr size_t kMaxPath = 4096;
char pendingPath[kMaxPending][kMaxPath];
std::atomic<bool> pendingUsed[kMaxPending];
std::mutex pendingMutex;

}  // namespace

void removePendingTemporaryFiles() {
    for (int i = 0; i < kMaxPending; ++i)
        if (pendingUsed[i].load()) ::unlink(pendingPath[i]);
}

Status checkWritable(const std::string& path) {
    if (path.empty()) return cannotWrite("''", "the output path is empty", "give an output file name");
    std::error_code ec;
    const fs::path target(path);
    if (target.filename().empty()) return cannotWrite(path, "names a folder, not a file", "give an output file name");
    const fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    if (!fs::exists(folder, ec))
        return cannotWrite(path, "folder " + folder.string() + " does not exist", "create it first");
    if (!fs::is_directory(folder, ec))
        return cannotWrite(path, folder.string() + " is not a folder", "choose another output path");
    if (::access(folder.c_str(), W_OK) != 0)
        return cannotWrite(path, "folder " + folder.string() + " is not writable", "choose another output folder");
    struct stat st {};
    if (::lstat(path.c_str(), &st) == 0) {
        if (S_ISDIR(st.st_mode)) return cannotWrite(path, "is a folder", "give an output file name");
        // The rename would replace the link itself with a file, leaving what it points to as it was:
        // neither is what the link's owner meant, so a link is refused rather than guessed about.
        if (S_ISLNK(st.st_mode)) {
            std::string target = fs::read_symlink(path, ec).string();
            return cannotWrite(path, "is a symbolic link" + (target.empty() ? std::string() : " to " + target),
                               "write to the file it points to, or remove the link first");
        }
        // A device, FIFO or socket would be replaced by a regular file (as root, even /dev/full).
        if (!S_ISREG(st.st_mode))
            return cannotWrite(path, "exists and is not a regular file (a device, FIFO or socket)",
                               "choose an output file name");
        // Checked by mode bits too: root passes access(W_OK) on any file, but a read-only output was
        // made read-only on purpose.
        if ((st.st_mode & 0222) == 0 || ::access(path.c_str(), W_OK) != 0)
            return cannotWrite(path, "exists and is read-only", "make it writable or choose another output");
    }
    return Done{};
}

int removeStaleTemporaryFiles(const std::string& folder, const std::string& stem) {
    std::error_code ec;
    int removed = 0;
    const std::string prefix = stem + ".hptmp-";
    for (const fs::directory_entry& entry : fs::directory_iterator(folder.empty() ? "." : folder, ec)) {
        // .STEM.hptmp-PID-N.EXT, as TemporaryFile names them, and any name made of one (earlier versions
        // wrapped a staged frame's name again: ..STEM.hptmp-PID-N.hptmp-PID-M.EXT). The first PID is the
        // process whose death makes the file stale.
        const std::string name = entry.path().filename().string();
        const size_t dots = name.find_first_not_of('.');
        if (dots == 0 || dots == std::string::npos) continue;
        const std::string bare = name.substr(dots);
        const size_t mark = stem.empty() ? bare.find(".hptmp-") : (bare.rfind(prefix, 0) == 0 ? stem.size() : std::string::npos);
        if (mark == std::string::npos) continue;
        if (!entry.is_regular_file(ec) || entry.is_symlink(ec)) continue;
        const long pid = std::strtol(bare.c_str() + mark + 7, nullptr, 10);
        if (pid <= 0 || pid == ::getpid()) continue;
        if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;  // its writer still runs
        if (fs::remove(entry.path(), ec)) ++removed;
    }
    return removed;
}

namespace {

// NAME.####.EXT, the way compositing and DCC tools spell a sequence, as NAME.EXT (which is ours).
std::string withoutFramePlaceholder(const std::string& path) {
    constexpr std::string_view kPlaceholder = ".####";
    const fs::path p(path);
    const std::string stem = p.stem().string();
    if (stem.size() <= kPlaceholder.size() || !stem.ends_with(kPlaceholder)) return path;
    return (p.parent_path() / (stem.substr(0, stem.size() - kPlaceholder.size()) + p.extension().string())).string();
}

}  // namespace

std::string frameFileName(const std::string& path, int frame, int frames) {
    if (frames <= 1) return path;
    const fs::path p(withoutFramePlaceholder(path));
    char number[16];
    std::snprintf(number, sizeof number, ".%04d", frame);
    return (p.parent_path() / (p.stem().string() + number + p.extension().string())).string();
}

std::vector<std::string> expandSequence(const std::string& path) {
    std::error_code ec;
    if (fs::exists(path, ec) || !fs::exists(frameFileName(path, 0, 2), ec)) return {path};
    std::vector<std::string> frames;
    for (int f = 0; f < 100000 && fs::exists(frameFileName(path, f, 2), ec); ++f) frames.push_back(frameFileName(path, f, 2));
    return frames;
}

Status copyFile(const std::string& from, const std::string& to) {
    if (Status s = checkWritable(to); !s) return s;
    TemporaryFile temp(to);
    std::error_code ec;
    fs::copy_file(from, temp.path(), fs::copy_options::overwrite_existing, ec);
    if (ec) return cannotWrite(to, "copying " + from + " failed: " + ec.message(), "check free disk space");
    return temp.commit();
}


namespace {

// Whether path is a temporary file this process has open: a staged output (StagedOutputs) that a
// writer is now asked to write.
bool isPendingTemporary(const std::string& path) {
    std::lock_guard<std::mutex> lock(pendingMutex);
    for (int i = 0; i < kMaxPending; ++i)
        if (pendingUsed[i].load() && path == pendingPath[i]) return true;
    return false;
}

}  // namespace

namespace {

// This machine's name, in the letters, digits and '-' a file name keeps everywhere; "host" if it has none.
std::string machineName() {
    char raw[256] = {};
    ::gethostname(raw, sizeof raw - 1);
    std::string name;
    for (const char* c = raw; *c; ++c) name += std::isalnum(static_cast<unsigned char>(*c)) ? *c : '-';
    return name.empty() ? "host" : name;
}

}  // namespace

TemporaryFile::TemporaryFile(const std::string& finalPath, TemporaryScope scope) : finalPath_(finalPath) {
    // A staged output is written where it is: it is already a temporary file, which its own
    // TemporaryFile moves into place (or removes) later. Wrapping it again would leave temporaries of
    // temporaries after a kill.
    if (isPendingTemporary(finalPath)) {
        path_ = finalPath;
        inPlace_ = true;
        return;
    }
    static std::atomic<unsigned> counter{0};
    const fs::path target(finalPath);
    // Built with append: GCC 12 gives a false -Wrestrict on a chain of operator+ here.
    std::string name = ".";
    name.append(target.stem().string()).append(".hptmp-");
    // "at-HOST-" before the process id: removeStaleTemporaryFiles reads no id there, so it leaves it alone.
    if (scope == TemporaryScope::SharedFolder) name.append("at-").append(machineName()).append("-");
    name.append(std::to_string(::getpid()));
    name.append("-").append(std::to_string(counter++)).append(target.extension().string());
    path_ = (target.parent_path() / name).string();
    // What a killed earlier run left of this same output goes first: one mechanism for every writer.
    if (scope == TemporaryScope::ThisMachine)
        removeStaleTemporaryFiles(target.parent_path().string(), target.stem().string());
    std::lock_guard<std::mutex> lock(pendingMutex);
    for (int i = 0; i < kMaxPending && path_.size() < kMaxPath; ++i) {
        if (!pendingUsed[i].load()) {
            std::memcpy(pendingPath[i], path_.c_str(), path_.size() + 1);
            pendingUsed[i].store(true);
            slot_ = i;
            break;
        }
    }
}

TemporaryFile::~TemporaryFile() {
    if (inPlace_) return;
    if (!committed_) ::unlink(path_.c_str());
    if (slot_ >= 0) pendingUsed[slot_].store(false);
}

EarlyWriteback::EarlyWriteback(const std::string& path) : fd_(::open(path.c_str(), O_RDONLY | O_CLOEXEC)) {}

EarlyWriteback::~EarlyWriteback() {
    if (fd_ >= 0) ::close(fd_);
}

void EarlyWriteback::wrote(size_t bytes) {
    constexpr size_t kStep = size_t(2) << 20;
    size_t unsent = unsent_.fetch_add(bytes) + bytes;
    // One caller of those that pass the step sends the pages: the others see the count already reset.
    if (fd_ < 0 || unsent < kStep || !unsent_.compare_exchange_strong(unsent, 0)) return;
#ifdef __linux__
    // The whole file: pages already on their way are left alone, so each call sends what is new.
    ::sync_file_range(fd_, 0, 0, SYNC_FILE_RANGE_WRITE);
#endif
}

Status TemporaryFile::commit() {
    if (inPlace_) return Done{};  // the staged file's own TemporaryFile flushes and moves it
    struct stat st {};
    if (::stat(finalPath_.c_str(), &st) == 0) ::chmod(path_.c_str(), st.st_mode & 07777);
    // The bytes reach the disk before the name does, and the name before commit() returns: after a
    // power loss the output is the old file or the whole new one (README, "Outputs").
    const int fd = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC);
    // EINVAL / ENOTSUP: a file system without fsync (some FUSE mounts); nothing more can be promised there.
    if (fd < 0 || (::fsync(fd) != 0 && errno != EINVAL && errno != ENOTSUP)) {
        const std::string why = std::strerror(errno);
        if (fd >= 0) ::close(fd);
        return cannotWrite(finalPath_, "cannot flush the finished file to disk: " + why, "check free disk space");
    }
    ::close(fd);
    if (::rename(path_.c_str(), finalPath_.c_str()) != 0)
        return cannotWrite(finalPath_, std::string("cannot move the finished file into place: ") + std::strerror(errno),
                           "check the folder's permissions");
    committed_ = true;
    const std::string folder = fs::path(finalPath_).parent_path().string();
    const int dir = ::open(folder.empty() ? "." : folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dir >= 0) {
        ::fsync(dir);  // some file systems refuse a folder's fsync; the rename has happened either way
        ::close(dir);
    }
    return Done{};
}


bool sameFile(const std::string& a, const std::string& b) {
    struct stat sa {}, sb {};
    if (a.empty() || b.empty() || ::stat(a.c_str(), &sa) != 0 || ::stat(b.c_str(), &sb) != 0) return false;
    return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

std::string lowerExtension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

Status checkOutputPath(const fs::path& path) {
    std::error_code ec;
    if (fs::exists(fs::symlink_status(path, ec))) return checkWritable(path.string());
    // The nearest folder above it that exists must be a writable folder (from the absolute path, so a
    // relative output folder that does not exist yet is judged by the current folder).
    for (fs::path up = fs::absolute(path, ec).parent_path(); !ec && !up.empty(); up = up.parent_path()) {
        if (!fs::exists(up, ec)) {
            if (up == up.parent_path()) break;
            continue;
        }
        if (!fs::is_directory(up, ec))
            return cannotWrite(path.string(), up.string() + " is not a folder", "choose another output folder");
        if (::access(up.c_str(), W_OK) != 0)
            return cannotWrite(path.string(), "folder " + up.string() + " is not writable", "choose another output folder");
        return Done{};
    }
    return cannotWrite(path.string(), "has no existing folder above it", "choose another output folder");
}

Status writeTextFile(const std::string& path, const std::string& text) {
    if (Status s = checkWritable(path); !s) return s;
    TemporaryFile temp(path);
    {
        std::ofstream out(temp.path(), std::ios::binary);
        out << text;
        out.flush();
        if (!out) return cannotWrite(path, "could not be written", "check free disk space");
    }
    return temp.commit();
}

FileLock::FileLock(const std::string& path) {
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) return;
    int granted;
    while ((granted = ::flock(fd_, LOCK_EX)) != 0 && errno == EINTR) {
    }
    if (granted != 0) {
        ::close(fd_);
        fd_ = -1;
    }
}

FileLock::~FileLock() {
    if (fd_ >= 0) ::close(fd_);  // closing the only descriptor releases the lock
}

const std::string& StagedOutputs::stage(const std::string& finalPath) {
    files_.push_back(std::make_unique<TemporaryFile>(finalPath));
    return files_.back()->path();
}

Status StagedOutputs::commit() {
    for (const std::unique_ptr<TemporaryFile>& file : files_)
        if (Status s = file->commit(); !s) return s;
    files_.clear();
    return Done{};
}

}  // namespace heightpack
