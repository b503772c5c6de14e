#include "support/block_oracles.hpp"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "heightpack/io/gpu_texture.hpp"

namespace heightpack::test {

std::vector<unsigned char> hexBytes(const std::string& hex) {
    std::vector<unsigned char> out;
    for (size_t i = 0; i + 1 < hex.size(); i += 2) out.push_back((unsigned char)std::stoi(hex.substr(i, 2), nullptr, 16));
    return out;
}

std::vector<double> numberList(const std::string& text) {
    std::vector<double> out;
    for (size_t at = 0; at < text.size();) {
        const size_t comma = std::min(text.find(',', at), text.size());
        out.push_back(std::stod(text.substr(at, comma - at)));
        at = comma + 1;
    }
    return out;
}

Image rgtcDecode(const std::vector<std::uint8_t>& blocks, int width, int height, int channels) {
    Image out(width, height, channels);
    const int blockSize = 8 * channels, across = (width + 3) / 4;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < channels; ++c) {
                const std::uint8_t* b = blocks.data() + size_t((y / 4) * across + x / 4) * blockSize + 8 * c;
                std::uint64_t bits = 0;
                for (int i = 5; i >= 0; --i) bits = bits * 256 + b[2 + i];
                const int code = int((bits >> (3 * (4 * (y % 4) + x % 4))) & 7);
                const double r0 = b[0], r1 = b[1];
                double v;
                if (code == 0) v = r0;
                else if (code == 1) v = r1;
                else if (b[0] > b[1]) v = ((8 - code) * r0 + (code - 1) * r1) / 7;
                else if (code < 6) v = ((6 - code) * r0 + (code - 1) * r1) / 5;
                else v = code == 6 ? 0.0 : 255.0;
                out.at(x, y, c) = float(v);
            }
    return out;
}

bool astcencInstalled() { return runProcess({"sh", "-c", "command -v astcenc"}).code == 0; }

Image astcencDecode(const ScratchDir& dir, const std::string& blocksHex, int side, int width, int height, AstcProfile profile) {
    std::vector<unsigned char> file = {0x13, 0xAB, 0xA1, 0x5C, (unsigned char)side, (unsigned char)side, 1};
    for (const int v : {width, height, 1})
        for (int i = 0; i < 3; ++i) file.push_back((unsigned char)(v >> (8 * i)));
    const std::vector<unsigned char> blocks = hexBytes(blocksHex);
    file.insert(file.end(), blocks.begin(), blocks.end());
    writeBytes(dir.file("level.astc"), file);
    const ProcessResult r = runProcess({"astcenc", profile == AstcProfile::Hdr ? "-dh" : "-dl", dir.file("level.astc"),
                                        dir.file("level.exr"), "-silent"});
    EXPECT_EQ(r.code, 0) << r.err << r.out;
    auto in = OIIO::ImageInput::open(dir.file("level.exr"));
    EXPECT_TRUE(in) << "astcenc wrote no EXR";
    if (!in) return {};
    const OIIO::ImageSpec& spec = in->spec();
    EXPECT_EQ(spec.nchannels, 4);
    Image out(spec.width, spec.height, spec.nchannels);
    EXPECT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, out.pixels.data()));
    return out;
}

namespace {

double xyAngleDegrees(double ax, double ay, double bx, double by) {
    auto unit = [](double x, double y, double n[3]) {
        const double rr = x * x + y * y;
        const double r = rr > 1.0 ? std::sqrt(rr) : 1.0;
        n[0] = x / r, n[1] = y / r, n[2] = std::sqrt(std::max(0.0, 1.0 - rr));
    };
    double a[3], b[3];
    unit(ax, ay, a);
    unit(bx, by, b);
    const double cross[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    const double sine = std::sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]);
    return std::atan2(sine, a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) * 180.0 / M_PI;
}

}  // namespace

double worstXyAngleDegrees(const std::string& stored, const std::string& reference) {
    const auto a = readGpuTexture(stored), b = readGpuTexture(reference);
    EXPECT_TRUE(a) << stored;
    EXPECT_TRUE(b) << reference;
    if (!a || !b) return 0.0;
    EXPECT_EQ(a->levels.size(), b->levels.size());
    double worst = 0.0;
    for (size_t level = 0; level < std::min(a->levels.size(), b->levels.size()); ++level) {
        const Image &s = a->levels[level], &r = b->levels[level];
        for (int y = 0; y < s.height; ++y)
            for (int x = 0; x < s.width; ++x)
                worst = std::max(worst, xyAngleDegrees(s.at(x, y, 0), s.at(x, y, 1), r.at(x, y, 0), r.at(x, y, 1)));
    }
    return worst;
}

}  // namespace heightpack::test
