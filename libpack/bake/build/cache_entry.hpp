// One entry of the shared cache, whichever backend holds it: a 4096-byte header (one JSON line: format,
// key, output, size, hash; zero padding) followed by the output's bytes, addressed by a name made from
// the output's key and its name. Folders keep it at FOLDER/NAME, servers at URL/NAME.
#pragma once

#include <cstdint>
#include <string>

namespace heightpack::detail {

// The output's bytes start on a block boundary, so a file system that shares blocks can clone them.
inline constexpr std::uint64_t kEntryHeaderBytes = 4096;

// Where the entry of (key, output) lives under its cache: "ab/abcdef...(32 hex digits).bin", the first two
// digits a subfolder (ccache's "subdirs" layout), so no folder holds more than a 256th of the entries.
// The output's name is part of it because the key leaves out what the name decides (the container its
// extension chooses, the intermediate's name a synthesised frame records).
std::string entryName(const std::string& key, const std::string& output);

// The header of an entry holding size bytes whose XXH3-128 is hash, padded to kEntryHeaderBytes; empty
// when it would not fit (a very long output name).
std::string entryHeader(const std::string& key, const std::string& output, std::uint64_t size, const std::string& hash);

// Why the entry whose header is text (its first kEntryHeaderBytes, or fewer when it is shorter) and which
// holds entryBytes in all is not a sound one of (key, output), or empty when it is; size and hash are
// then what its bytes must be. Whatever the header holds (a damaged entry, another program's file, a
// server's error page), it is only read, never trusted.
std::string judgeEntryHeader(const std::string& text, std::uint64_t entryBytes, const std::string& key,
                             const std::string& output, std::uint64_t& size, std::string& hash);

}  // namespace heightpack::detail
