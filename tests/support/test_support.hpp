// Helpers shared by the tests: scratch folders, fields, writing images through OpenImageIO, and
// reference computations written independently of libpack.
#pragma once

#include <OpenImageIO/typedesc.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "heightpack/core/image.hpp"

namespace heightpack::test {

// Whether a test whose independent reader (ktx-parse, nvddsinfo, strace) is missing may skip: only where
// the run says so (HEIGHTPACK_TESTS_MAY_SKIP=1). Elsewhere, CI included, a missing oracle fails the test,
// so a run cannot pass without the readers that judge it.
bool mayRunWithoutOracles();


// A fresh, empty folder under the system temp folder, removed when the object goes.
class ScratchDir {
public:
    ScratchDir();
    ~ScratchDir();
    ScratchDir(const ScratchDir&) = delete;
    ScratchDir& operator=(const ScratchDir&) = delete;
    std::string file(const std::string& name) const { return (path_ / name).string(); }
    const std::filesystem::path& path() const { return path_; }
    // Names of the files in the folder, sorted.
    std::vector<std::string> listing() const;

private:
    std::filesystem::path path_;
};

// An image whose texel (x, y) is f(x, y).
Image makeImage(int width, int height, const std::function<float(int x, int y)>& f);
// A smooth, non-periodic height in [0.1, 0.9] at texel (x, y): the CLI tests' ordinary map.
inline float smoothWave(int x, int y) { return static_cast<float>(0.5 + 0.4 * std::sin(x * 0.19) * std::cos(y * 0.13)); }
// Uniform random values in [lo, hi) from a fixed seed.
Image randomImage(int width, int height, unsigned seed, float lo = 0.0f, float hi = 1.0f);

// Writes pixels (width * height * channels floats in [0,1] for integer types) with OpenImageIO in the
// format the file name says, stored as `type` (uint8, uint16, half, float). Fails the test on error.
void writeImage(const std::string& path, int width, int height, int channels, const std::vector<float>& pixels,
                OIIO::TypeDesc type);
void writeImage(const std::string& path, const Image& image, OIIO::TypeDesc type);

std::vector<unsigned char> readBytes(const std::string& path);
// Little-endian fields of a container header read from its bytes (bounds-checked: a short file fails).
std::uint32_t le32(const std::vector<unsigned char>& b, size_t at);
float leFloat(const std::vector<unsigned char>& b, size_t at);
void writeBytes(const std::string& path, const std::vector<unsigned char>& bytes);

// A PNG whose header claims width x height, followed by a tiny, valid data stream.
std::vector<unsigned char> pngWithClaimedSize(unsigned width, unsigned height);

// A finished child process: its exit code (128 + signal if killed) and what it printed.
struct ProcessResult {
    int code = -1;
    std::string out, err;
    long peakKiB = 0;  // the largest resident set of the process or of any process it waited for
};

// Runs argv (argv[0] looked up on PATH) with the given environment (this process's when empty),
// capturing stdout and stderr.
ProcessResult runProcess(const std::vector<std::string>& argv, const std::vector<std::string>& environment = {});

// Reference lookups written from the definitions, sharing no code with libpack.
// Texel index i brought into [0, n) periodically or by clamping.
int referenceWrap(long long i, int n, bool periodic);
// Plain bilinear filtering of channel 0 at texture coordinate (u, v), as GL_LINEAR does it.
double referenceBilinear(const Image& level, double u, double v, bool periodic);

}  // namespace heightpack::test

// In a test body: skips, or fails where skipping is not allowed (mayRunWithoutOracles), saying why.
#define HEIGHTPACK_WITHOUT_ORACLE(why)                                                                        \
    do {                                                                                                       \
        if (::heightpack::test::mayRunWithoutOracles()) GTEST_SKIP() << why;                                   \
        FAIL() << why << " (HEIGHTPACK_TESTS_MAY_SKIP=1 lets it skip)";                                       \
    } while (false)

