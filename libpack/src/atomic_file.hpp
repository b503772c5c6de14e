// Internal: outputs that appear whole or not at all.
#pragma once

#include <string>

#include "heightpack/result.hpp"

namespace heightpack::detail {

// A temporary file beside the final output (same folder, so rename is atomic; same extension, so
// libraries that choose a format by name still see it). commit() renames it over the output; otherwise
// the destructor removes it. While it exists its path is registered for removePendingTemporaryFiles().
class TemporaryFile {
public:
    explicit TemporaryFile(const std::string& finalPath);
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
};

}  // namespace heightpack::detail
