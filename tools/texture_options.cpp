#include "texture_options.hpp"

namespace heightpack::cli {

void addPixelTypeOption(CLI::App& cmd, std::string& pixelType) {
    cmd.add_option("--pixel-type", pixelType,
                   "float (32-bit), half (16-bit float, rounded to nearest) or uint16 (16-bit normalised to the "
                   "chain's range, scale and offset recorded; .ktx2 and .dds only)")
        ->capture_default_str()
        ->check(CLI::IsMember(allNames<PixelType>()));
}

std::vector<std::string> compressionNames() {
    std::vector<std::string> names;
    for (const auto& name : allNames<Compression>()) names.emplace_back(name);
    names.emplace_back("zstd");  // KTX2's supercompression, not an EXR codec
    return names;
}

bool isGpuContainer(const std::string& path) {
    const auto c = containerForPath(path);
    return c == Container::Ktx2 || c == Container::Dds;
}

std::string checkContainerChoice(const std::vector<std::string>& outputs, PixelType pixelType,
                                 const std::string& compression, bool compressionGiven,
                                 Supercompression& supercompression) {
    supercompression = Supercompression::None;
    for (const std::string& path : outputs) {
        if (path.empty()) continue;
        const auto c = containerForPath(path);
        if (c == Container::Ktx2) {
            if (compressionGiven && compression != "none" && compression != "zstd")
                return path + ": a KTX2 takes --compression none or zstd";
            if (compressionGiven && compression == "zstd") supercompression = Supercompression::Zstd;
        } else if (c == Container::Dds) {
            if (compressionGiven && compression != "none")
                return path + ": a DDS is stored uncompressed: leave out --compression";
        } else {
            if (pixelType == PixelType::Uint16)
                return path + ": --pixel-type uint16 needs a .ktx2 or .dds output (an EXR has no 16-bit normalised "
                              "channels)";
            if (compression == "zstd") return path + ": --compression zstd is for .ktx2 outputs";
        }
    }
    return {};
}

}  // namespace heightpack::cli
