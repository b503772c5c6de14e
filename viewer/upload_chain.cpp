#include "upload_chain.hpp"

#include <algorithm>
#include <cstring>

namespace heightpack::view {

UploadChain storeFloats(const std::vector<Image>& levels, ComponentKind kind) {
    UploadChain chain;
    chain.channels = levels.empty() ? 1 : levels[0].channels;
    chain.kind = kind;
    chain.width = levels.empty() ? 0 : levels[0].width;
    chain.height = levels.empty() ? 0 : levels[0].height;
    for (const Image& level : levels) {
        std::vector<std::uint8_t> bytes(level.pixels.size() * (kind == ComponentKind::Float16 ? 2 : 4));
        if (kind == ComponentKind::Float16) {
            for (size_t i = 0; i < level.pixels.size(); ++i) {
                const std::uint16_t h = floatToHalf(level.pixels[i]);
                std::memcpy(bytes.data() + 2 * i, &h, 2);
            }
        } else {
            std::memcpy(bytes.data(), level.pixels.data(), bytes.size());
        }
        chain.levels.push_back(std::move(bytes));
    }
    return chain;
}

UploadChain storeGpuTexture(GpuTexture& texture) {
    const TexelFormatInfo& f = texelFormatInfo(texture.format);
    UploadChain chain;
    chain.channels = f.channels;
    chain.kind = f.kind;
    if (f.isBlock()) chain.blockFormat = texture.format;
    chain.width = texture.width;
    chain.height = texture.height;
    chain.levels = std::move(texture.levelBytes);
    // decodeLevel maps a normalised texel the same way: offset + scale * u / 65535 (a block's u / 255).
    if (f.kind == ComponentKind::Unorm16 || f.isBlock()) chain.decode = texture.normalisation.value_or(Normalisation{});
    return chain;
}

UploadChain unitFloats(const std::vector<Image>& decoded, const Normalisation& decode) {
    std::vector<Image> units = decoded;
    for (Image& level : units)
        for (float& v : level.pixels) v = (v - decode.offset) / decode.scale;
    UploadChain chain = storeFloats(units);
    chain.decode = decode;
    return chain;
}

UploadChain firstChannel(const UploadChain& chain) {
    UploadChain out = chain;
    out.channels = 1;
    const size_t in = chain.bytesPerTexel(), keep = out.bytesPerTexel();
    for (std::vector<std::uint8_t>& level : out.levels) {
        const size_t texels = level.size() / in;
        for (size_t t = 0; t < texels; ++t) std::memmove(level.data() + t * keep, level.data() + t * in, keep);
        level.resize(texels * keep);
    }
    return out;
}

UploadChain packStoredNeighbour4(const UploadChain& plain, Wrap wrap) {
    UploadChain packed = plain;
    packed.channels = 4;
    const size_t b = plain.bytesPerTexel();
    for (size_t l = 0; l < plain.levels.size(); ++l) {
        const int w = plain.levelWidth(int(l)), h = plain.levelHeight(int(l));
        const std::uint8_t* src = plain.levels[l].data();
        std::vector<std::uint8_t>& dst = packed.levels[l];
        dst.assign(size_t(w) * h * 4 * b, 0);
        auto texel = [&](long long x, long long y) {
            return src + (size_t(wrapIndex(y, h, wrap)) * w + size_t(wrapIndex(x, w, wrap))) * b;
        };
        std::uint8_t* out = dst.data();
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x, out += 4 * b) {
                std::memcpy(out, texel(x, y), b);
                std::memcpy(out + b, texel(x + 1, y), b);
                std::memcpy(out + 2 * b, texel(x, y + 1), b);
                std::memcpy(out + 3 * b, texel(x + 1, y + 1), b);
            }
        }
    }
    return packed;
}

GatherAtlas buildGatherAtlas(const UploadChain& plain, Wrap wrap) {
    GatherAtlas atlas;
    UploadChain& t = atlas.texels;
    t.channels = 1;
    t.kind = plain.kind;
    t.decode = plain.decode;
    // Level 0 and its border; the column of the coarser levels beside it.
    const int levels = int(plain.levels.size());
    int columnHeight = 0;
    for (int l = 0; l < levels; ++l) {
        atlas.origins.push_back(l == 0 ? GatherAtlas::Origin{0, 0}
                                       : GatherAtlas::Origin{plain.width + 1, columnHeight});
        if (l > 0) columnHeight += plain.levelHeight(l) + 1;
    }
    t.width = plain.width + 1 + (levels > 1 ? plain.levelWidth(1) + 1 : 0);
    t.height = std::max(plain.height + 1, columnHeight);
    const size_t b = plain.bytesPerTexel();
    std::vector<std::uint8_t> bytes(size_t(t.width) * t.height * b, 0);
    for (int l = 0; l < levels; ++l) {
        const int w = plain.levelWidth(l), h = plain.levelHeight(l);
        const std::uint8_t* src = plain.levels[size_t(l)].data();
        for (int y = 0; y <= h; ++y) {
            for (int x = 0; x <= w; ++x) {
                const size_t from = (size_t(wrapIndex(y, h, wrap)) * w + size_t(wrapIndex(x, w, wrap))) * b;
                const size_t to = (size_t(atlas.origins[size_t(l)].y + y) * t.width + size_t(atlas.origins[size_t(l)].x + x)) * b;
                std::memcpy(bytes.data() + to, src + from, b);
            }
        }
    }
    t.levels.push_back(std::move(bytes));
    return atlas;
}

}  // namespace heightpack::view
