// What a height file says about the world it stands for: how many metres its tile spans, how many metres
// one unit of its heights is, and how a sequence it belongs to is timed. Read once from the header
// (EXR attributes, KTX2 key/values, a DDS record, PNG text) into numbers; callers ask these, never the text.
#pragma once

#include <optional>
#include <string>

#include "heightpack/core/result.hpp"
#include "heightpack/io/attributes.hpp"

namespace heightpack {

struct MapUnits {
    // Metres the map's width and height span (heightpack:tileWidth, heightpack:tileHeight); a file that
    // records the width alone has square texels.
    std::optional<double> tileWidth, tileHeight;
    // Metres between a height of 0 and a height of 1 of the file's values: heightpack:heightRange where
    // recorded (packed, plain and normal maps), else for a synthesised sea its heightScale (its values are
    // metres = heightOffset + heightScale * value: 1 in a float EXR; describeTexture fills that in).
    // Absent: the file does not say.
    std::optional<double> heightRange;
    // Seconds a looping sequence spans, and where this frame sits in it (heightpack:loopPeriod, :time).
    std::optional<double> loopPeriod, time;
};

// The units attributes records. A recorded value that is no number, not finite, or (for the lengths and the loop
// period) not positive is damaged metadata: BadInput naming path and the attribute.
Result<MapUnits> readMapUnits(const Attributes& attributes, const std::string& path);

}  // namespace heightpack
