// The options every texture-writing command shares for KTX2 and DDS: --pixel-type, and --compression's
// meaning per container (EXR's codecs, KTX2's zstd, DDS none).
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "heightpack/io/gpu_texture.hpp"

namespace heightpack::cli {

// Adds --pixel-type float|half|uint16 to cmd.
void addPixelTypeOption(CLI::App& cmd, std::string& pixelType);

// The EXR compressions and the KTX2 one, for --compression's check.
std::vector<std::string> compressionNames();

// Whether path names a .ktx2 or .dds output.
bool isGpuContainer(const std::string& path);

// Checks the pixel type and compression against the container of every output (by extension); sets
// supercompression. Returns what is wrong, for usage(), or empty.
std::string checkContainerChoice(const std::vector<std::string>& outputs, PixelType pixelType,
                                 const std::string& compression, bool compressionGiven,
                                 Supercompression& supercompression);

}  // namespace heightpack::cli
