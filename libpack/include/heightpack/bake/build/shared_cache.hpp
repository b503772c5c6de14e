// The shared cache of built outputs as a folder, local or on a network share, where every builder (two
// artists' machines, CI agents) keeps what it baked under the output's cache key, so another build of the
// same key copies the bytes instead of baking them. Several builders use one folder at once without
// locks (network file systems lack reliable ones): an entry appears whole or not at all (a temporary file
// renamed into place), is verified on the way out (its size and its hash), and a damaged or foreign entry
// is reported and never trusted.
//
// Layout: FOLDER/ab/abcdef...(32 hex digits).bin, one file per entry, named by a hash of the output's key
// and its name. An entry is a 4096-byte header (one JSON line: format, key, output, size, hash; zero
// padding) followed by the output's bytes, so the bytes start on a block boundary and a file system that
// shares blocks (btrfs, XFS) can clone them instead of copying. A server (cache_session.hpp) holds the
// same entries under the same names.
#pragma once

#include <cstdint>
#include <string>

#include "heightpack/bake/build/cache_options.hpp"
#include "heightpack/core/result.hpp"

namespace heightpack {

// Makes the cache folder if it is missing (and the folders above it); fails with CannotWrite when it is
// not a folder (a file is there) or cannot be written.
Status openCache(const std::string& folder);

// The file that holds, or would hold, the output (relative to its output folder) made with key. The
// output's name is part of the address because the key leaves out what the name decides (the container
// its extension chooses, the intermediate's name a synthesised frame records).
std::string cacheEntryPath(const std::string& folder, const std::string& key, const std::string& output);

// What looking in the cache found.
struct CacheLookup {
    bool hit = false;
    std::string hash;      // on a hit: XXH3-128 of the restored bytes, 32 hex digits (what the state records)
    std::string rejected;  // an entry was there and failed verification: why (then it is no hit)
    bool unavailable = false;  // the cache could not be asked (a server down or refusing): no hit, nothing known
};

// Copies the entry of (key, output), if the cache holds a sound one, to destination atomically (a
// temporary file beside it, renamed into place), verifying the copy's size and hash against the entry's
// header, and, when markUsed, marks the entry as just used (its modification time). A missing entry is no hit; a
// damaged or foreign one (another key or output inside, truncated, bytes that do not match their hash) is
// no hit with rejected saying why, and destination is left as it was. Fails only when destination cannot
// be written.
Result<CacheLookup> restoreFromCache(const std::string& folder, const std::string& key, const std::string& output,
                                     const std::string& destination, bool markUsed = true);

// Stores the file at source, whose XXH3-128 is hash, as the entry of (key, output), replacing any entry
// there (a rejected one is so rewritten). Written atomically: readers see the old entry or the whole new
// one. A failure leaves the cache as it was.
Status storeInCache(const std::string& folder, const std::string& key, const std::string& output,
                    const std::string& source, const std::string& hash);

struct CacheTrim {
    int removed = 0;              // entries removed, least recently used first
    std::uint64_t bytesLeft = 0;  // what the entries left hold
};

// Removes the least recently used entries (oldest modification time first) until the entries hold at
// most limit bytes, and the temporary files of writers killed more than a day ago. Another builder may
// trim the same folder at once: a file already gone is skipped.
CacheTrim trimCache(const std::string& folder, std::uint64_t limit);

}  // namespace heightpack
