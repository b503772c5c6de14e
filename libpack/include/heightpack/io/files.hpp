// Files as the tools handle them: outputs that appear whole or not at all, checks before any work,
// frame sequences, and the names that choose a format.
#pragma once

#include <atomic>
#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "heightpack/core/result.hpp"

namespace heightpack {

// Whether a and b name the same existing file: same device and inode, so hard links, symbolic links
// and other spellings of one path all count. False when either does not exist.
bool sameFile(const std::string& a, const std::string& b);

// Copies the file at from to to, atomically (to appears whole or not at all).
Status copyFile(const std::string& from, const std::string& to);

// Checks, before any work, that path can be written: it is not empty, its folder exists and is
// writable, and anything already there is a regular file that is not read-only (a folder, a symbolic
// link, a device, FIFO or socket is refused). Fails with CannotWrite naming the problem.
Status checkWritable(const std::string& path);

// Whether path can be written once the folders above it that are missing are made: the nearest existing
// one is a writable folder, and path itself is not a folder or a read-only file. Creates nothing.
Status checkOutputPath(const std::filesystem::path& path);

// Writes text to path atomically (a temporary file beside it, renamed into place), after checking that
// path can be written (checkWritable: its folder must exist).
Status writeTextFile(const std::string& path, const std::string& text);

// An exclusive lock on the file at path (created when missing), held from construction to destruction:
// of the workers that would make one shared file (threads of one build, or a plan's processes run side by
// side), one makes it while the others wait, then find it made. Advisory (flock), so only workers that
// take it are kept apart. Where the file cannot be opened or its file system grants no locks, nothing is
// held (locked() is false) and each worker makes the file for itself: slower, never wrong.
class FileLock {
public:
    explicit FileLock(const std::string& path);
    ~FileLock();
    FileLock(const FileLock&) = delete;
    FileLock& operator=(const FileLock&) = delete;
    bool locked() const { return fd_ >= 0; }

private:
    int fd_ = -1;
};

// Sequences of frames are numbered files: NAME.0000.EXT, NAME.0001.EXT, ... The file frame f of n goes
// to: path itself when n is 1, else NAME.FFFF.EXT. A path NAME.####.EXT (four '#', as compositing tools
// write a sequence) means the same as NAME.EXT, for inputs and outputs alike.
std::string frameFileName(const std::string& path, int frame, int frames);

// The files a path names: itself when it exists; else, when NAME.0000.EXT exists, every consecutive
// frame from there; else itself (so that loading it reports the missing file).
std::vector<std::string> expandSequence(const std::string& path);

// Removes the temporary files in folder that a heightpack process killed mid-write (SIGKILL, power
// loss) left behind: those whose writing process no longer runs; with stem, only those of outputs
// named STEM.EXT. Every atomic write calls it for its own output first. Returns how many it removed.
int removeStaleTemporaryFiles(const std::string& folder, const std::string& stem = {});

// Removes every temporary file an unfinished write in this process has open. Async-signal-safe: meant
// for a SIGINT/SIGTERM handler, so an interrupted run leaves nothing behind.
void removePendingTemporaryFiles();

// A file name's extension in lower case, with its dot (".exr"); empty when it has none. Formats are
// chosen and checked by it, and "MAP.EXR" is an EXR too.
std::string lowerExtension(const std::filesystem::path& path);

// A temporary file beside the final output (same folder, so rename is atomic; same extension, so
// libraries that choose a format by name still see it). commit() renames it over the output; otherwise
// the destructor removes it. While it exists its path is registered for removePendingTemporaryFiles().
// Given a path that is itself a pending temporary file (a StagedOutputs frame), it writes that path
// directly and commit() leaves the move to the staged file's owner: one temporary name per output.
// In a SharedFolder (a cache that builders on other machines write at once, over NFS or SMB) the name
// also carries this machine's name, so two machines' writers never share a temporary, and the leftovers
// of killed writers are not removed by process id: another machine's process is not this one's to see.
enum class TemporaryScope { ThisMachine, SharedFolder };
class TemporaryFile {
public:
    explicit TemporaryFile(const std::string& finalPath, TemporaryScope scope = TemporaryScope::ThisMachine);
    ~TemporaryFile();
    TemporaryFile(const TemporaryFile&) = delete;
    TemporaryFile& operator=(const TemporaryFile&) = delete;

    const std::string& path() const { return path_; }
    // Moves the finished file into place, keeping the permissions of a file it replaces.
    Status commit();

private:
    std::string finalPath_;
    std::string path_;
    int slot_ = -1;
    bool committed_ = false;
    bool inPlace_ = false;  // finalPath is a staged output: written where it is, moved by its own owner
};

// Starts the disk writes of a file while it is still being written (Linux: sync_file_range), so that the
// fsync TemporaryFile::commit makes before its rename waits for the last bytes only, not for them all (a
// 268 MB synth output spent 0.17 s there). A writer calls wrote(n) after each n bytes it wrote, from any
// thread; every 8 MB the pages written so far are sent to the disk while the writer goes on. Where the file
// cannot be opened or the call is missing, nothing happens: commit's fsync still writes everything.
class EarlyWriteback {
public:
    explicit EarlyWriteback(const std::string& path);
    ~EarlyWriteback();
    EarlyWriteback(const EarlyWriteback&) = delete;
    EarlyWriteback& operator=(const EarlyWriteback&) = delete;
    void wrote(size_t bytes);

private:
    int fd_ = -1;
    std::atomic<size_t> unsent_{0};
};

// The outputs of a sequence, written under temporary names and moved into place together once every
// frame has succeeded. A bad frame k then leaves the folder as it was (frames 0..k-1 of an earlier run
// stay, none of this run's appear), instead of half a new sequence beside half an old one.
class StagedOutputs {
public:
    // The path to write in place of finalPath: a TemporaryFile beside it.
    const std::string& stage(const std::string& finalPath);
    // Moves every staged file into place, in the order staged. Staged paths nothing was written to are
    // an internal error: a job that succeeded always writes its output.
    Status commit();

private:
    std::vector<std::unique_ptr<TemporaryFile>> files_;
};

}  // namespace heightpack
