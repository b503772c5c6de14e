// The browser test's reference: every level of a BC4, BC5 or ASTC KTX2 as heightpack's reader decodes it
// (readGpuTexture, whose BC decode tests/viewer/block_upload_test.cpp holds to Mesa's GPU decoder within
// 1.5 codes; ASTC: astcenc's decoder, heights as R, normals as R (x) and A (y)), written as the unorm values a GPU returns, so the page can compare texel by texel.
//   heightpack_decoded_levels FILE.ktx2 OUT.bin
// OUT.bin: each level's values as little-endian float32, level 0 first, rows top down, channels
// interleaved. stdout: one JSON line {"width", "height", "channels", "levels", "offset", "scale"}.
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "heightpack/io/gpu_texture.hpp"

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: heightpack_decoded_levels FILE.ktx2 OUT.bin\n");
        return 2;
    }
    const heightpack::Result<heightpack::GpuTexture> read = heightpack::readGpuTexture(argv[1]);
    if (!read) {
        std::fprintf(stderr, "%s: %s\n", argv[1], read.error().what.c_str());
        return 3;
    }
    const heightpack::GpuTexture& t = read.value();
    // Block texels are stored normalised: value = offset + scale * unorm; the GPU samples the unorm.
    const heightpack::Normalisation n = t.normalisation.value_or(heightpack::Normalisation{});
    std::ofstream out(argv[2], std::ios::binary);
    for (const heightpack::Image& level : t.levels) {
        std::vector<float> unorm(level.pixels.size());
        for (size_t i = 0; i < unorm.size(); ++i) unorm[i] = (level.pixels[i] - n.offset) / n.scale;
        out.write(reinterpret_cast<const char*>(unorm.data()), std::streamsize(unorm.size() * sizeof(float)));
    }
    if (!out.flush()) {
        std::fprintf(stderr, "%s: cannot write\n", argv[2]);
        return 4;
    }
    const int channels = t.levels.empty() ? 0 : t.levels.front().channels;
    std::printf("{\"width\": %d, \"height\": %d, \"channels\": %d, \"levels\": %zu, \"offset\": %.9g, \"scale\": %.9g}\n",
                t.width, t.height, channels, t.levels.size(), double(n.offset), double(n.scale));
    return 0;
}
