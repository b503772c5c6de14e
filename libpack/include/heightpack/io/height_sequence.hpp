// A displacement layer's height maps as the viewer and the CPU sampler (bake/material_sampler.hpp) both
// load them: one map, or the frames of a sequence (NAME.0000.EXT ...), each frame read by the caller in
// its own form (texels as stored for the GPU, floats for the CPU) and held to one set of rules: every frame
// like the first in size, texel type and companions, and one loop period for all.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "heightpack/core/image.hpp"
#include "heightpack/core/result.hpp"
#include "heightpack/io/texture_description.hpp"

namespace heightpack {

// What the sequence's rules compare between a frame and the first: a frame reader fills it in.
struct SequenceFrame {
    int width = 0, height = 0;  // level 0
    size_t levels = 0;
    int texelType = 0;  // how the frame's texels are stored, a code of the reader's: one GPU array holds all frames
    bool shift = false, foam = false;  // holds Dx, Dy; holds foam coverage
    std::optional<double> loopPeriod;         // what the frame records (heightpack:loopPeriod)
};

struct HeightSequence {
    std::vector<std::string> files;  // the frames in order; one file for a single map
    double loopPeriod = 0.0;         // seconds the frames span; 0 for a single map
};

// Reads frame `index` (file) of a sequence: what it holds, or why it cannot be read.
using ReadSequenceFrame = std::function<Result<SequenceFrame>(const std::string& file, size_t index)>;

// Reads the map at path, or every frame of the sequence it names (expandSequence), through readFrame, in
// order. Fails with BadInput naming the frame when a later frame differs from the first in size or level
// count, in texel type, in holding Dx, Dy or in holding foam. The loop period is the first frame's record,
// else declaredPeriod when positive, else four frames a second.
Result<HeightSequence> readHeightSequence(const std::string& path, const ReadSequenceFrame& readFrame,
                                          double declaredPeriod = 0.0);

// A height texture's float levels split by what each channel holds (description.channels), each level as
// the file lays it out: heights, Dx and Dy with four channels (packed) or one (plain); foam as F(i,j)
// alone, one channel. Dx, Dy and foam have no levels where the file holds none.
struct HeightChains {
    std::vector<Image> heights, dx, dy, foam;
};
HeightChains splitHeightChains(const std::vector<Image>& levels, const TextureChannels& channels);

}  // namespace heightpack
