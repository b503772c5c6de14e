// material.json's description of a built material, read back from the headers of the files the build
// wrote (sizes, levels, frames, a sequence's loop period), so it says what is on disk.
#pragma once

#include <string>

#include "heightpack/bake/manifest.hpp"
#include "heightpack/bake/material.hpp"
#include "heightpack/core/result.hpp"

namespace heightpack {

// The description of manifest m's outputs in folder; version is the generator's ("heightpack VERSION").
// Fails (BadInput) when an output is missing or is not a texture heightpack can read.
Result<MaterialDescription> describeMaterial(const Manifest& m, const std::string& folder, const std::string& version);

}  // namespace heightpack
