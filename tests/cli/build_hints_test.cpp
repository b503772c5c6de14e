// The commands `heightpack build` suggests, run as a person would run them: each way a build fails with
// a command in its hint is made to happen, the command is taken from the error line, run by the shell in
// the folder the build ran in, the manifest changed as the hint says, and the manifest then builds.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support/heightpack_process.hpp"
#include "support/test_support.hpp"

namespace heightpack::test {
namespace {

namespace fs = std::filesystem;

// A painting whose edges do not meet (a ramp across it and an off-period wave): it does not tile.
float hintPainting(int x, int y, int size, double phase) {
    return static_cast<float>(0.2 + 0.5 * x / size + 0.1 * std::sin(0.37 * y + phase) * std::cos(0.23 * x));
}

// Interleaved channels: the painting in channel `heights` of `channels` (in every one when it is -1:
// its luma), the others something else.
std::vector<float> hintColourPainting(int size, int channels, int heights) {
    std::vector<float> pixels;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            for (int c = 0; c < channels; ++c)
                pixels.push_back(c == heights || heights < 0 ? hintPainting(x, y, size, 0.0) : 0.3f + 0.2f * c * y / size);
    return pixels;
}

std::string hintQuoted(const std::string& word) { return "'" + word + "'"; }  // for the paths of this test

// Runs a command line with the shell in folder, heightpack standing for the binary under test.
ProcessResult hintShell(const fs::path& folder, const std::string& command) {
    std::string line = command;
    if (line.rfind("heightpack ", 0) == 0) line = hintQuoted(HEIGHTPACK_EXE) + line.substr(10);
    return runProcess({"/bin/sh", "-c", "cd " + hintQuoted(folder.string()) + " && " + line});
}

// What a failing build suggests: per error line, the command and the source the manifest is to name.
struct Suggestion {
    std::string command;
    std::string source;
    bool removeChannel = false;
};

// Parsed by hand, not with <regex>: GCC 12 warns inside <regex> in the sanitizer build, and warnings are
// errors. A line reads: ... make it tile with 'COMMAND'..., then set source = "SOURCE"[ and remove channel]
std::vector<Suggestion> suggestions(const std::string& err) {
    std::vector<Suggestion> found;
    std::istringstream lines(err);
    const std::string lead = "make it tile with '", set = ", then set source = \"";
    for (std::string line; std::getline(lines, line);) {
        const size_t start = line.find(lead);
        const size_t commandEnd = start == std::string::npos ? start : line.find('\'', start + lead.size());
        const size_t setAt = commandEnd == std::string::npos ? commandEnd : line.find(set, commandEnd);
        const size_t sourceEnd = setAt == std::string::npos ? setAt : line.find('"', setAt + set.size());
        EXPECT_NE(sourceEnd, std::string::npos) << line;
        if (sourceEnd == std::string::npos) continue;
        Suggestion s;
        s.command = line.substr(start + lead.size(), commandEnd - start - lead.size());
        s.source = line.substr(setAt + set.size(), sourceEnd - setAt - set.size());
        s.removeChannel = line.compare(sourceEnd + 1, 19, " and remove channel") == 0;
        found.push_back(s);
    }
    return found;
}

void hintWrite(const fs::path& path, const std::string& text) {
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
}

// The manifest with its source line (and, as the hint asks, its channel line) changed.
std::string hintApplied(std::string text, const std::string& sourceLine, const Suggestion& s) {
    const size_t at = text.find(sourceLine);
    EXPECT_NE(at, std::string::npos) << sourceLine;
    text.replace(at, sourceLine.size(), "source = \"" + s.source + "\"\n");
    if (s.removeChannel) {
        const size_t channel = text.find("channel = \"");
        EXPECT_NE(channel, std::string::npos);
        if (channel != std::string::npos) text.erase(channel, text.find('\n', channel) + 1 - channel);
    }
    return text;
}

struct HintCase {
    const char* what;
    std::string manifest;    // water/m.toml
    std::string sourceLine;  // the line the hint's source replaces
    int failures;            // error lines, each with a command
    std::vector<std::string> mentions;  // what the commands must say
};

// The build fails in the folder that holds water/ and "my maps/"; every suggested command run from that
// folder exits 0, and the manifest changed as the hint says then builds.
void expectSuggestionsWork(const ScratchDir& dir, const HintCase& c) {
    SCOPED_TRACE(c.what);
    const fs::path manifest = dir.path() / "water/m.toml";
    hintWrite(manifest, c.manifest);
    const ProcessResult failed = hintShell(dir.path(), "heightpack build water/m.toml -o out -q");
    ASSERT_EQ(failed.code, 1) << failed.err;
    const std::vector<Suggestion> hints = suggestions(failed.err);
    ASSERT_EQ(static_cast<int>(hints.size()), c.failures) << failed.err;
    for (const Suggestion& s : hints) {
        for (const std::string& word : c.mentions) EXPECT_NE(s.command.find(word), std::string::npos) << s.command;
        const ProcessResult tiled = hintShell(dir.path(), s.command);
        EXPECT_EQ(tiled.code, 0) << s.command << "\n" << tiled.err;
        EXPECT_EQ(s.source, hints[0].source) << "every frame's hint names the same source";
    }
    hintWrite(manifest, hintApplied(c.manifest, c.sourceLine, hints[0]));
    const ProcessResult built = hintShell(dir.path(), "heightpack build water/m.toml -o out -q");
    EXPECT_EQ(built.code, 0) << "after the hint's source = \"" << hints[0].source << "\":\n" << built.err;
    EXPECT_TRUE(fs::exists(dir.path() / "out/material.json"));
}

TEST(BuildHints, EverySuggestedTileCommandWorksAndTheManifestThenBuilds) {
    ScratchDir dir;
    constexpr int kSize = 128;
    const fs::path maps = dir.path() / "my maps";  // a space: the command must quote the path
    fs::create_directories(maps);
    // The case: a colour PNG whose luma holds the heights.
    writeImage((maps / "wz_water.png").string(), kSize, kSize, 3, hintColourPainting(kSize, 3, -1),
               OIIO::TypeDesc::UINT8);
    // Heights in alpha, for the normal map: after tiling there is no alpha, so channel must go.
    writeImage((maps / "ripple.png").string(), kSize, kSize, 4, hintColourPainting(kSize, 4, 3), OIIO::TypeDesc::UINT8);
    // A sequence of two frames, neither tiling.
    for (int f = 0; f < 2; ++f)
        writeImage((maps / ("waves.000" + std::to_string(f) + ".png")).string(),
                   makeImage(kSize, kSize, [&](int x, int y) { return hintPainting(x, y, kSize, 1.3 * f); }),
                   OIIO::TypeDesc::UINT16);

    const std::string head = "format = 1\nname = \"wz\"\n";
    const std::vector<HintCase> cases = {
        {"colour source, channel = luma",
         head + "\n[[displacement]]\nname = \"water\"\nsource = \"../my maps/wz_water.png\"\nchannel = \"luma\"\n"
                "tile_size = 32.0\n",
         "source = \"../my maps/wz_water.png\"\n", 1, {"--channel luma", "\"my maps/wz_water.png\""}},
        {"normal map in alpha, another filter and threshold",
         "format = 1\nname = \"wz\"\nthreshold = 8.0\n\n[[displacement]]\nname = \"water\"\nsource = "
         "\"../my maps/waves.0000.png\"\ntile_size = 32.0\ntileable = false\n\n[normals]\nsource = "
         "\"../my maps/ripple.png\"\nchannel = \"a\"\nfilter = \"box\"\ntile_size = 8.0\nheight = 0.05\n",
         "source = \"../my maps/ripple.png\"\n", 1, {"--channel a", "--filter box", "--threshold 8"}},
        {"a sequence whose frames do not tile",
         head + "\n[defaults]\nfilter = \"triangle\"\n\n[[displacement]]\nname = \"waves\"\nsource = "
                "\"../my maps/waves.png\"\ntile_size = 32.0\n",
         "source = \"../my maps/waves.png\"\n", 2, {"--filter triangle", "waves_tiled.000"}},
    };
    for (const HintCase& c : cases) expectSuggestionsWork(dir, c);
}

}  // namespace
}  // namespace heightpack::test
