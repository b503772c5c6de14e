// Foam that loops: whitecaps where the choppy surface folds or nearly folds (its Jacobian J below a
// threshold), building up while it does and fading exponentially after, over a loop that closes exactly.
#pragma once

#include <vector>

#include "heightpack/core/image.hpp"

namespace heightpack {

struct FoamOptions {
    double threshold = 0.5;  // foam forms where J < threshold (J = 1: untouched, J < 0: the surface folds)
    double decay = 2.0;      // s: the e-folding time of foam left behind
    double buildUp = 4.0;    // 1/s: foam density gained per second per unit of J below the threshold
};

// One step of the foam density over dt seconds during which the surface's Jacobian was `jacobian`:
//   density' = q density + buildUp * decay * (1 - q) * max(0, threshold - J),  q = exp(-dt / decay),
// the exact solution of d(density)/dt = -density / decay + buildUp * max(0, threshold - J) with J held.
// Stays 0 wherever J stays at or above the threshold. density and jacobian have the same texel count.
void advanceFoam(std::vector<float>& density, const Image& jacobian, double dt, const FoamOptions& options);

// The density a sea frozen with Jacobian `jacobian` at a texel settles at (advanceFoam's fixed point):
// buildUp * decay * max(0, threshold - J).
float frozenFoamDensity(float jacobian, const FoamOptions& options);

// The coverage one texel of `density` shows: 1 - exp(-density), in [0, 1).
float foamCoverageOf(float density);

// Coverage in [0, 1) from a density: 1 - exp(-density), so coverage saturates instead of clipping.
// Rows shared among `threads` threads (0 = all cores); each texel on its own, so any count gives the same.
Image foamCoverage(const std::vector<float>& density, int width, int height, int threads = 1);

// The foam densities of a looping sequence: jacobians[f] is frame f's, at t = f * period / F. The foam
// starts one full period early from nothing (the warm-up), and since the dynamics are linear in the
// density, what that warm-up leaves, divided by 1 - exp(-period / decay), is the state the loop has
// after infinitely many periods: started from it, the frame after the last (F) equals frame 0 exactly,
// not only to within the exp(-period / decay) that a warm-up alone leaves. One frame (or no loop): the
// density a sea frozen at that frame settles at, buildUp * decay * max(0, threshold - J), which is the
// same formula with F = 1.
std::vector<std::vector<float>> loopingFoamDensity(const std::vector<Image>& jacobians, double period,
                                                   const FoamOptions& options);

}  // namespace heightpack
