#include "support/seam_families.hpp"

#include <OpenImageIO/imageio.h>
#include <opencv2/core.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <thread>

namespace heightpack::test {

const char* familyName(Family family) {
    switch (family) {
        case Family::Periodic: return "periodic";
        case Family::Crop: return "crop";
        case Family::Ramp: return "ramp";
        case Family::Parabola: return "parabola";
    }
    return "?";
}

const char* formatName(MapFormat format) {
    switch (format) {
        case MapFormat::Png8: return "png8";
        case MapFormat::Png16: return "png16";
        case MapFormat::ExrFloat: return "exr";
        case MapFormat::Jpeg75: return "jpeg75";
        case MapFormat::Jpeg90: return "jpeg90";
    }
    return "?";
}

const char* formatExtension(MapFormat format) {
    switch (format) {
        case MapFormat::Png8:
        case MapFormat::Png16: return ".png";
        case MapFormat::ExrFloat: return ".exr";
        case MapFormat::Jpeg75:
        case MapFormat::Jpeg90: return ".jpg";
    }
    return "";
}

MapSpec drawMap(Family family, int index) {
    std::seed_seq seq{static_cast<unsigned>(family) + 1, static_cast<unsigned>(index), 11u};
    std::mt19937 rng(seq);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    MapSpec spec;
    spec.family = family;
    spec.index = index;
    spec.format = kAllFormats[index % 5];
    spec.seed = static_cast<unsigned>(rng());
    spec.beta = 1.5 + 2.5 * unit(rng);
    const bool anisotropic = unit(rng) < 0.5;
    const double stretch = 1.0 + 2.0 * unit(rng), angle = 3.141592653589793 * unit(rng);
    spec.aniso = anisotropic ? stretch : 1.0;
    spec.angle = anisotropic ? angle : 0.0;
    // Long side: 64 (25%), 128 (30%), 256 (25%), 512 (15%), 1024 (5%).
    const double s = unit(rng);
    const int longSide = s < 0.25 ? 64 : s < 0.55 ? 128 : s < 0.80 ? 256 : s < 0.95 ? 512 : 1024;
    // Square (60%), 4:1 wide (20%), 1:4 tall (20%). A 4:1 map is at least 128x32: check judges a direction
    // only with 32 texels along it (fewer cuts give no stable spread), so a 16-texel side is never judged.
    const double shape = unit(rng);
    const int side = shape < 0.6 ? longSide : std::max(longSide, 128);
    spec.width = shape < 0.8 ? side : side / 4;
    spec.height = shape < 0.6 ? side : shape < 0.8 ? side / 4 : side;
    spec.alongX = unit(rng) < 0.5;
    return spec;
}

std::string describe(const MapSpec& spec) {
    char text[200];
    std::snprintf(text, sizeof text, "%s #%d seed %u beta %.3f aniso %.2f angle %.3f %dx%d %s",
                  familyName(spec.family), spec.index, spec.seed, spec.beta, spec.aniso, spec.angle, spec.width,
                  spec.height, formatName(spec.format));
    std::string s = text;
    if (spec.family == Family::Ramp || spec.family == Family::Parabola) s += spec.alongX ? " along x" : " along y";
    return s;
}

namespace {

void normalise(Image& map, float lo = 0.0f, float hi = 1.0f) {
    const auto [mn, mx] = std::minmax_element(map.pixels.begin(), map.pixels.end());
    const double a = *mn, span = std::max(1e-30, double(*mx) - a);
    for (float& v : map.pixels) v = static_cast<float>(lo + (hi - lo) * ((v - a) / span));
}

// The map at the precision its format stores (integer formats round to their steps; JPEG is 8-bit).
Image atStoredPrecision(const Image& map, MapFormat format) {
    const double steps = format == MapFormat::ExrFloat ? 0.0 : format == MapFormat::Png16 ? 65535.0 : 255.0;
    if (steps == 0.0) return map;
    Image q = map;
    for (float& v : q.pixels) v = static_cast<float>(std::round(std::clamp(double(v), 0.0, 1.0) * steps) / steps);
    return q;
}

// Adds f(i) to every texel, i its index along x (or y).
void addProfile(Image& map, bool alongX, const std::function<double(int)>& f) {
    for (int y = 0; y < map.height; ++y)
        for (int x = 0; x < map.width; ++x) map.at(x, y) += static_cast<float>(f(alongX ? x : y));
}

}  // namespace

Image periodicField(int width, int height, unsigned seed, double beta, double aniso, double angle) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, 1.0);
    const double c = std::cos(angle), s = std::sin(angle);
    cv::Mat spectrum(height, width, CV_64FC2);
    for (int y = 0; y < height; ++y) {
        const double fy = double(y <= height / 2 ? y : y - height) / height;  // cycles per texel
        for (int x = 0; x < width; ++x) {
            const double fx = double(x <= width / 2 ? x : x - width) / width;
            const double u = c * fx + s * fy, v = -s * fx + c * fy;
            const double k = std::hypot(u * aniso, v);
            const double amplitude = k > 0 ? std::pow(k, -beta / 2) : 0.0;  // no DC
            const double re = noise(rng), im = noise(rng);                  // drawn for every bin
            spectrum.at<cv::Vec2d>(y, x) = cv::Vec2d(re * amplitude, im * amplitude);
        }
    }
    cv::Mat field;
    cv::dft(spectrum, field, cv::DFT_INVERSE);  // complex to complex; the real part is periodic too
    Image map(width, height, 1);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) map.at(x, y) = static_cast<float>(field.at<cv::Vec2d>(y, x)[0]);
    normalise(map);
    return map;
}

double meanFirstDifference(const Image& map, bool alongX) {
    double sum = 0;
    long long n = 0;
    for (int y = 0; y + (alongX ? 0 : 1) < map.height; ++y)
        for (int x = 0; x + (alongX ? 1 : 0) < map.width; ++x, ++n)
            sum += std::abs(double(map.at(x + alongX, y + !alongX)) - map.at(x, y));
    return n ? sum / double(n) : 0.0;
}

double meanSecondDifference(const Image& map, bool alongX) {
    double sum = 0;
    long long n = 0;
    const int dx = alongX ? 1 : 0, dy = alongX ? 0 : 1;
    for (int y = dy; y + dy < map.height; ++y)
        for (int x = dx; x + dx < map.width; ++x, ++n)
            sum += std::abs(double(map.at(x + dx, y + dy)) - 2.0 * map.at(x, y) + map.at(x - dx, y - dy));
    return n ? sum / double(n) : 0.0;
}

Image makeMap(const MapSpec& spec) {
    if (spec.family == Family::Crop) {
        // A window of a field twice the size: its opposite edges are w texels apart in that field, never
        // neighbours.
        const Image big = periodicField(2 * spec.width, 2 * spec.height, spec.seed, spec.beta, spec.aniso, spec.angle);
        std::mt19937 rng(spec.seed ^ 0x5eedu);
        const int ox = std::uniform_int_distribution<int>(0, spec.width)(rng);
        const int oy = std::uniform_int_distribution<int>(0, spec.height)(rng);
        Image crop(spec.width, spec.height, 1);
        for (int y = 0; y < spec.height; ++y)
            for (int x = 0; x < spec.width; ++x) crop.at(x, y) = big.at(ox + x, oy + y);
        normalise(crop);
        return crop;
    }
    Image map = periodicField(spec.width, spec.height, spec.seed, spec.beta, spec.aniso, spec.angle);
    if (spec.family == Family::Periodic) return map;
    // The mean differences of the periodic map as its format stores it: an 8-bit smooth map's second
    // differences are mostly its rounding, and a kink far below one grey level is not in the file at all.
    const Image stored = atStoredPrecision(map, spec.format);
    const int n = spec.alongX ? spec.width : spec.height;
    if (spec.family == Family::Ramp) {
        // r(i) = 3 mu1 i / n: inside it climbs 3 mu1 / n a texel; across the wrap it falls 3 mu1 (n-1) / n,
        // a jump of exactly 3 mu1 from where the ramp would have gone.
        const double mu1 = meanFirstDifference(stored, spec.alongX);
        addProfile(map, spec.alongX, [&](int i) { return 3.0 * mu1 * i / n; });
    } else {
        // r(i) = b (i + 0.5 - n/2)^2: r(0) = r(n-1), so heights meet, and the slope goes from about +b n at
        // the right end to -b n at the left: a kink of 2 b n = 6 mu2.
        const double mu2 = meanSecondDifference(stored, spec.alongX);
        const double b = 3.0 * mu2 / n;
        addProfile(map, spec.alongX, [&](int i) { return b * (i + 0.5 - n / 2.0) * (i + 0.5 - n / 2.0); });
    }
    normalise(map);
    return map;
}

WrapRatios wrapRatios(const Image& map) {
    auto along = [&](bool alongX, bool second) {
        const int n = alongX ? map.width : map.height, across = alongX ? map.height : map.width;
        auto h = [&](int i, int j) { return double(alongX ? map.at((i + n) % n, j) : map.at(j, (i + n) % n)); };
        double sum = 0;
        for (int j = 0; j < across; ++j)
            sum += second ? 0.5 * (std::abs(h(n - 2, j) - 2 * h(n - 1, j) + h(0, j)) +
                                   std::abs(h(n - 1, j) - 2 * h(0, j) + h(1, j)))
                          : std::abs(h(0, j) - h(n - 1, j));
        const double inside = second ? meanSecondDifference(map, alongX) : meanFirstDifference(map, alongX);
        return inside > 0 ? sum / across / inside : INFINITY;
    };
    return {along(true, false), along(false, false), along(true, true), along(false, true)};
}

std::string WrapRatios::text() const {
    char t[160];
    std::snprintf(t, sizeof t, "wrap/inside: first x %.3g y %.3g, second x %.3g y %.3g", firstX, firstY, secondX,
                  secondY);
    return t;
}

std::string writeMap(const std::string& path, const Image& map, MapFormat format) {
    if (map.channels != 1) return "writeMap takes one channel";
    auto out = OIIO::ImageOutput::create(path);
    if (!out) return "cannot create a writer for " + path + ": " + OIIO::geterror();
    const OIIO::TypeDesc type = format == MapFormat::ExrFloat ? OIIO::TypeDesc::FLOAT
                                : format == MapFormat::Png16  ? OIIO::TypeDesc::UINT16
                                                              : OIIO::TypeDesc::UINT8;
    OIIO::ImageSpec spec(map.width, map.height, 1, type);
    if (format == MapFormat::Jpeg75) spec.attribute("Compression", "jpeg:75");
    if (format == MapFormat::Jpeg90) spec.attribute("Compression", "jpeg:90");
    if (!out->open(path, spec)) return "cannot open " + path + ": " + out->geterror();
    if (!out->write_image(OIIO::TypeDesc::FLOAT, map.pixels.data()))
        return "cannot write " + path + ": " + out->geterror();
    if (!out->close()) return "cannot close " + path + ": " + out->geterror();
    return {};
}

// ---- Reading a check report: the one place that knows SeamScore's fields ----

std::string WorstSeam::text() const {
    if (level < 0) return "nothing measured";
    char t[160];
    std::snprintf(t, sizeof t, "level %d (%dx%d) %s %s %.3g", level, levelWidth, levelHeight, edge.c_str(),
                  kind.c_str(), score);
    return t;
}

WorstSeam worstSeam(const CheckReport& report) {
    WorstSeam worst;
    for (size_t i = 0; i < report.levels.size(); ++i) {
        const LevelSeams& level = report.levels[i];
        auto consider = [&](const SeamScore& s, const char* edge) {
            if (!s.measured) return;
            for (auto [score, kind] : {std::pair{s.value, "value"}, std::pair{s.slope, "slope"}}) {
                if (worst.level < 0 || score > worst.score || std::isnan(score)) {
                    worst.score = std::isnan(score) ? INFINITY : score;  // an unreadable score is the worst
                    worst.level = static_cast<int>(i);
                    worst.levelWidth = level.width;
                    worst.levelHeight = level.height;
                    worst.edge = edge;
                    worst.kind = kind;
                }
            }
        };
        consider(level.leftRight, "left/right");
        consider(level.topBottom, "top/bottom");
    }
    return worst;
}

// ---- Running many maps ----

void parallelFor(int count, const std::function<void(int)>& job) {
    const int threads = std::max(2u, std::thread::hardware_concurrency());
    std::atomic<int> next{0};
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
        pool.emplace_back([&] {
            for (int i = next++; i < count; i = next++) job(i);
        });
    for (std::thread& t : pool) t.join();
}

MapVerdict checkGeneratedMap(const MapSpec& spec, const std::string& folder) {
    static std::atomic<unsigned> counter{0};
    MapVerdict verdict;
    verdict.spec = spec;
    const std::string path = (std::filesystem::path(folder) / ("map" + std::to_string(counter++) +
                                                                formatExtension(spec.format))).string();
    const Image map = makeMap(spec);
    verdict.ratios = wrapRatios(map);
    verdict.error = writeMap(path, map, spec.format);
    if (verdict.error.empty()) {
        auto report = checkFile(path, CheckOptions{});
        if (report) {
            verdict.tiles = report->tiles;
            verdict.worst = worstSeam(*report);
        } else {
            verdict.error = report.error().what;
        }
    }
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
    return verdict;
}

double quantile(std::vector<double> values, double q) {
    if (values.empty()) return NAN;
    std::sort(values.begin(), values.end());
    const double rank = std::ceil(q * double(values.size()));
    const size_t i = static_cast<size_t>(std::clamp(rank - 1.0, 0.0, double(values.size() - 1)));
    return values[i];
}

std::string distributionText(const std::vector<double>& values) {
    char text[200];
    std::snprintf(text, sizeof text, "min %.3g  p1 %.3g  median %.3g  p99 %.3g  max %.3g", quantile(values, 0.0),
                  quantile(values, 0.01), quantile(values, 0.5), quantile(values, 0.99), quantile(values, 1.0));
    return text;
}

int scaledCount(int count, int minimum) {
    double scale = 1.0;
    if (const char* s = std::getenv("HEIGHTPACK_SEAM_SCALE")) {
        char* end = nullptr;
        const double v = std::strtod(s, &end);
        if (end != s && v > 0) scale = v;
    }
    return std::max(minimum, static_cast<int>(std::lround(count * scale)));
}

}  // namespace heightpack::test
