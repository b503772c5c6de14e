// loadHeightMap on arbitrary bytes, through every reader heightpack accepts: the first byte picks the
// file's extension (OpenImageIO tries the reader the name suggests first, then every other one), the
// second the --channel choice; the rest is the file. Any Error is fine; a crash, a sanitizer report, a
// hang, or heights that are not finite are findings.
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdint>
#include <iterator>

#include "heightpack/io/read.hpp"

#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    OIIO::attribute("threads", 1);  // no thread pools: one input, one thread, reproducible
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const char* const kExtensions[] = {"png", "tif", "exr", "jpg", "bmp", "tga", "hdr", "pgm",
                                              "psd", "gif", "dds", "ico", "sgi", "dpx", "webp", "pfm"};
    static const heightpack::ChannelSelect kChannels[] = {heightpack::ChannelSelect::Auto, heightpack::ChannelSelect::R,
                                                          heightpack::ChannelSelect::G,    heightpack::ChannelSelect::B,
                                                          heightpack::ChannelSelect::A,    heightpack::ChannelSelect::Luma};
    if (size < 3) return 0;
    const std::string ext = kExtensions[data[0] % std::size(kExtensions)];
    heightpack::LoadOptions options;
    options.channel = kChannels[data[1] % std::size(kChannels)];
    options.maxSide = 4096;            // the harness's limits, so an input cannot ask for gigabytes
    options.maxTexels = int64_t(1) << 20;
    options.threads = 1;
    const std::string path = heightpack::fuzz::writeInput("input." + ext, data + 2, size - 2);
    auto loaded = heightpack::loadHeightMap(path, options);
    if (loaded) {
        const heightpack::Image& h = loaded->heights;
        if (h.channels != 1 || h.width < 1 || h.height < 1 || h.pixels.size() != h.texelCount()) __builtin_trap();
        for (float v : h.pixels)
            if (!std::isfinite(v)) __builtin_trap();  // loadHeightMap promises finite heights
    }
    return 0;
}
