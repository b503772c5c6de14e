#include "heightpack/io/height_sequence.hpp"

#include "heightpack/io/files.hpp"

namespace heightpack {

Result<HeightSequence> readHeightSequence(const std::string& path, const ReadSequenceFrame& readFrame,
                                          double declaredPeriod) {
    HeightSequence sequence;
    sequence.files = expandSequence(path);
    SequenceFrame first;
    for (size_t f = 0; f < sequence.files.size(); ++f) {
        const std::string& file = sequence.files[f];
        auto frame = readFrame(file, f);
        if (!frame) return frame.error();
        if (f == 0) {
            first = *frame;
            continue;
        }
        if (frame->levels != first.levels || frame->width != first.width || frame->height != first.height)
            return badInput(file, "differs in size from the sequence's first frame", "make every frame the same size");
        if (frame->texelType != first.texelType)
            return badInput(file, "differs in pixel type from the sequence's first frame",
                            "write every frame with the same pixel type");
        if (frame->shift != first.shift)
            return badInput(file, "differs from the sequence's first frame in holding Dx, Dy",
                            "make every frame with the shift (Dx, Dy), or none");
        if (frame->foam != first.foam)
            return badInput(file, "differs from the sequence's first frame in holding foam",
                            "make every frame with foam, or none");
    }
    if (sequence.files.size() > 1) {
        // Untimed: four frames a second.
        sequence.loopPeriod = first.loopPeriod            ? *first.loopPeriod
                              : declaredPeriod > 0.0 ? declaredPeriod
                                                     : double(sequence.files.size()) / 4.0;
    }
    return sequence;
}

HeightChains splitHeightChains(const std::vector<Image>& levels, const TextureChannels& channels) {
    HeightChains chains;
    for (const Image& level : levels) {
        chains.heights.push_back(selectChannels(level, channels.heights));
        if (channels.shift()) {
            chains.dx.push_back(selectChannels(level, channels.dx));
            chains.dy.push_back(selectChannels(level, channels.dy));
        }
        if (channels.hasFoam()) chains.foam.push_back(selectChannels(level, {channels.foam.front()}));
    }
    return chains;
}

}  // namespace heightpack
