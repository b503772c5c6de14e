// Making a map tile by re-synthesising a band around its wrap lines: new content that continues both
// sides, drawn from the map's own statistics, instead of a blend of the map with shifted copies of itself.
#pragma once

#include <cstdint>
#include <memory>

#include "heightpack/core/image.hpp"

namespace heightpack {

struct ResynthesisOptions {
    // Width of the band replaced around each wrap line, as a fraction of the tile across it; 0 chooses it
    // from the map: four correlation lengths of its slopes, at least 1/32 and at most 1/4 of the tile.
    double band = 0.0;
    uint64_t seed = 1;  // the unconditional sample's noise: the same seed gives the same bytes
    // The input's height step (1/255 for 8 bits, 1/65535 for 16, 0 for float): a quantised map is first
    // made smooth within its rounding intervals, so its terraces are not taken for texture.
    double quantum = 0.0;
    int threads = 0;    // 0 = all cores; the result does not depend on it
};

struct ResynthesisResult {
    Image map;
    int bandX = 0;  // texels replaced across the left/right wrap line (a vertical band)
    int bandY = 0;  // texels replaced across the top/bottom wrap line
};

// Gaussian conditional simulation of the bands around the wrap lines (Galerne & Leclaire 2017, "Texture
// inpainting using efficient Gaussian conditional simulation"), in the rank-Gaussianised domain of Heitz &
// Neyret, so the heights keep the map's histogram:
//   1. the map's model: its values become standard Gaussians through their ranks, whose covariance and
//      spectrum the sample and the kriging use (a quantised map's terraces first undone);
//   2. the large scales are made periodic by Moisan's smooth field of a low-pass of the heights (heights
//      only: the offsets it removes are larger than the band could bridge), and that map Gaussianised;
//   3. a band across the left/right wrap line is replaced by a sample of the stationary Gaussian field with
//      the map's own covariance conditioned on the texels beside the band: an unconditional sample (the
//      map's spectrum times white noise) plus the kriged difference between the map and that sample. The
//      conditioning texels are whole columns, so in the Fourier domain along the band each vertical
//      frequency is its own small system, solved exactly (Cholesky);
//   4. the same across the top/bottom wrap line, now conditioned on a map that already wraps left/right;
//   5. back through the corrected map's sorted values in the bands; beyond them the map itself less the
//      smooth field of step 2, so its own fine detail (terraces and all) stays exactly. Deterministic for a seed,
// whatever the thread count. Maps smaller than 16 texels on a side get Moisan's periodic component.
ResynthesisResult resynthesiseTile(const Image& map, const ResynthesisOptions& options = {});

// The same for several attempts on one map (tile tries other seeds and bands when one does not pass):
// step 1 is made once, step 2 once per large-scale width, so an attempt costs a sample and the bands.
// attempt(seed, band) gives what resynthesiseTile with that seed and band gives. map must outlive it.
class Resynthesiser {
public:
    Resynthesiser(const Image& map, double quantum, int threads);
    ~Resynthesiser();
    Resynthesiser(const Resynthesiser&) = delete;
    Resynthesiser& operator=(const Resynthesiser&) = delete;
    ResynthesisResult attempt(uint64_t seed, double band);

private:
    struct State;
    std::unique_ptr<State> state_;
    // asSource: the map is an enlarged map's source, taken for an enlargement again by a source's rules.
    Resynthesiser(const Image& map, double quantum, int threads, bool asSource);
    // An attempt on an enlarged map's source, enlarged back: the map beyond the bands (plus the source's
    // smooth change), the enlarged source result within them.
    ResynthesisResult enlargedAttempt(ResynthesisResult fromSource) const;
};

}  // namespace heightpack
