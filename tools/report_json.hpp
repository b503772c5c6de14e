// What a run reports, as text and JSON: the channel the heights came from, a resize, seam scores, sizes.
#pragma once

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

#include "heightpack/core/tile/tileable.hpp"
#include "heightpack/io/read.hpp"

namespace heightpack::cli {

// Says which channel the heights came from when that may surprise: "  note: ..." on stdout.
void printChannelNote(const SourceInfo& source);
// {"used": name, "note": text or null}, for --json.
nlohmann::json channelJson(const SourceInfo& source);

// What --resize pow2 did to a width x height map: the new size, the change of aspect, and the nearest
// powers of two per side (the size to export at to keep the shape). One line, no newline.
std::string resizeNote(int fromWidth, int fromHeight, int toWidth, int toHeight);
nlohmann::json resizeJson(int fromWidth, int fromHeight, int toWidth, int toHeight);

// One edge pair's seam scores as JSON: measured, value, slope, pass. A score is a number, or the string
// "inf" when it is infinite (docs/tiling.md, "Seam scores"); an unmeasured pair is {"measured": false}.
nlohmann::json seamScoreJson(const SeamScore& score, double threshold);
// A chain's per-level scores: [{level, width, height, leftRight, topBottom, pass}, ...].
nlohmann::json seamLevelsJson(const std::vector<LevelSeams>& levels, double threshold);
// The first failing edge: {level, width, height, edge, kind, score, text}, or null.
nlohmann::json seamFailureJson(const std::optional<SeamFailure>& failure, double threshold);

// "1.5 MiB", "312 KiB": a size for people.
std::string humanBytes(unsigned long long bytes);

}  // namespace heightpack::cli
