#include "support/test_support.hpp"

#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cstdlib>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

extern char** environ;

namespace heightpack::test {

bool mayRunWithoutOracles() {
    const char* may = std::getenv("HEIGHTPACK_TESTS_MAY_SKIP");
    return may != nullptr && std::string(may) == "1";
}


namespace fs = std::filesystem;

ScratchDir::ScratchDir() {
    static std::atomic<int> counter{0};
    path_ = fs::temp_directory_path() /
            ("heightpack-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    fs::remove_all(path_);
    fs::create_directories(path_);
}

ScratchDir::~ScratchDir() {
    std::error_code ec;
    // Make read-only files removable again.
    for (const auto& entry : fs::recursive_directory_iterator(path_, ec))
        fs::permissions(entry.path(), fs::perms::owner_all, fs::perm_options::add, ec);
    fs::remove_all(path_, ec);
}

std::vector<std::string> ScratchDir::listing() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(path_)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

Image makeImage(int width, int height, const std::function<float(int, int)>& f) {
    Image image(width, height, 1);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) image.at(x, y) = f(x, y);
    return image;
}

Image randomImage(int width, int height, unsigned seed, float lo, float hi) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> dist(lo, hi);
    return makeImage(width, height, [&](int, int) { return dist(rng); });
}

void writeImage(const std::string& path, int width, int height, int channels, const std::vector<float>& pixels,
                OIIO::TypeDesc type) {
    ASSERT_EQ(pixels.size(), size_t(width) * height * channels);
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out) << OIIO::geterror();
    OIIO::ImageSpec spec(width, height, channels, type);
    ASSERT_TRUE(out->open(path, spec)) << out->geterror();
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data())) << out->geterror();
    ASSERT_TRUE(out->close());
}

void writeImage(const std::string& path, const Image& image, OIIO::TypeDesc type) {
    writeImage(path, image.width, image.height, image.channels, image.pixels, type);
}

std::vector<unsigned char> readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const std::string& path, const std::vector<unsigned char>& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

std::vector<unsigned char> pngWithClaimedSize(unsigned width, unsigned height) {
    std::vector<unsigned char> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    auto be32 = [](std::vector<unsigned char>& v, unsigned x) {
        for (int s = 24; s >= 0; s -= 8) v.push_back(static_cast<unsigned char>(x >> s));
    };
    auto chunk = [&](const char* type, const std::vector<unsigned char>& data) {
        be32(png, static_cast<unsigned>(data.size()));
        std::vector<unsigned char> body(type, type + 4);
        body.insert(body.end(), data.begin(), data.end());
        png.insert(png.end(), body.begin(), body.end());
        be32(png, static_cast<unsigned>(crc32(0, body.data(), static_cast<uInt>(body.size()))));
    };
    std::vector<unsigned char> ihdr;
    be32(ihdr, width);
    be32(ihdr, height);
    ihdr.insert(ihdr.end(), {8, 0, 0, 0, 0});  // 8-bit grey, deflate, no filter, no interlace
    chunk("IHDR", ihdr);
    // One compressed row of zeros: far too little for the claimed size.
    std::vector<unsigned char> raw(64, 0), packed(128);
    uLongf packedSize = static_cast<uLongf>(packed.size());
    compress(packed.data(), &packedSize, raw.data(), static_cast<uLong>(raw.size()));
    packed.resize(packedSize);
    chunk("IDAT", packed);
    chunk("IEND", {});
    return png;
}

std::uint32_t le32(const std::vector<unsigned char>& b, size_t at) {
    return std::uint32_t(b.at(at)) | std::uint32_t(b.at(at + 1)) << 8 | std::uint32_t(b.at(at + 2)) << 16 |
           std::uint32_t(b.at(at + 3)) << 24;
}

float leFloat(const std::vector<unsigned char>& b, size_t at) {
    const std::uint32_t u = le32(b, at);
    float v;
    std::memcpy(&v, &u, 4);
    return v;
}

ProcessResult runProcess(const std::vector<std::string>& argv, const std::vector<std::string>& environment) {
    ScratchDir io;
    const std::string outPath = io.file("stdout"), errPath = io.file("stderr");
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, outPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, 2, errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    std::vector<std::string> args = argv, env = environment;
    std::vector<char*> argp, envp;
    for (auto& a : args) argp.push_back(a.data());
    argp.push_back(nullptr);
    for (auto& e : env) envp.push_back(e.data());
    envp.push_back(nullptr);
    ProcessResult result;
    pid_t pid = 0;
    const int spawned = posix_spawnp(&pid, argp[0], &actions, nullptr, argp.data(), env.empty() ? environ : envp.data());
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0) return result;
    int status = 0;
    struct rusage usage {};
    wait4(pid, &status, 0, &usage);
    result.peakKiB = usage.ru_maxrss;
    result.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    auto slurp = [](const std::string& path) {
        std::ifstream in(path);
        std::stringstream text;
        text << in.rdbuf();
        return text.str();
    };
    result.out = slurp(outPath);
    result.err = slurp(errPath);
    return result;
}

int referenceWrap(long long i, int n, bool periodic) {
    if (!periodic) return static_cast<int>(std::min<long long>(std::max<long long>(i, 0), n - 1));
    long long r = i;
    while (r < 0) r += n;
    return static_cast<int>(r % n);
}

double referenceBilinear(const Image& level, double u, double v, bool periodic) {
    // GL_LINEAR: the four texels around (u*W - 0.5, v*H - 0.5), each index wrapped on its own.
    const double x = u * level.width - 0.5, y = v * level.height - 0.5;
    const long long x0 = static_cast<long long>(std::floor(x)), y0 = static_cast<long long>(std::floor(y));
    const double a = x - x0, b = y - y0;
    auto h = [&](long long i, long long j) {
        return double(level.at(referenceWrap(i, level.width, periodic), referenceWrap(j, level.height, periodic)));
    };
    return (1 - a) * (1 - b) * h(x0, y0) + a * (1 - b) * h(x0 + 1, y0) + (1 - a) * b * h(x0, y0 + 1) +
           a * b * h(x0 + 1, y0 + 1);
}

}  // namespace heightpack::test
