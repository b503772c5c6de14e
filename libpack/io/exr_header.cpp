// The OpenEXR header judged before OpenEXR reads it: every attribute read the way OpenEXR 3.1's reader
// reads it, the data window against the size limits, and the chunk offset table against the file's size.
#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "image_input.hpp"
#include "input_format.hpp"

namespace heightpack::detail {

namespace {

// A bounds-checked little-endian reader over the header bytes.
struct Cursor {
    const std::vector<unsigned char>& b;
    size_t at = 0;
    bool ok = true;

    bool has(size_t n) const { return ok && at <= b.size() && b.size() - at >= n; }
    uint32_t u32() {
        if (!has(4)) return ok = false, 0;
        const uint32_t v = uint32_t(b[at]) | uint32_t(b[at + 1]) << 8 | uint32_t(b[at + 2]) << 16 | uint32_t(b[at + 3]) << 24;
        at += 4;
        return v;
    }
    int32_t i32() { return static_cast<int32_t>(u32()); }
    // A NUL-terminated name of at most maxLength characters.
    std::string name(size_t maxLength) {
        const size_t start = at;
        while (has(1) && b[at] != 0 && at - start <= maxLength) ++at;
        if (!has(1) || b[at] != 0) return ok = false, std::string();
        return std::string(reinterpret_cast<const char*>(b.data() + start), at++ - start);
    }
};

// The attribute types whose OpenEXR 3.1 reader takes a fixed number of bytes, whatever the size field says.
struct FixedType {
    std::string_view name;
    size_t bytes;
};
constexpr FixedType kFixedTypes[] = {
    {"box2i", 16}, {"box2f", 16}, {"chromaticities", 32}, {"compression", 1}, {"deepImageState", 1},
    {"double", 8}, {"envmap", 1},  {"float", 4},           {"int", 4},          {"keycode", 28},
    {"lineOrder", 1}, {"m33d", 72}, {"m33f", 36},         {"m44d", 128},       {"m44f", 64},
    {"rational", 8}, {"tiledesc", 9}, {"timecode", 8},    {"v2d", 16},         {"v2f", 8},
    {"v2i", 8},     {"v3d", 24},   {"v3f", 12},           {"v3i", 12},
};

// How many bytes OpenEXR 3.1's reader of an attribute takes from the file, starting at value.at, for a
// value whose size field says size; nullopt where that reader would fail on its own (a name with no end).
// Only strings, string vectors and unknown types are read by the size field; a channel list is read to its
// empty name, a float vector in whole floats, a fixed type whole. Where this differs from the size, OpenEXR reads
// every later attribute from another place than the one judged here: that is how a 2 KB file, whose
// channel list ran past its size, made OpenEXR allocate a 2 GB string that no size field claimed.
std::optional<size_t> openExrReadLength(std::string_view type, Cursor value, size_t size, size_t maxName) {
    for (const FixedType& fixed : kFixedTypes)
        if (type == fixed.name) return fixed.bytes;
    if (type == "chlist") {
        const size_t start = value.at;
        while (value.has(1) && value.b[value.at] != 0) {
            value.name(maxName);
            if (!value.ok || !value.has(16)) return std::nullopt;
            value.at += 16;
        }
        if (!value.has(1)) return std::nullopt;
        return value.at + 1 - start;
    }
    if (type == "floatvector") return size - size % 4;
    if (type == "preview") {
        const uint64_t width = value.u32(), height = value.u32();
        return value.ok && width * height * 4 + 8 == size ? std::optional<size_t>(size) : std::nullopt;
    }
    return size;  // string, stringvector (each length checked against the size by OpenEXR), unknown types
}

struct ExrPart {
    bool tiled = false, deep = false;
    bool haveWindow = false;
    int64_t width = 0, height = 0;
    int channels = 0;
    unsigned compression = 0;
    uint32_t tileX = 0, tileY = 0;
    unsigned levelMode = 0, roundUp = 0;
    int64_t chunkCount = -1;  // multi-part files record it
};

int64_t ceilDiv(int64_t a, int64_t b) { return (a + b - 1) / b; }

int64_t levelSize(int64_t size, int level, bool roundUp) {
    const int64_t down = size >> level;
    const bool exact = (down << level) == size;
    return std::max<int64_t>(1, roundUp && !exact ? down + 1 : down);
}

int levelCount(int64_t size, bool roundUp) {
    int levels = 1;
    while (levelSize(size, levels - 1, roundUp) > 1) ++levels;
    return levels;
}

// How many chunks (and so offset-table entries) a part of this shape has: a lower bound on the file's size.
int64_t chunksOf(const ExrPart& p) {
    if (p.chunkCount >= 0) return p.chunkCount;
    if (!p.tiled) {
        static const int64_t linesPerBlock[] = {1, 1, 1, 16, 32, 16, 32, 32, 32, 256};
        const int64_t lines = p.compression < std::size(linesPerBlock) ? linesPerBlock[p.compression] : 1;
        return ceilDiv(p.height, lines);
    }
    const bool up = p.roundUp != 0;
    const int lx = levelCount(p.width, up), ly = levelCount(p.height, up);
    int64_t chunks = 0;
    const auto tiles = [&](int x, int y) {
        return ceilDiv(levelSize(p.width, x, up), p.tileX) * ceilDiv(levelSize(p.height, y, up), p.tileY);
    };
    if (p.levelMode == 0) return tiles(0, 0);
    if (p.levelMode == 1)
        for (int l = 0; l < std::max(lx, ly); ++l) chunks += tiles(std::min(l, lx - 1), std::min(l, ly - 1));
    else
        for (int x = 0; x < lx; ++x)
            for (int y = 0; y < ly; ++y) chunks += tiles(x, y);
    return chunks;
}

}  // namespace

Status judgeExrHeader(const std::string& path, const std::vector<unsigned char>& bytes, const SizeLimits& limits) {
    const auto damaged = [&](const std::string& what) {
        return badInput(path, "is a damaged OpenEXR file: " + what, "export it again");
    };
    Cursor c{bytes, 4};
    const uint32_t version = c.u32();
    if (!c.ok || (version & 0xFF) != 2) return damaged("its version field is not 2");
    const bool multiPart = version & 0x1000, longNames = version & 0x400;
    if (version & 0x800) return badInput(path, "is a deep OpenEXR file, not a height map", kExportHint);
    const size_t maxName = longNames ? 255 : 31;
    std::vector<ExrPart> parts;
    while (true) {
        if (multiPart && c.has(1) && bytes[c.at] == 0) break;  // the empty header that ends the list
        ExrPart part;
        part.tiled = !multiPart && (version & 0x200);
        while (true) {
            if (!c.has(1)) return damaged("its header runs past the end of the file");
            if (bytes[c.at] == 0) {
                ++c.at;
                break;
            }
            const std::string name = c.name(maxName), type = c.name(maxName);
            const int32_t size = c.i32();
            const std::string shown = "attribute '" + name.substr(0, 64) + "'";
            if (!c.ok || size < 0 || !c.has(size_t(size))) return damaged(shown + " claims more bytes than the file holds");
            // OpenEXR 3.1.5 reads an ID manifest's length as 8 bytes where it counts 4, and so the rest of the
            // header 4 bytes out of step.
            if (type == "idmanifest")
                return badInput(path, "holds an ID manifest, which the OpenEXR library heightpack reads with misreads",
                                "export it without the ID manifest");
            if (openExrReadLength(type, Cursor{bytes, c.at}, size_t(size), maxName) != size_t(size))
                return damaged(shown + " of type '" + type.substr(0, 32) + "' does not hold the " +
                               std::to_string(size) + " bytes its size claims");
            Cursor value{bytes, c.at};
            if (name == "dataWindow" && type == "box2i") {
                const int64_t x0 = value.i32(), y0 = value.i32(), x1 = value.i32(), y1 = value.i32();
                part.width = x1 - x0 + 1, part.height = y1 - y0 + 1, part.haveWindow = true;
            } else if (name == "channels" && type == "chlist") {
                while (bytes[value.at] != 0) {
                    value.name(maxName);
                    value.at += 16;
                    ++part.channels;
                }
            } else if (name == "compression" && type == "compression") {
                part.compression = bytes[value.at];
            } else if (name == "tiles" && type == "tiledesc") {
                part.tileX = value.u32(), part.tileY = value.u32();
                part.levelMode = bytes[value.at] & 0x0F, part.roundUp = bytes[value.at] >> 4 & 1;
            } else if (name == "type" && type == "string") {
                const std::string kind(reinterpret_cast<const char*>(bytes.data() + c.at), size_t(size));
                part.tiled = kind == "tiledimage", part.deep = kind.rfind("deep", 0) == 0;
            } else if (name == "chunkCount" && type == "int") {
                part.chunkCount = value.i32();
            }
            c.at += size_t(size);
        }
        if (!part.haveWindow) return damaged("its header has no dataWindow");
        if (part.deep) return badInput(path, "is a deep OpenEXR file, not a height map", kExportHint);
        if (part.width <= 0 || part.height <= 0 || part.width > limits.maxSide || part.height > limits.maxSide ||
            part.width * part.height > limits.maxTexels)
            return badInput(path, "claims a data window of " + std::to_string(part.width) + "x" + std::to_string(part.height) +
                                      ", outside what heightpack accepts (" + std::to_string(limits.maxSide) + " texels a side)",
                            "split or downsize the map");
        if (part.channels < 1) return damaged("it has no channels");
        if (part.tiled && (part.tileX == 0 || part.tileY == 0 || part.levelMode > 2))
            return damaged("its tile description is invalid");
        parts.push_back(part);
        if (!multiPart) break;
    }
    // Every chunk has an 8-byte entry in the offset tables that follow the headers.
    int64_t chunks = 0;
    for (const ExrPart& p : parts) chunks += std::max<int64_t>(0, chunksOf(p));
    if (chunks > int64_t(bytes.size() / 8))
        return damaged("its header claims " + std::to_string(chunks) + " chunks, more than its " +
                       std::to_string(bytes.size()) + " bytes can hold");
    return Done{};
}

}  // namespace heightpack::detail
