// Generated families of height maps whose verdict is known by construction, for judging the seam
// measure (`check`) and the seam fixer (`tile`) from the outside. Written from the definitions in issue 11,
// sharing no code with libpack's measure:
//   - periodic: the inverse DFT of complex white noise shaped to a power spectrum k^-beta, so every level
//     of it tiles exactly;
//   - crop: a window of a periodic field twice its size, so its edges are two unrelated places;
//   - ramp: periodic + a linear ramp whose jump at the wrap is 3 mean neighbour differences;
//   - parabola: periodic + a parabola whose slopes flip at the wrap, a kink of 6 mean second differences.
// Every map is drawn from its index alone, so any failure can be reproduced from what is printed.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "heightpack/bake/check_job.hpp"
#include "heightpack/core/image.hpp"

namespace heightpack::test {

enum class Family { Periodic, Crop, Ramp, Parabola };
inline constexpr Family kSeamedFamilies[] = {Family::Crop, Family::Ramp, Family::Parabola};
const char* familyName(Family family);

// How a map is stored: every format a height map comes in, lossless and lossy.
enum class MapFormat { Png8, Png16, ExrFloat, Jpeg75, Jpeg90 };
inline constexpr MapFormat kAllFormats[] = {MapFormat::Png8, MapFormat::Png16, MapFormat::ExrFloat,
                                            MapFormat::Jpeg75, MapFormat::Jpeg90};
const char* formatName(MapFormat format);       // "png8", "png16", "exr", "jpeg75", "jpeg90"
const char* formatExtension(MapFormat format);  // ".png", ".exr", ".jpg"

// Everything that determines one generated map.
struct MapSpec {
    Family family = Family::Periodic;
    int index = 0;       // drawMap(family, index) gives this spec again
    MapFormat format = MapFormat::Png8;
    unsigned seed = 0;   // of the noise (and of the crop offset)
    double beta = 2.0;   // power spectrum k^-beta, in [1.5, 4]
    double aniso = 1.0;  // 1 (isotropic) to 3: one axis of k stretched by this after rotating by angle
    double angle = 0.0;  // radians
    int width = 64;
    int height = 64;
    bool alongX = true;  // ramp and parabola: the direction they vary in (the seam is at that wrap)
};

// Map `index` of a family, drawn from (family, index) alone: beta uniform in [1.5, 4], half of the maps
// isotropic and half anisotropic up to 3:1, sizes 64 to 1024 weighted toward small ones (most 64-256, some
// 512, a few 1024), square or 4:1 either way (short side at least 16). The format cycles with the index,
// so any run of 5 consecutive indices covers all five.
MapSpec drawMap(Family family, int index);
// The parameters as one line: family, index, seed, beta, aniso, angle, size, format (and direction).
std::string describe(const MapSpec& spec);

// An exactly periodic width x height field with power spectrum k^-beta (k in cycles per texel, after the
// anisotropic stretch), no DC, normalised to [0, 1].
Image periodicField(int width, int height, unsigned seed, double beta, double aniso, double angle);
// The map spec describes, in [0, 1] (renormalised after adding a ramp or a parabola).
Image makeMap(const MapSpec& spec);

// Mean |h(i+1) - h(i)| and mean |h(i+1) - 2h(i) + h(i-1)| along x (or y), over interior texels.
double meanFirstDifference(const Image& map, bool alongX);
double meanSecondDifference(const Image& map, bool alongX);

// How strong a map's seam is, measured on the map itself (independently of check): the mean absolute first
// (second) difference across the wrap over the mean inside, along x and along y. About 1 for a periodic
// map; a ramp's first ratio along its direction is about 3 plus the map's own step there.
struct WrapRatios {
    double firstX = 0, firstY = 0, secondX = 0, secondY = 0;
    std::string text() const;  // "wrap/inside: first x 1.02 y 0.98, second x 1.1 y 0.95"
};
WrapRatios wrapRatios(const Image& map);

// Writes a one-channel map in [0, 1] with OpenImageIO (JPEG quality through the "Compression" attribute,
// "jpeg:75"). Returns an empty string, or what went wrong.
std::string writeMap(const std::string& path, const Image& map, MapFormat format);

// ---- Reading a check report ----
// The only code here that reads seam scores: if SeamScore's fields change, this is what changes.

struct WorstSeam {
    double score = 0.0;    // the largest score over measured levels, both edge pairs, value and slope
    int level = -1;        // where it is; -1 when nothing was measured
    int levelWidth = 0, levelHeight = 0;
    std::string edge;      // "left/right" or "top/bottom"
    std::string kind;      // "value" or "slope"
    std::string text() const;  // "level 2 (32x32) left/right value 4.01"
};
WorstSeam worstSeam(const CheckReport& report);
inline double worstScore(const CheckReport& report) { return worstSeam(report).score; }

// ---- Running many maps ----

// Calls job(i) for i in [0, count) on all cores (std::thread, at least 2); job must be thread-safe.
void parallelFor(int count, const std::function<void(int)>& job);

// The outcome of writing one generated map and checking it.
struct MapVerdict {
    MapSpec spec;
    std::string error;  // writing or checking failed
    bool tiles = false;
    WorstSeam worst;
    WrapRatios ratios;  // of the map as generated, before it was stored
};
// Makes the map, writes it in its format under folder, runs checkFile with default options, removes the file.
MapVerdict checkGeneratedMap(const MapSpec& spec, const std::string& folder);

// Order statistics of a sample (nearest rank): q in [0, 1].
double quantile(std::vector<double> values, double q);
// "min 0.81  p1 0.85  median 1.02  p99 1.9  max 2.3" (p-values over the finite and infinite scores alike).
std::string distributionText(const std::vector<double>& values);

// A number of maps scaled by HEIGHTPACK_SEAM_SCALE (a positive factor, default 1), never below minimum.
int scaledCount(int count, int minimum);

}  // namespace heightpack::test
