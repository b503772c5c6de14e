// heightpack's own KTX2 and DDS readers (libpack/io/ktx2.cpp, dds.cpp) on arbitrary bytes: what `info`
// and the tests read back. The first bytes choose the extension the reader is given (a KTX2 identifier
// gives .ktx2, anything else .dds), so both parsers see every input that starts like theirs. Any result
// is fine (levels, or an error naming what is wrong); a crash, a sanitizer report or a hang is a finding.
#include <cstdint>
#include <cstring>

#include "fuzz_support.hpp"
#include "heightpack/io/gpu_texture.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const uint8_t kKtx2[4] = {0xAB, 'K', 'T', 'X'};
    const bool ktx2 = size >= 4 && std::memcmp(data, kKtx2, 4) == 0;
    const std::string path = heightpack::fuzz::writeInput(ktx2 ? "input.ktx2" : "input.dds", data, size);
    const auto texture = heightpack::readGpuTexture(path);
    if (texture) {
        // What the reader returns must be self-consistent: every level it lists has its pixels.
        if (texture->levels.empty() || texture->levels.size() != texture->levelBytes.size()) __builtin_trap();
        for (const heightpack::Image& level : texture->levels)
            if (level.pixels.size() != level.texelCount() * size_t(level.channels)) __builtin_trap();
    }
    return 0;
}
