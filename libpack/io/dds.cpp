// DDS files with the DX10 extended header (Microsoft's "DDS file layout" and DDS_HEADER_DXT10), written
// and read by heightpack itself: magic "DDS ", the 124-byte DDS_HEADER (pixel format FourCC "DX10"), the
// 20-byte DDS_HEADER_DXT10 (DXGI format, TEXTURE2D, array size: 1, or the layers of an array), then each
// layer's every level, level 0 first, rows tightly packed (an array: layer 0's whole chain, then layer 1's).
//
// DDS has no key/value store. What heightpack records goes into nine of the header's eleven reserved
// words (dwReserved1; NVIDIA's tools use words 9 and 10, which stay zero):
//   [0] 'HPCK'  [1] record version 1  [2] layout (1 neighbour4, 2 plain, 3 normal, 4 fresnel, 5 normalXY,
//       0 other)
//   [3] wrap (1 periodic, 2 clamp)  [4] heightScale  [5] heightOffset (floats, when [6] bit 0)
//   [6] flags: bit 0 height scale/offset present, bit 1 normalisation present, bit 2 an array's layers
//       Dx, Dy follow the heights, bit 3 an array's last layer is Foam (so the layers are, in this fixed
//       order, heights, then Dx, Dy, then Foam: the order heightpack:layers names in a KTX2)
//   [7] normalised offset  [8] normalised scale (uint16: value = offset + scale * u / 65535)
// and, flagged in [6], three floats in the header's words that Microsoft's layout leaves unused (dwCaps3,
// dwCaps4, dwReserved2): bit 4 the tile width in metres in dwCaps3, bit 5 the height range (metres per
// stored unit) in dwCaps4, bit 6 a sequence's loop period in seconds in dwReserved2.
// Everything else the EXR header and KTX2 key/values carry (filter, source, hash, version, ...) is lost.
#include <algorithm>
#include <array>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "heightpack/io/attributes.hpp"
#include "heightpack/io/files.hpp"
#include "heightpack/io/gpu_texture.hpp"
#include "heightpack/io/texture_description.hpp"
#include "heightpack/io/texture_write.hpp"
#include "level_write.hpp"
#include "texel_encode.hpp"

namespace heightpack {

using detail::readLe32;

namespace {

constexpr std::uint32_t fourCC(char a, char b, char c, char d) {
    return std::uint32_t(std::uint8_t(a)) | std::uint32_t(std::uint8_t(b)) << 8 | std::uint32_t(std::uint8_t(c)) << 16 |
           std::uint32_t(std::uint8_t(d)) << 24;
}
constexpr std::uint32_t kMagic = fourCC('D', 'D', 'S', ' ');
constexpr std::uint32_t kDx10 = fourCC('D', 'X', '1', '0');
constexpr std::uint32_t kRecord = fourCC('H', 'P', 'C', 'K');
constexpr size_t kDataStart = 4 + 124 + 20;

// dwFlags, ddspf.dwFlags, dwCaps and the DX10 resource dimension.
constexpr std::uint32_t kCaps = 0x1, kHeight = 0x2, kWidth = 0x4, kPitch = 0x8, kPixelFormat = 0x1000,
                        kMipMapCount = 0x20000;
constexpr std::uint32_t kLinearSize = 0x80000;
constexpr std::uint32_t kFourCCFlag = 0x4;
constexpr std::uint32_t kCapsComplex = 0x8, kCapsTexture = 0x1000, kCapsMipMap = 0x400000;
constexpr std::uint32_t kTexture2D = 3;

// The record's layout codes, 1 and up, in this order (the header's words); new layouts only ever join at the end.
const std::array<LayoutWord, 5> kLayouts = {{{TextureKind::Heights, Layout::Neighbour4},
                                             {TextureKind::Heights, Layout::Plain},
                                             {TextureKind::Normals, Layout::Rgb},
                                             {TextureKind::FresnelRamp, std::nullopt},
                                             {TextureKind::Normals, Layout::Xy}}};
// The record's wrap codes, 1 and up, in this order.
constexpr std::array<Wrap, 2> kWraps = {Wrap::Periodic, Wrap::Clamp};

// Record flags.
constexpr std::uint32_t kScaleOffsetFlag = 1, kNormalisationFlag = 2, kShiftFlag = 4, kFoamFlag = 8;
// The units, each a float in a DDS_HEADER word (from its start, after the magic) that is otherwise unused.
struct UnitWord {
    AttributeKey<float> key;
    std::uint32_t flag;
    int word;
};
constexpr std::array<UnitWord, 3> kUnitWords = {UnitWord{attr::tileWidth, 16, 28}, UnitWord{attr::heightRange, 32, 29},
                                                UnitWord{attr::loopPeriod, 64, 30}};

// The layers the record's flags name, in their fixed order.
std::vector<std::string> recordedLayers(std::uint32_t flags) {
    std::vector<std::string> names = {layerName::heights};
    if (flags & kShiftFlag) names.insert(names.end(), {layerName::dx, layerName::dy});
    if (flags & kFoamFlag) names.emplace_back(layerName::foam);
    return names;
}

std::uint32_t floatBits(float v) {
    std::uint32_t u;
    std::memcpy(&u, &v, 4);
    return u;
}
float bitsFloat(std::uint32_t u) {
    float v;
    std::memcpy(&v, &u, 4);
    return v;
}
// A value's code in a record table, 0 for none (a value the table does not hold).
template <class T, size_t N>
std::uint32_t codeOf(const std::array<T, N>& values, const std::optional<T>& value) {
    for (size_t i = 0; i < N; ++i)
        if (value == values[i]) return std::uint32_t(i + 1);
    return 0;
}

}  // namespace

Status writeDds(const std::string& path, const ChainToWrite& content, const TextureWriteOptions& options) {
    auto storage = planTexelStorage({path, Container::Dds}, content, options);
    if (!storage) return storage.error();
    return writeDds(path, content, options, storage->plan);
}

Status writeDds(const std::string& path, const ChainToWrite& content, const TextureWriteOptions& options,
                 const WritePlan& decided) {
    if (Status s = checkWritable(path); !s) return s;
    if (options.storage.supercompression != Supercompression::None)
        return cannotWrite(path, "DDS has no supercompression", "write it uncompressed, or as KTX2");
    // An array's layers: only the fixed order the record's flags can name.
    std::uint32_t layerFlags = 0;
    for (const std::string& n : content.layerNames) {
        if (n == layerName::dx) layerFlags |= kShiftFlag;
        if (n == layerName::foam) layerFlags |= kFoamFlag;
    }
    if (!content.layerNames.empty() && content.layerNames != recordedLayers(layerFlags))
        return Error{ErrorKind::Internal, path, "internal error: a DDS records only the layers heights, Dx, Dy, Foam, in that order",
                     "please report this"};
    const detail::EncodePlan plan = detail::encodePlanOf(content, options, decided);
    const TexelFormatInfo& f = plan.format;
    const int layers = content.layerCount();

    std::array<std::uint32_t, 1 + 31 + 5> h{};  // magic, DDS_HEADER, DDS_HEADER_DXT10
    std::uint32_t* header = h.data() + 1;
    h[0] = kMagic;
    header[0] = 124;
    header[1] = kCaps | kHeight | kWidth | kPitch | kPixelFormat | kMipMapCount;
    header[2] = static_cast<std::uint32_t>(content.height);
    header[3] = static_cast<std::uint32_t>(content.width);
    // Level 0's pitch, or for a block format its whole size (DDSD_LINEARSIZE in place of DDSD_PITCH).
    header[4] = static_cast<std::uint32_t>(f.isBlock() ? detail::imageBytes(f, content.width, content.height)
                                                      : size_t(content.width) * f.bytesPerTexel());
    if (f.isBlock()) header[1] = (header[1] & ~kPitch) | kLinearSize;
    header[6] = static_cast<std::uint32_t>(plan.levels);
    std::uint32_t* reserved = header + 7;
    Attributes text = detail::attributesAsText(content.attributes);
    reserved[0] = kRecord;
    reserved[1] = 1;
    // The words the chain's attributes hold, read back through their one table each.
    reserved[2] = codeOf(kLayouts, parseLayoutWord(findAttribute(text, attr::layout)));
    reserved[3] = codeOf(kWraps, enumFromAttribute<Wrap>(findAttribute(text, attr::wrap)));
    for (const ExrAttribute& a : content.attributes) {
        if (!std::holds_alternative<float>(a.value)) continue;
        if (a.name == attr::heightScale.name) reserved[4] = floatBits(std::get<float>(a.value)), reserved[6] |= kScaleOffsetFlag;
        if (a.name == attr::heightOffset.name) reserved[5] = floatBits(std::get<float>(a.value)), reserved[6] |= kScaleOffsetFlag;
        for (const UnitWord& u : kUnitWords)
            if (a.name == u.key.name) header[u.word] = floatBits(std::get<float>(a.value)), reserved[6] |= u.flag;
    }
    reserved[6] |= layerFlags;
    if (plan.normalisation) {
        reserved[6] |= kNormalisationFlag;
        reserved[7] = floatBits(plan.normalisation->offset);
        reserved[8] = floatBits(plan.normalisation->scale);
    }
    std::uint32_t* pf = header + 18;
    pf[0] = 32;
    pf[1] = kFourCCFlag;
    pf[2] = kDx10;
    header[26] = kCapsTexture | (plan.levels > 1 ? kCapsComplex | kCapsMipMap : 0);
    std::uint32_t* dx10 = header + 31;
    dx10[0] = f.dxgiFormat;
    dx10[1] = kTexture2D;
    dx10[2] = 0;  // not a cube map
    dx10[3] = static_cast<std::uint32_t>(layers);  // array size
    dx10[4] = 0;  // alpha mode unknown: alpha holds heights or a normal's w, not coverage

    // Each layer's levels from level 0, one layer's chain after another, right after the headers.
    std::vector<std::uint8_t> head(h.size() * 4);
    std::memcpy(head.data(), h.data(), head.size());  // little-endian words, as the file holds them
    if (f.isBlock()) {  // encoded when planned: each layer's levels in turn after the headers
        const BlockLevels* blocks = plan.blocks.get();
        if (!blocks || blocks->images.size() != size_t(layers) * size_t(plan.levels))
            return Error{ErrorKind::Internal, path, "internal error: a block format was not encoded when it was planned",
                         "please report this"};
        for (const std::vector<std::uint8_t>& image : blocks->images) head.insert(head.end(), image.begin(), image.end());
        if (options.progress) options.progress(1.0);
        return writeTextFile(path, std::string(head.begin(), head.end()));
    }
    std::vector<detail::PlacedImage> images;
    std::uint64_t offset = head.size();
    for (int pass = 0; pass < layers * plan.levels; ++pass) {
        const int layer = pass / plan.levels, level = pass % plan.levels;
        images.push_back({layer, level, offset});
        offset += std::uint64_t(mipLevelSide(content.width, level)) * mipLevelSide(content.height, level) *
                  f.bytesPerTexel();
    }
    TemporaryFile temp(path);
    if (Status s = detail::writePlacedImages(path, temp.path(), head, images, content, plan, options.threads,
                                             options.progress);
        !s)
        return s;
    return temp.commit();
}

namespace detail {

Result<GpuTexture> readDds(const std::string& path) {
    auto read = readWholeFile(path);
    if (!read) return read.error();
    const std::vector<std::uint8_t>& b = *read;
    auto corrupt = [&](const std::string& what) {
        return badInput(path, "is not a DDS file heightpack can read: " + what,
                        "write it again with heightpack, or check that it was copied whole");
    };
    if (b.size() < kDataStart || readLe32(b.data()) != kMagic) return corrupt("no DDS magic");
    const std::uint8_t* header = b.data() + 4;
    auto word = [&](int i) { return readLe32(header + 4 * i); };
    if (word(0) != 124 || word(18) != 32) return corrupt("its header sizes are wrong");
    if (!(word(19) & kFourCCFlag) || word(20) != kDx10) return corrupt("it has no DX10 extended header");
    GpuTexture t;
    t.container = Container::Dds;
    const auto format = texelFormatFromDxgi(word(31));
    if (!format) return corrupt("DXGI format " + std::to_string(word(31)) + " is not one heightpack writes");
    t.format = *format;
    const TexelFormatInfo& f = texelFormatInfo(t.format);
    if (word(32) != kTexture2D || (word(33) & 0x4)) return corrupt("it is not a 2D texture or array");
    if (word(34) > 64) return corrupt("it lists " + std::to_string(word(34)) + " layers, more than heightpack writes");
    const int layers = word(34) > 1 ? int(word(34)) : 1;
    const std::uint32_t height = word(2), width = word(3);
    if (width == 0 || height == 0 || width > 65536 || height > 65536) return corrupt("its size is out of range");
    t.width = int(width);
    t.height = int(height);
    const int levels = (word(1) & kMipMapCount) && word(6) > 0 ? int(std::min<std::uint32_t>(word(6), 64)) : 1;
    if (levels > mipLevelCount(t.width, t.height)) return corrupt("it lists more levels than its size allows");

    std::uint32_t flags = 0;  // the record's, when it has one
    if (word(7) == kRecord && word(8) == 1) {
        const std::uint32_t layout = word(9), wrap = word(10);
        flags = word(13);
        // Code 0: not recorded; a code past the tables is a damaged record.
        if (layout > kLayouts.size() || wrap > kWraps.size())
            return badInput(path, std::string("its heightpack record's ") + (layout > kLayouts.size() ? attr::layout.name : attr::wrap.name) +
                                      " code " + std::to_string(layout > kLayouts.size() ? layout : wrap) + " is not one heightpack writes",
                            "write the texture again");
        if (layout >= 1) t.keyValues.emplace_back(attr::layout.name, layoutWord(kLayouts[layout - 1]));
        if (wrap >= 1) t.keyValues.emplace_back(attr::wrap.name, attributeText(kWraps[wrap - 1]));
        if (flags & kScaleOffsetFlag) {
            t.keyValues.emplace_back(attr::heightScale.name, floatText(bitsFloat(word(11))));
            t.keyValues.emplace_back(attr::heightOffset.name, floatText(bitsFloat(word(12))));
        }
        for (const UnitWord& u : kUnitWords)
            if (flags & u.flag) t.keyValues.emplace_back(u.key.name, floatText(bitsFloat(word(u.word))));
        if ((flags & kNormalisationFlag) && (f.kind == ComponentKind::Unorm16 || f.isBlock())) {
            t.normalisation = Normalisation{bitsFloat(word(14)), bitsFloat(word(15))};
            t.keyValues.emplace_back(attr::normalisedOffset.name, floatText(t.normalisation->offset));
            t.keyValues.emplace_back(attr::normalisedScale.name, floatText(t.normalisation->scale));
        }
    }
    if (layers > 1) {
        // The layers the flags name, when they are this many; the attributes a KTX2 holding the same
        // layers records: the companions laid out as the heights are.
        const std::vector<std::string> recorded = recordedLayers(flags);
        const bool named = int(recorded.size()) == layers;
        t.layerNames = named ? recorded : layerNamesOf("", layers);
        t.keyValues.emplace_back(attr::layers.name, layerList(t.layerNames));
        const std::string heights = findAttribute(t.keyValues, attr::layout);
        if (named && (flags & kShiftFlag)) t.keyValues.emplace_back(attr::shift.name, heights);
        if (named && (flags & kFoamFlag)) t.keyValues.emplace_back(attr::foam.name, heights);
    }
    // Each layer's chain in turn; gathered level by level, as a KTX2 level holds its layers.
    t.levelBytes.resize(size_t(levels));
    size_t at = kDataStart;
    for (int pass = 0; pass < layers * levels; ++pass) {
        const int level = pass % levels;
        const int w = mipLevelSide(t.width, level), h = mipLevelSide(t.height, level);
        const size_t n = imageBytes(f, w, h);
        if (n > b.size() - at) return corrupt("level " + std::to_string(level) + " is truncated");
        t.levelBytes[size_t(level)].insert(t.levelBytes[size_t(level)].end(), b.begin() + std::ptrdiff_t(at),
                                           b.begin() + std::ptrdiff_t(at + n));
        at += n;
    }
    for (int level = 0; level < levels; ++level)
        t.levels.push_back(decodeLayers(f, t.levelBytes[size_t(level)].data(), mipLevelSide(t.width, level),
                                        mipLevelSide(t.height, level), layers, t.normalisation));
    return t;
}

}  // namespace detail

}  // namespace heightpack
