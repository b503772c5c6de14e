// The material both shared-cache suites build (build_cache_test.cpp against a folder, build_server_test.cpp
// against an HTTP server): two painted maps, a normal map, the Fresnel ramp and a synthesised sea of two
// frames, and ways to compare what two builds wrote.
#pragma once

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>

#include "support/test_support.hpp"

namespace heightpack::test {

// Waves with whole periods across the tile: every level tiles, so the build's checks pass.
inline Image waves(int size, int kx, int ky, double phase) {
    return makeImage(size, size, [=](int x, int y) {
        double h = 0.5;
        for (int n = 1; n <= 6; ++n) {
            const double t = 2 * std::numbers::pi * ((kx * n % 7) * double(x) / size + (ky + n) % 5 * double(y) / size);
            h += 0.1 / n * std::sin(t + phase * n);
        }
        return static_cast<float>(h);
    });
}

// Two painted maps, a normal map, the Fresnel ramp and a synthesised sea of two frames: six outputs.
inline const char* kSea = R"(format = 1
name = "sea"

[[displacement]]
name = "long"
source = "maps/a.png"
tile_size = 64.0

[[displacement]]
name = "short"
source = "maps/b.png"
tile_size = 16.0

[[displacement]]
name = "swell"
tile_size = 32.0
synth = { wind = 9.0, size = 32, seed = 2, loop = 4.0, frames = 2 }

[normals]
name = "ripple_n"
source = "maps/r.png"
tile_size = 8.0
height = 0.05

[fresnel]
ior = 1.333
)";

// Writes the material's maps under folder/maps and kSea at manifest.
inline void writeCacheMaterial(const std::filesystem::path& folder, const std::string& manifest) {
    std::filesystem::create_directories(folder / "maps");
    writeImage((folder / "maps/a.png").string(), waves(64, 1, 2, 0.3), OIIO::TypeDesc::UINT16);
    writeImage((folder / "maps/b.png").string(), waves(32, 3, 1, 1.1), OIIO::TypeDesc::UINT16);
    writeImage((folder / "maps/r.png").string(), waves(32, 2, 3, 2.0), OIIO::TypeDesc::UINT8);
    std::ofstream(manifest) << kSea;
}
inline constexpr int kOutputs = 6;

inline std::string bytesOf(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Every file under root, relative path -> bytes.
inline std::map<std::string, std::string> filesUnder(const std::filesystem::path& root) {
    namespace fs = std::filesystem;
    std::map<std::string, std::string> files;
    for (const auto& e : fs::recursive_directory_iterator(root))
        if (e.is_regular_file()) files[fs::relative(e.path(), root).string()] = bytesOf(e.path());
    return files;
}

}  // namespace heightpack::test
