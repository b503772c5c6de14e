// How check, tile and build word the frame, blob and echo statistics (heightpack/core/tile/look.hpp).
#pragma once

#include <nlohmann/json.hpp>

#include <string>

#include "heightpack/core/tile/look.hpp"

namespace heightpack::cli {

// {"measured", "frame", "blobs", "echo", "echoBaseline", "thresholds": {...}, "passes", "over": [names]}.
nlohmann::json lookJson(const TileLook& look, const LookThresholds& thresholds);
// "frame 2.1, blobs 1.8, echo 0.03" with "(over 7.5)" after each statistic over its threshold.
std::string lookText(const TileLook& look, const LookThresholds& thresholds);
// The check's lines on stdout: "  look: frame 2.1, blobs 1.8, echo 0.03 (thresholds ...)", then a WARNING (or
// LOOK FAILS when it fails the check) line per statistic over its threshold, saying what a person would see.
void printLook(const TileLook& look, const LookThresholds& thresholds, bool fails);

}  // namespace heightpack::cli
