// Start-up: a command that touches only PNG, EXR, KTX2 and DDS maps no OpenImageIO library, and one that
// reads a TIFF or a JPEG loads it (the format module). What a process maps is the loader's own report
// (LD_DEBUG=files: every object it unmaps at exit, however it was loaded), not heightpack's word.
#include <gtest/gtest.h>

#include <unistd.h>

#include <string>
#include <vector>

#include "support/heightpack_process.hpp"
#include "support/test_support.hpp"

extern char** environ;

namespace heightpack::test {
namespace {

std::vector<std::string> environmentWith(const std::vector<std::string>& extra) {
    std::vector<std::string> env;
    for (char** e = environ; *e; ++e) env.emplace_back(*e);
    env.insert(env.end(), extra.begin(), extra.end());
    return env;
}

// heightpack run with the loader reporting every object it loads and unloads on stderr.
ProcessResult traced(const std::vector<std::string>& args, const std::vector<std::string>& extraEnv = {}) {
    std::vector<std::string> argv = {HEIGHTPACK_EXE};
    argv.insert(argv.end(), args.begin(), args.end());
    std::vector<std::string> env = {"LD_DEBUG=files"};
    env.insert(env.end(), extraEnv.begin(), extraEnv.end());
    return runProcess(argv, environmentWith(env));
}

bool mapped(const ProcessResult& run, const std::string& library) {
    return run.err.find("calling fini: ") != std::string::npos && run.err.find(library) != std::string::npos;
}

// The lines a run printed on stderr that are not the loader's (which start with a pid and a tab).
std::string ownErrors(const std::string& err) {
    std::string own;
    size_t at = 0;
    while (at < err.size()) {
        const size_t end = std::min(err.find('\n', at), err.size());
        const std::string line = err.substr(at, end - at);
        const size_t tab = line.find('\t');
        const bool loader = tab != std::string::npos && line.find_first_not_of(" 0123456789:") == tab;
        if (!loader && !line.empty()) own += line + "\n";
        at = end + 1;
    }
    return own;
}

TEST(Startup, PngExrKtx2AndDdsMapNoOpenImageIO) {
    ScratchDir dir;
    const std::string png = dir.file("map.png");
    writeImage(png, makeImage(64, 64, smoothWave), OIIO::TypeDesc::UINT16);
    writeImage(dir.file("written-by-openimageio.exr"), makeImage(64, 64, smoothWave), OIIO::TypeDesc::HALF);
    const std::vector<std::vector<std::string>> commands = {
        {"--version"},
        {"pack", png, "-o", dir.file("map.ktx2")},
        {"pack", png, "-o", dir.file("map.exr")},
        {"pack", png, "-o", dir.file("map.dds"), "--pixel-type", "half"},
        {"info", dir.file("map.exr")},
        {"info", dir.file("map.ktx2"), "--json"},
        {"info", dir.file("map.dds")},
        {"info", png},
        {"info", dir.file("written-by-openimageio.exr")},
        {"synth", "-o", dir.file("sea.exr"), "--size", "32", "--wind", "8", "--tile-size", "16m", "--foam"},
        {"info", dir.file("sea.exr")},
        {"pack", dir.file("sea.exr"), "-o", dir.file("sea.ktx2"), "--shift", "--foam"},
    };
    for (const auto& args : commands) {
        const ProcessResult run = traced(args);
        std::string line;
        for (const auto& a : args) line += a + " ";
        EXPECT_EQ(run.code, 0) << line << ownErrors(run.err);
        // The report is there (the program's own libraries are in it), and names no OpenImageIO library.
        EXPECT_TRUE(mapped(run, "libOpenEXR")) << line;
        EXPECT_FALSE(mapped(run, "libOpenImageIO")) << line;
        EXPECT_FALSE(mapped(run, "libheightpack_oiio")) << line;
    }
}

TEST(Startup, TiffAndJpegLoadTheModule) {
    ScratchDir dir;
    for (const char* name : {"map.tif", "map.jpg", "map.tga"}) {
        const std::string path = dir.file(name);
        writeImage(path, makeImage(32, 32, smoothWave), OIIO::TypeDesc::UINT8);
        const ProcessResult run = traced({"info", path});
        EXPECT_EQ(run.code, 0) << name << ownErrors(run.err);
        EXPECT_TRUE(mapped(run, "libheightpack_oiio")) << name;
        EXPECT_TRUE(mapped(run, "libOpenImageIO")) << name;
        const ProcessResult packed = traced({"pack", path, "-o", dir.file(std::string(name) + ".ktx2")});
        EXPECT_EQ(packed.code, 0) << name << ownErrors(packed.err);
    }
    const ProcessResult version = heightpackRun({"--version", "--verbose"});
    EXPECT_EQ(version.code, 0) << version.err;
    EXPECT_NE(version.out.find("libheightpack_oiio.so"), std::string::npos) << version.out;
    EXPECT_NE(version.out.find("OpenImageIO 2."), std::string::npos) << version.out;
}

TEST(Startup, MissingOrBrokenModuleIsOneLineNeverACrash) {
    ScratchDir dir;
    const std::string tif = dir.file("map.tif"), exr = dir.file("map.exr");
    writeImage(tif, makeImage(32, 32, smoothWave), OIIO::TypeDesc::UINT8);
    ASSERT_EQ(heightpackRun({"pack", tif, "-o", exr}).code, 0);
    const std::string broken = dir.file("broken.so");
    writeBytes(broken, std::vector<unsigned char>(100, 0x7f));
    for (const std::string& module : {dir.file("nothing-here.so"), broken}) {
        const std::vector<std::string> env = {"HEIGHTPACK_FORMAT_MODULE=" + module};
        const ProcessResult tiff = runProcess({HEIGHTPACK_EXE, "info", tif}, environmentWith(env));
        EXPECT_EQ(tiff.code, 70) << tiff.err;
        expectOneLineError(tiff, tif);
        EXPECT_NE(tiff.err.find("HEIGHTPACK_FORMAT_MODULE"), std::string::npos) << tiff.err;
        const ProcessResult packed = runProcess({HEIGHTPACK_EXE, "pack", tif, "-o", dir.file("out.exr")}, environmentWith(env));
        EXPECT_EQ(packed.code, 70) << packed.err;
        expectOneLineError(packed, tif);
        EXPECT_FALSE(std::filesystem::exists(dir.file("out.exr")));
        // An EXR needs no module.
        const ProcessResult fine = runProcess({HEIGHTPACK_EXE, "info", exr}, environmentWith(env));
        EXPECT_EQ(fine.code, 0) << fine.err;
        const ProcessResult version = runProcess({HEIGHTPACK_EXE, "--version", "--verbose"}, environmentWith(env));
        EXPECT_EQ(version.code, 70) << version.err;
    }
}

}  // namespace
}  // namespace heightpack::test
