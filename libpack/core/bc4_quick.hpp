// The quick pass of the BC4 encoder (block_compression.cpp): eight blocks' endpoint searches side by side,
// one block a vector lane, so a search's per-pair setup (table lookups, divisions) and its texel loops are
// shared by eight blocks. The thorough pass (bc4_fit.hpp) takes the few blocks that decide the worst error.
#pragma once

#include <cstdint>

namespace heightpack::bc4 {

constexpr int kQuickBlocks = 8;

// Eight blocks of one channel, texel t (texel (x, y) at 4y + x) of block `lane` at [t][lane]. In: the
// values (clamped to [0, 1] here), or where source[0] is set, eight blocks side by side in an image: the
// block row's four rows from the first block's first texel of the channel, `step` floats from texel to
// texel (its channels); they are then read from there into value. Out: each block's endpoints, codes,
// decoded values, and squared and worst error.
struct QuickBlocks {
    const float* source[4] = {};
    int step = 1;
    float value[16][kQuickBlocks];
    int e0[kQuickBlocks], e1[kQuickBlocks];
    std::uint8_t code[16][kQuickBlocks];
    float decoded[16][kQuickBlocks];
    float error[kQuickBlocks], worst[kQuickBlocks];
};

// Each block's pair of least squared error among: in the eight-value mode, the pair at the values' range
// and the least-squares fits from it (while they improve, at most three); in the six-value mode (for
// blocks with values within 16 codes of 0 or 1) the same from the range of the values not at 0 or 1.
// Each lane's results depend on its block alone, in the same operations on any instruction set (AVX2
// where the processor has it, SSE2 or plain code otherwise), so the bytes are the same everywhere.
void quickSearch(QuickBlocks& blocks);

// The same without AVX2 (four lanes at a time): what quickSearch does on processors without it.
void quickSearchPortable(QuickBlocks& blocks);

// BC5 normals: each block's worst chord between the unit normals of the given x, y (offset + scale *
// value) and of the decoded ones, z rebuilt as a shader does (x, y past the unit circle: on it); the
// same operations as block_compression.cpp's thorough pass measures a texel with.
void quickWorstChords(const QuickBlocks& x, const QuickBlocks& y, float offset, float scale, float worst[kQuickBlocks]);

// The same without AVX2: what quickWorstChords does on processors without it.
void quickWorstChordsPortable(const QuickBlocks& x, const QuickBlocks& y, float offset, float scale, float worst[kQuickBlocks]);

}  // namespace heightpack::bc4
