// heightpack's own PNG decoder (libpack/io/png_fast.cpp) on arbitrary bytes. loadHeightMap calls it
// with the size OpenImageIO read from the IHDR chunk, after judging that size; the harness does the same
// with the first IHDR's size, capped so one input cannot ask for gigabytes. Any result is fine (an image
// or "not mine"); a crash, a sanitizer report or a hang is a finding.
#include <cstdint>
#include <vector>

#include "png_fast.hpp"

namespace {

uint32_t be32(const uint8_t* p) { return (uint32_t(p[0]) << 24) | (uint32_t(p[1]) << 16) | (uint32_t(p[2]) << 8) | p[3]; }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 8 + 25) return 0;
    const uint32_t width = be32(data + 16), height = be32(data + 20);  // the signature, then IHDR's length and name
    if (width == 0 || height == 0 || width > 4096 || height > 4096 || uint64_t(width) * height > (1u << 20)) return 0;
    const std::vector<unsigned char> file(data, data + size);
    for (int channel = 0; channel < 2; ++channel) {
        const auto plan = heightpack::detail::planGreyPng(file, int(width), int(height), channel);
        if (!plan) continue;
        const auto image = heightpack::detail::decodeGreyPng(file, *plan, 1);
        if (image && (image->width != int(width) || image->height != int(height) || image->channels != 1)) __builtin_trap();
    }
    return 0;
}
