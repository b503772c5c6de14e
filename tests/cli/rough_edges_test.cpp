// The rough edges a new user hits first: progress on a terminal, one JSON document per sequence, channel
// names and what was used, heightpack's own textures as input, what --resize pow2 did, ignored options.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <poll.h>
#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <filesystem>

#include "support/heightpack_process.hpp"
#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

// Runs heightpack with stdout and stderr on one pseudo-terminal, as a person at a terminal sees it.
ProcessResult runInPty(const std::vector<std::string>& args, const std::string& cwd = {}) {
    std::vector<std::string> argv = {HEIGHTPACK_EXE};
    argv.insert(argv.end(), args.begin(), args.end());
    int master = -1;
    const pid_t pid = forkpty(&master, nullptr, nullptr, nullptr);
    if (pid == 0) {
        if (!cwd.empty() && chdir(cwd.c_str()) != 0) _exit(127);
        std::vector<char*> raw;
        for (std::string& a : argv) raw.push_back(a.data());
        raw.push_back(nullptr);
        execv(raw[0], raw.data());
        _exit(127);
    }
    ProcessResult result;
    char buffer[4096];
    for (;;) {
        const ssize_t n = read(master, buffer, sizeof buffer);
        if (n <= 0) break;  // EIO once the child has gone and the terminal is closed
        result.out.append(buffer, static_cast<size_t>(n));
    }
    close(master);
    int status = 0;
    waitpid(pid, &status, 0);
    result.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    return result;
}

// Every line that reports a result starts at column 0: at the start of the output, after a newline, or
// right after the bar was cleared with "\r\033[K".
void expectResultLinesAtColumnZero(const std::string& screen, const std::vector<std::string>& starts) {
    for (const std::string& start : starts) {
        size_t found = 0;
        for (size_t at = screen.find(start); at != std::string::npos; at = screen.find(start, at + 1)) {
            ++found;
            const bool lineStart = at == 0 || screen[at - 1] == '\n' ||
                                   (at >= 4 && screen.compare(at - 4, 4, "\r\033[K") == 0);
            EXPECT_TRUE(lineStart) << "'" << start << "' does not start a line: ..."
                                   << screen.substr(at >= 40 ? at - 40 : 0, 80);
        }
        EXPECT_GT(found, 0u) << "no '" << start << "' in: " << screen;
    }
}

// The percentages the bar showed, in order: "] NN%". (Parsed by hand: GCC 12 warns inside <regex> under
// the sanitizer build's -O2, and warnings are errors.)
std::vector<int> percentages(const std::string& screen) {
    std::vector<int> out;
    for (size_t at = screen.find(']'); at != std::string::npos; at = screen.find(']', at + 1)) {
        size_t i = at + 1;
        while (i < screen.size() && screen[i] == ' ') ++i;
        if (i == at + 1) continue;
        const size_t digits = i;
        while (i < screen.size() && std::isdigit(static_cast<unsigned char>(screen[i]))) ++i;
        if (i > digits && i < screen.size() && screen[i] == '%') out.push_back(std::stoi(screen.substr(digits, i - digits)));
    }
    return out;
}

// The labels of the bars drawn: "\r\x1b[K" LABEL ": " stage " [" 24 of '#' or ' ' "]".
std::vector<std::string> barLabels(const std::string& screen) {
    std::vector<std::string> labels;
    const std::string start = "\r\x1b[K";
    for (size_t at = screen.find(start); at != std::string::npos; at = screen.find(start, at + 1)) {
        const size_t label = at + start.size();
        const size_t colon = screen.find(": ", label);
        const size_t lineEnd = screen.find_first_of("\r\n", label);
        if (colon == std::string::npos || (lineEnd != std::string::npos && colon > lineEnd)) continue;
        const size_t open = screen.find('[', colon);
        if (open == std::string::npos || (lineEnd != std::string::npos && open > lineEnd) || open + 25 >= screen.size())
            continue;
        const std::string cells = screen.substr(open + 1, 24);
        if (screen[open + 25] == ']' && cells.find_first_not_of("# ") == std::string::npos)
            labels.push_back(screen.substr(label, colon - label));
    }
    return labels;
}

void expectNeverDown(const std::vector<int>& shown) {
    for (size_t i = 1; i < shown.size(); ++i) EXPECT_GE(shown[i], shown[i - 1]) << "at " << i;
}

float wave(int x, int y) { return static_cast<float>(0.5 + 0.4 * std::sin(x * 0.09) * std::cos(y * 0.07)); }

// A float EXR with the given channel names, channel c of texel (x, y) being f(c, x, y).
void writeNamedExr(const std::string& path, int w, int h, const std::vector<std::string>& names,
                   const std::function<float(int, int, int)>& f) {
    OIIO::ImageSpec spec(w, h, static_cast<int>(names.size()), OIIO::TypeDesc::FLOAT);
    spec.channelnames = names;
    std::vector<float> pixels(size_t(w) * h * names.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (size_t c = 0; c < names.size(); ++c) pixels[(size_t(y) * w + x) * names.size() + c] = f(int(c), x, y);
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out && out->open(path, spec));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    out->close();
}

// Level 0 of an image file, every channel.
std::vector<float> readLevel0(const std::string& path, int& channels) {
    auto in = OIIO::ImageInput::open(path);
    EXPECT_TRUE(in) << path;
    if (!in) return {};
    const OIIO::ImageSpec& spec = in->spec();
    channels = spec.nchannels;
    std::vector<float> pixels(spec.image_pixels() * spec.nchannels);
    EXPECT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()));
    return pixels;
}

}  // namespace

TEST(RoughEdges, PackProgressIsClearedBeforeTheResultAndNeverGoesBack) {
    ScratchDir dir;
    writeImage(dir.file("big.png"), makeImage(1024, 1024, wave), OIIO::TypeDesc::UINT16);
    const ProcessResult run = runInPty({"pack", dir.file("big.png"), "-o", dir.file("big.exr")});
    ASSERT_EQ(run.code, 0) << run.out;
    EXPECT_FALSE(percentages(run.out).empty()) << "no bar on a terminal: " << run.out;
    expectResultLinesAtColumnZero(run.out, {"wrote "});
    expectNeverDown(percentages(run.out));
}

TEST(RoughEdges, EveryCommandThatWorksShowsABarAndClearsIt) {
    ScratchDir dir;
    writeImage(dir.file("map.png"), makeImage(512, 512, wave), OIIO::TypeDesc::UINT16);
    const std::vector<std::vector<std::string>> runs = {
        {"synth", "--wind", "8m/s", "--tile-size", "64m", "--size", "256", "-o", dir.file("sea.exr")},
        {"tile", dir.file("map.png"), "--force", "-o", dir.file("tiled.png")},
        {"check", dir.file("map.png")},
        {"normal", dir.file("map.png"), "--tile-size", "8m", "--height", "1m", "-o", dir.file("n.exr")},
    };
    for (const auto& args : runs) {
        const ProcessResult run = runInPty(args);
        ASSERT_LE(run.code, 1) << args[0] << ": " << run.out;
        const std::vector<int> shown = percentages(run.out);
        EXPECT_FALSE(shown.empty()) << args[0] << " shows no bar: " << run.out;
        expectNeverDown(shown);
        // Whatever follows the bar starts on a cleared line.
        const size_t lastBar = run.out.rfind('%');
        ASSERT_NE(lastBar, std::string::npos);
        EXPECT_EQ(run.out.compare(lastBar + 1, 4, "\r\033[K"), 0) << args[0] << ": " << run.out.substr(lastBar);
        expectResultLinesAtColumnZero(run.out, {args[0] == "check" ? dir.file("map.png") + ": " : "wrote "});
    }
}

TEST(RoughEdges, BuildShowsOneBarForAllJobs) {
    ScratchDir dir;
    const std::string examples = std::string(HEIGHTPACK_SOURCE_DIR) + "/examples/";
    const ProcessResult run = runInPty({"build", examples + "ocean.toml", examples + "lagoon.toml", "--jobs", "2",
                                        "-o", dir.file("out")});
    ASSERT_EQ(run.code, 0) << run.out;
    expectNeverDown(percentages(run.out));
    expectResultLinesAtColumnZero(run.out, {"  rebuilt", "building ocean", "ocean: ", "lagoon: "});
    // One bar: labelled by the build, never by one output of one material.
    const std::vector<std::string> labels = barLabels(run.out);
    for (const std::string& label : labels) EXPECT_EQ(label, "build");
    EXPECT_FALSE(labels.empty()) << run.out;
}

TEST(RoughEdges, SequenceJsonIsOneDocumentAndInfoDescribesTheSequence) {
    ScratchDir dir;
    const ProcessResult synth = heightpackRun({"synth", "--wind", "8m/s", "--tile-size", "64m", "--size", "64",
                                               "--frames", "3", "--loop", "8s", "-o", dir.file("seq.exr"), "-q"});
    ASSERT_EQ(synth.code, 0) << synth.err;
    const std::string seq = dir.file("seq.exr");

    const ProcessResult check = heightpackRun({"check", seq, "--json"});
    ASSERT_LE(check.code, 1) << check.err;
    const auto c = nlohmann::json::parse(check.out);  // throws on several documents
    ASSERT_EQ(c["frames"].size(), 3u);
    bool all = true;
    for (const auto& f : c["frames"]) all = all && f["tiles"].get<bool>();
    EXPECT_EQ(c["tiles"], all);
    EXPECT_EQ(c["frames"][2]["input"], dir.file("seq.0002.exr"));

    const ProcessResult normal =
        heightpackRun({"normal", seq, "--tile-size", "64m", "--height", "1m", "-o", dir.file("n.exr"), "--json"});
    ASSERT_EQ(normal.code, 0) << normal.err;
    const auto n = nlohmann::json::parse(normal.out);
    ASSERT_EQ(n["frames"].size(), 3u);
    EXPECT_EQ(n["frames"][1]["output"], dir.file("n.0001.exr"));

    const ProcessResult info = heightpackRun({"info", seq, "--json"});
    ASSERT_EQ(info.code, 0) << info.err;
    const auto i = nlohmann::json::parse(info.out);
    ASSERT_EQ(i["frames"].size(), 3u);
    // Each frame's statistics are those of its file.
    for (int f = 0; f < 3; ++f) {
        int channels = 0;
        const std::vector<float> px = readLevel0(dir.file("seq.000" + std::to_string(f) + ".exr"), channels);
        EXPECT_FLOAT_EQ(i["frames"][f]["levels"][0]["channels"][0]["max"].get<float>(),
                        *std::max_element(px.begin(), px.end()));
    }
    const ProcessResult text = heightpackRun({"info", seq});
    ASSERT_EQ(text.code, 0) << text.err;
    EXPECT_NE(text.out.find("3 frames"), std::string::npos) << text.out;
}

TEST(RoughEdges, ChannelByNameAndWhatWasUsed) {
    ScratchDir dir;
    // A DCC tool's EXR: the height in a layer, with other channels beside it.
    writeNamedExr(dir.file("dcc.exr"), 64, 64, {"Z", "depth", "height.Y"},
                  [](int c, int x, int y) { return float(c) + wave(x, y); });
    for (const auto& [name, channel] : std::vector<std::pair<std::string, int>>{{"Z", 0}, {"depth", 1}, {"height.Y", 2},
                                                                                {"height", 2}}) {
        const ProcessResult pack =
            heightpackRun({"pack", dir.file("dcc.exr"), "--channel", name, "-o", dir.file("out.exr"), "--json"});
        ASSERT_EQ(pack.code, 0) << name << ": " << pack.err;
        const auto j = nlohmann::json::parse(pack.out);
        EXPECT_EQ(j["source"]["channel"]["used"], channel == 0 ? "Z" : channel == 1 ? "depth" : "height.Y");
        int channels = 0;
        const std::vector<float> px = readLevel0(dir.file("out.exr"), channels);
        ASSERT_EQ(channels, 4);
        for (int y = 0; y < 64; y += 7)
            for (int x = 0; x < 64; x += 5) ASSERT_NEAR(px[(y * 64 + x) * 4], channel + wave(x, y), 1e-6) << name;
    }
    const ProcessResult missing = heightpackRun({"pack", dir.file("dcc.exr"), "--channel", "nope", "-o", dir.file("x.exr")});
    EXPECT_EQ(missing.code, 3);
    EXPECT_NE(missing.err.find("height.Y"), std::string::npos) << missing.err;  // says what it has

    // Grey + alpha: the grey is used and that is said.
    const Image grey = makeImage(64, 64, wave);
    std::vector<float> greyAlpha;
    for (float v : grey.pixels) greyAlpha.insert(greyAlpha.end(), {v, 1.0f - v});
    writeImage(dir.file("ga.png"), 64, 64, 2, greyAlpha, OIIO::TypeDesc::UINT16);
    const ProcessResult ga = heightpackRun({"pack", dir.file("ga.png"), "-o", dir.file("ga.exr")});
    ASSERT_EQ(ga.code, 0) << ga.err;
    EXPECT_NE(ga.out.find("note: grey image with alpha"), std::string::npos) << ga.out;
    const ProcessResult gaJson = heightpackRun({"check", dir.file("ga.png"), "--json"});
    EXPECT_FALSE(nlohmann::json::parse(gaJson.out)["channel"]["note"].is_null()) << gaJson.out;

    // A colour choice on a grey image: accepted, and said.
    writeImage(dir.file("grey.png"), grey, OIIO::TypeDesc::UINT16);
    const ProcessResult r = heightpackRun({"normal", dir.file("grey.png"), "--channel", "r", "--tile-size", "8m",
                                           "--height", "1m", "-o", dir.file("n.exr"), "--json"});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_FALSE(nlohmann::json::parse(r.out)["channel"]["note"].is_null()) << r.out;
    const ProcessResult rText = heightpackRun({"tile", dir.file("grey.png"), "--channel", "r", "-o", dir.file("t.png")});
    ASSERT_EQ(rText.code, 0) << rText.err;
    EXPECT_NE(rText.out.find("note: grey image"), std::string::npos) << rText.out;
}

TEST(RoughEdges, EveryCommandReadsHeightpacksOwnTexturesBackToValues) {
    ScratchDir dir;
    writeImage(dir.file("map.png"), makeImage(64, 64, wave), OIIO::TypeDesc::UINT16);
    ASSERT_EQ(heightpackRun({"pack", dir.file("map.png"), "--scale", "2.5", "--offset", "-1", "-o", dir.file("p.exr"),
                             "--emit-plain", dir.file("plain.exr")})
                  .code,
              0);
    // normal of the packed and of the plain texture is the normal of the painting they came from.
    const std::vector<std::string> common = {"--tile-size", "8m", "--height", "1m"};
    for (const std::string& input : {dir.file("map.png"), dir.file("p.exr"), dir.file("plain.exr")}) {
        std::vector<std::string> args = {"normal", input, "-o", dir.file(std::filesystem::path(input).stem().string() + "_n.exr")};
        args.insert(args.end(), common.begin(), common.end());
        const ProcessResult run = heightpackRun(args);
        ASSERT_EQ(run.code, 0) << input << ": " << run.err;
    }
    int channels = 0;
    const std::vector<float> reference = readLevel0(dir.file("map_n.exr"), channels);
    for (const char* made : {"p_n.exr", "plain_n.exr"}) {
        const std::vector<float> px = readLevel0(dir.file(made), channels);
        ASSERT_EQ(px.size(), reference.size());
        for (size_t i = 0; i < px.size(); ++i) ASSERT_NEAR(px[i], reference[i], 1e-4) << made << " at " << i;
    }
    // pack and tile of the packed texture see the painted values: stored = offset + scale * value again.
    ASSERT_EQ(heightpackRun({"pack", dir.file("p.exr"), "-o", dir.file("again.exr")}).code, 0);
    const std::vector<float> again = readLevel0(dir.file("again.exr"), channels);
    const Image painted = makeImage(64, 64, wave);
    for (size_t i = 0; i < painted.pixels.size(); ++i)
        ASSERT_NEAR(again[i * 4], std::round(painted.pixels[i] * 65535.0f) / 65535.0f, 1e-5) << i;
    const ProcessResult tile = heightpackRun({"tile", dir.file("p.exr"), "--force", "-o", dir.file("t.exr")});
    EXPECT_EQ(tile.code, 0) << tile.err;
    // A normal map is not heights: refused, naming what it is.
    const ProcessResult refused = heightpackRun({"pack", dir.file("p_n.exr"), "-o", dir.file("x.exr")});
    EXPECT_EQ(refused.code, 3);
    EXPECT_NE(refused.err.find("normal map"), std::string::npos) << refused.err;
}

TEST(RoughEdges, ResizeSaysTheNewSizeTheAspectAndTheNearestPowersOfTwo) {
    ScratchDir dir;
    writeImage(dir.file("odd.png"), makeImage(1000, 600, wave), OIIO::TypeDesc::UINT8);
    const ProcessResult text = heightpackRun({"pack", dir.file("odd.png"), "--resize", "pow2", "-o", dir.file("o.exr")});
    ASSERT_EQ(text.code, 0) << text.err;
    EXPECT_NE(text.out.find("1000x600 to 1024x1024"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("stretched"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("1024x512"), std::string::npos) << text.out;  // 600 is nearer 512 than 1024
    const ProcessResult json = heightpackRun({"normal", dir.file("odd.png"), "--resize", "pow2", "--tile-size", "8m",
                                              "--height", "1m", "-o", dir.file("n.exr"), "--json"});
    ASSERT_EQ(json.code, 0) << json.err;
    const auto j = nlohmann::json::parse(json.out)["resize"];
    EXPECT_EQ(j["to"]["width"], 1024);
    EXPECT_EQ(j["to"]["height"], 1024);
    EXPECT_NEAR(j["aspectFrom"].get<double>(), 1000.0 / 600.0, 1e-9);
    EXPECT_EQ(j["nearestPowerOfTwo"]["width"], 1024);
    EXPECT_EQ(j["nearestPowerOfTwo"]["height"], 512);
}

TEST(RoughEdges, SynthWarnsWhenJonswapOptionsMeetPhillips) {
    ScratchDir dir;
    const ProcessResult run = heightpackRun({"synth", "--spectrum", "phillips", "--fetch", "10km", "--wind", "8m/s",
                                             "--tile-size", "64m", "--size", "32", "-o", dir.file("s.exr")});
    ASSERT_EQ(run.code, 0) << run.err;
    EXPECT_NE(run.err.find("--fetch is ignored"), std::string::npos) << run.err;
    const ProcessResult help = heightpackRun({"synth", "--help"});
    EXPECT_NE(help.out.find("100km"), std::string::npos) << help.out;  // --fetch's default is stated
}

TEST(RoughEdges, FresnelTakesTheManifestsIorRange) {
    // docs/manifest.md: ior 1-4. The command line took up to 10.
    ScratchDir dir;
    EXPECT_EQ(heightpackRun({"fresnel", "--ior", "4", "-o", dir.file("a.exr")}).code, 0);
    EXPECT_EQ(heightpackRun({"fresnel", "--ior", "5", "-o", dir.file("b.exr")}).code, 2);
}
