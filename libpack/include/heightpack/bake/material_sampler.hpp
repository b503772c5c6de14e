// A built material's water heights on the CPU: material.json's displacement layers, their packed chains
// read from disk, as a WaterSampler (heightpack/core/water_sampler.hpp) that answers H(x, y, t) as
// heightpack-view draws it. For an engine's build tools and tests; the engine itself ports
// sampleWaterHeight (forty lines) beside its own texture loader.
#pragma once

#include <string>

#include "heightpack/core/result.hpp"
#include "heightpack/core/water_sampler.hpp"

namespace heightpack {

// Reads material.json and every frame of every displacement layer it names (packed or plain chains in any
// container heightpack writes; a plain chain is packed in memory). Fails with BadInput naming the file when
// one is missing, damaged, not a height chain, or differs in size from its sequence's first frame.
Result<WaterSampler> loadMaterialSampler(const std::string& materialPath);

}  // namespace heightpack
