// Reading height maps (any format OpenImageIO reads) and writing tiled, mip-mapped float EXRs, atomically.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "heightpack/image.hpp"
#include "heightpack/result.hpp"

namespace heightpack {

// Which channel of a colour input holds the height. Named: the channel LoadOptions::channelName names
// (an EXR layer's "height.Y", "Z", "depth"); the others find the channel by its usual names, then by position.
enum class ChannelSelect { Auto, R, G, B, A, Luma, Named };
// "r", "g", "b", "a", "luma"; nullopt for anything else (which a caller may take as a channel name).
std::optional<ChannelSelect> parseChannelSelect(std::string_view name);

struct LoadOptions {
    // Auto takes a one-channel image (or grey + alpha), or the channel named Y of any image, and
    // refuses a colour image.
    // A heightpack texture (packed neighbour4 or plain) gives its height channel, R or Y, mapped back
    // through its recorded heightScale and heightOffset to the values it was made from.
    ChannelSelect channel = ChannelSelect::Auto;
    std::string channelName;  // with Named: matched exactly, else ignoring case
    // Images larger than this are refused from their header, before any pixel is allocated.
    int maxSide = 32768;
    int64_t maxTexels = int64_t(1) << 28;  // 1 GiB of floats
    // Some decoders (libpng under OpenImageIO 2.4) print their own diagnostics on stderr; what they say
    // also reaches the returned Error. When set, stderr (fd 2) of the whole process is sent to /dev/null
    // while a file is decoded, so a command-line tool keeps its one-line error contract.
    bool silenceDecoderMessages = false;
    int threads = 0;  // 0 = all cores; the decoded heights do not depend on it
};

// What the input file held, for reports and metadata.
struct SourceInfo {
    std::string path;
    std::string format;     // OpenImageIO's format name: "png", "openexr", "tiff", ...
    std::string pixelType;  // "uint8", "uint16", "half", "float", ...
    int width = 0;
    int height = 0;
    int channels = 0;
    std::string channelUsed;  // the name of the channel the heights came from, or "luma"
    // Set when the channel was chosen in a way a person may not expect (alpha of a grey image ignored,
    // a colour choice on a grey image, a heightpack texture read back): one sentence saying what was used.
    std::string channelNote;
    std::string decoder;      // "heightpack-png" (fast path for grey PNGs) or "openimageio"
    // Where the map sits in an animation, if its file says (heightpack:loopPeriod, heightpack:time):
    // carried into what is made from it, so a packed sequence still knows its timing.
    std::string loopPeriod, time;
};

struct LoadedHeights {
    Image heights;  // one channel: 8-bit / 255, 16-bit / 65535, float as is
    SourceInfo source;
};

// Loads the height map at path. Fails with BadInput for a missing, unreadable, corrupt or oversized file,
// a colour image without a channel choice, or non-finite values.
Result<LoadedHeights> loadHeightMap(const std::string& path, const LoadOptions& options = {});

// Checks, before anything is opened, that path names a regular file (not a folder, FIFO, device or
// socket: those would hang or mislead a decoder) that this process may read and that is not empty.
// Fails with BadInput saying which, with a hint.
Status checkReadable(const std::string& path);

// Fails with BadInput naming the first texel of channel `channel` of image that is NaN or infinite;
// `where` (e.g. "level 2") goes before "holds NaN" in the message.
Status checkFinite(const Image& image, const std::string& path, int channel = 0, const std::string& where = {});

// Whether a and b name the same existing file: same device and inode, so hard links, symbolic links
// and other spellings of one path all count. False when either does not exist.
bool sameFile(const std::string& a, const std::string& b);

// A 64-bit hash (XXH3) of an image's texel values, as 16 hex digits; identical pixels give the same hash.
std::string hashPixels(const Image& image);

// EXR compressions offered: the lossless ones, since heights must come back exactly as computed.
enum class Compression { None, Rle, Zips, Zip, Piz };
const char* compressionName(Compression compression);
std::optional<Compression> parseCompression(std::string_view name);

// A header attribute: a string or a float.
struct ExrAttribute {
    std::string name;
    std::variant<std::string, float> value;
};

// A tiled, mip-mapped float EXR described by its level-0 size, channel names, and a function that fills
// any band of rows of any level on demand, so the writer never holds more than a band of output.
struct TiledExrContent {
    int width = 0;
    int height = 0;
    std::vector<std::string> channelNames;  // interleaved in this order in the rows fillRows writes
    // Writes `rows` rows of level `level` starting at y0 into dst (levelWidth * channels floats a row).
    std::function<void(int level, int y0, int rows, float* dst)> fillRows;
    std::vector<ExrAttribute> attributes;
};

struct ExrWriteOptions {
    Compression compression = Compression::Zip;
    int tileSize = 64;
    int threads = 0;  // for packing and compressing tiles; 0 = all cores; the bytes do not depend on it
    // Called after each row of tiles with the fraction written so far; may be empty.
    std::function<void(double fraction)> progress;
};

// Writes content as a tiled (tileSize^2), MIPMAP_LEVELS, ROUND_DOWN EXR of 32-bit float channels. The
// file appears at path only once complete: it is written to a temporary file in the same folder and
// renamed, so a failure or interruption leaves no partial file and any existing file untouched.
Status writeTiledExr(const std::string& path, const TiledExrContent& content, const ExrWriteOptions& options);

// A flat (single-level, scanline) image file: a PNG, a TIFF, a scanline EXR, chosen by the extension.
struct FlatImageOptions {
    int bits = 32;          // 8 or 16 (unsigned integer) or 32 (float)
    int srgbChannels = 0;   // the first this many channels are linear colours to encode as sRGB (8/16-bit)
    std::vector<ExrAttribute> attributes;  // metadata; a PNG holds numbers as text
    std::vector<std::string> channelNames; // empty: Y, RGB or RGBA by count
};

// Writes image (1 to 4 channels: Y, RGB or RGBA) atomically, as writeTiledExr does. Integer formats clamp
// to [0,1] and round to nearest; alpha is stored unassociated.
Status writeFlatImage(const std::string& path, const Image& image, const FlatImageOptions& options);

// Copies the file at from to to, atomically (to appears whole or not at all).
Status copyFile(const std::string& from, const std::string& to);

// Checks, before any work, that path can be written: it is not empty, its folder exists and is
// writable, and anything already there is a regular file that is not read-only (a folder, a symbolic
// link, a device, FIFO or socket is refused). Fails with CannotWrite naming the problem.
Status checkWritable(const std::string& path);

// Sequences of frames are numbered files: NAME.0000.EXT, NAME.0001.EXT, ... The file frame f of n goes
// to: path itself when n is 1, else NAME.FFFF.EXT.
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

}  // namespace heightpack
