#include "exr_write_parts.hpp"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfTiledOutputFile.h>
#include <Imath/half.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <exception>
#include <string>
#include <vector>

#include "heightpack/io/files.hpp"

#include "text.hpp"

namespace heightpack::detail {

Status requireFinite(const std::string& path, const float* values, size_t count, int level) {
    // An exponent of all ones is an infinity or a NaN. No branch per value, so the loop vectorises: the
    // writers check every texel they write, and an early exit made this a scalar scan.
    std::uint32_t nonFinite = 0;
    for (size_t i = 0; i < count; ++i) nonFinite |= (std::bit_cast<std::uint32_t>(values[i]) & 0x7f800000u) == 0x7f800000u;
    if (nonFinite)
        return Error{ErrorKind::Internal, path,
                     "internal error: level " + std::to_string(level) + " holds a non-finite value; nothing was written",
                     "please report this with the command line"};
    return Done{};
}

namespace {

Imf::Compression toImf(Compression compression) {
    switch (compression) {
        case Compression::None: return Imf::NO_COMPRESSION;
        case Compression::Rle: return Imf::RLE_COMPRESSION;
        case Compression::Zips: return Imf::ZIPS_COMPRESSION;
        case Compression::Zip: return Imf::ZIP_COMPRESSION;
        case Compression::Piz: return Imf::PIZ_COMPRESSION;
    }
    return Imf::ZIP_COMPRESSION;
}

}  // namespace

Status writeTiledWithImf(const std::string& finalPath, const std::string& path, const ChainToWrite& content,
                         const ExrWriteOptions& options) {
    Imf::Header header(content.width, content.height);
    header.compression() = toImf(options.compression);
    header.setTileDescription(
        Imf::TileDescription(options.tileSize, options.tileSize, Imf::MIPMAP_LEVELS, Imf::ROUND_DOWN));
    const Imf::PixelType type = options.half ? Imf::HALF : Imf::FLOAT;
    for (const std::string& name : content.channelNames) header.channels().insert(name, Imf::Channel(type));
    for (const ExrAttribute& a : content.attributes) {
        if (const auto* s = std::get_if<std::string>(&a.value))
            header.insert(a.name, Imf::StringAttribute(*s));
        else
            header.insert(a.name, Imf::FloatAttribute(std::get<float>(a.value)));
    }
    try {
        Imf::TiledOutputFile file(path.c_str(), header);
        const int channels = static_cast<int>(content.channelNames.size());
        const size_t texelBytes = sizeof(float) * channels;
        long long rowsTotal = 0, rowsDone = 0;
        for (int level = 0; level < file.numLevels(); ++level) rowsTotal += file.levelHeight(level);
        std::vector<float> band;
        std::vector<Imath::half> halves;
        for (int level = 0; level < file.numLevels(); ++level) {
            const int w = file.levelWidth(level), h = file.levelHeight(level);
            band.resize(static_cast<size_t>(w) * options.tileSize * channels);
            if (options.half) halves.resize(band.size());
            for (int ty = 0; ty < file.numYTiles(level); ++ty) {
                const int y0 = ty * options.tileSize;
                const int rows = std::min(options.tileSize, h - y0);
                content.fillRows(level, y0, rows, band.data());
                if (Status s = requireFinite(finalPath, band.data(), size_t(w) * rows * channels, level); !s) return s;
                Imf::FrameBuffer frame;
                if (options.half) {
                    for (size_t i = 0; i < size_t(w) * rows * channels; ++i) halves[i] = Imath::half(band[i]);
                    const size_t halfTexel = sizeof(Imath::half) * channels;
                    for (int c = 0; c < channels; ++c)
                        frame.insert(content.channelNames[c],
                                     Imf::Slice::Make(Imf::HALF, halves.data() + c, IMATH_NAMESPACE::V2i(0, y0), w,
                                                      rows, halfTexel, halfTexel * w));
                }
                for (int c = 0; c < channels && !options.half; ++c) {
                    frame.insert(content.channelNames[c],
                                 Imf::Slice::Make(Imf::FLOAT, band.data() + c, IMATH_NAMESPACE::V2i(0, y0), w, rows,
                                                  texelBytes, texelBytes * w));
                }
                file.setFrameBuffer(frame);
                // A whole row of tiles per call lets OpenEXR compress them on its thread pool.
                file.writeTiles(0, file.numXTiles(level) - 1, ty, ty, level);
                rowsDone += rows;
                if (options.progress) options.progress(double(rowsDone) / rowsTotal);
            }
        }
    } catch (const std::exception& e) {
        return cannotWrite(finalPath, "writing failed: " + detail::firstLine(e.what()), "check free disk space and permissions");
    }
    return Done{};
}

}  // namespace heightpack::detail
