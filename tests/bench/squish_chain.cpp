// libsquish's BC4 or BC5 of a whole mip chain, as bench_block.sh times nvcompress's: load an 8-bit image,
// make its chain with a 2x2 box filter (nvcompress's default), encode every level, write the blocks.
//   heightpack_squish_chain bc4|bc5|raw IN.png OUT.bin
// BC4 takes the image's first channel, BC5 its first two. libsquish encodes on one thread. raw does all
// but the encoding (it writes each level's RGBA texels): bench_block.sh takes its time from bc4's and
// bc5's for the encoding's own.
#include <squish.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

int main(int argc, char** argv) {
    const std::string mode = argc == 4 ? argv[1] : "";
    if (mode != "bc4" && mode != "bc5" && mode != "raw") {
        std::fprintf(stderr, "usage: heightpack_squish_chain bc4|bc5|raw IN.png OUT.bin\n");
        return 2;
    }
    const bool bc5 = mode == "bc5", raw = mode == "raw";
    auto in = OIIO::ImageInput::open(argv[2]);
    if (!in) {
        std::fprintf(stderr, "heightpack_squish_chain: cannot read %s\n", argv[2]);
        return 1;
    }
    const OIIO::ImageSpec spec = in->spec();
    int width = spec.width, height = spec.height;
    const int channels = spec.nchannels;
    std::vector<unsigned char> pixels(size_t(width) * height * channels);
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, pixels.data())) {
        std::fprintf(stderr, "heightpack_squish_chain: cannot decode %s\n", argv[2]);
        return 1;
    }
    // RGBA, R and G from the image's first channels (G = R for a grey image).
    std::vector<squish::u8> rgba(size_t(width) * height * 4, 255);
    for (size_t t = 0; t < size_t(width) * height; ++t) {
        rgba[t * 4] = pixels[t * channels];
        rgba[t * 4 + 1] = pixels[t * channels + (channels > 1 ? 1 : 0)];
    }
    const int flags = bc5 ? squish::kBc5 : squish::kBc4;
    std::FILE* out = std::fopen(argv[3], "wb");
    if (!out) {
        std::fprintf(stderr, "heightpack_squish_chain: cannot write %s\n", argv[3]);
        return 1;
    }
    std::vector<unsigned char> blocks;
    for (;;) {
        if (raw) {
            std::fwrite(rgba.data(), 1, rgba.size(), out);
        } else {
            blocks.resize(size_t(squish::GetStorageRequirements(width, height, flags)));
            squish::CompressImage(rgba.data(), width, height, blocks.data(), flags);
            std::fwrite(blocks.data(), 1, blocks.size(), out);
        }
        if (width == 1 && height == 1) break;
        const int w = std::max(1, width / 2), h = std::max(1, height / 2);
        std::vector<squish::u8> next(size_t(w) * h * 4);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                for (int c = 0; c < 4; ++c) {
                    int sum = 0;
                    for (int dy = 0; dy < 2; ++dy)
                        for (int dx = 0; dx < 2; ++dx) {
                            const int sx = std::min(2 * x + dx, width - 1), sy = std::min(2 * y + dy, height - 1);
                            sum += rgba[(size_t(sy) * width + sx) * 4 + size_t(c)];
                        }
                    next[(size_t(y) * w + x) * 4 + size_t(c)] = squish::u8((sum + 2) / 4);
                }
        rgba.swap(next);
        width = w, height = h;
    }
    return std::fclose(out) == 0 ? 0 : 1;
}
