// The build state file: what it writes reads back the same; anything damaged reads as no state at all
// (so everything is rebuilt), never as an error or a half state. And the file hashes it records.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "heightpack/bake/build/build_state.hpp"

#include "support/test_support.hpp"

namespace heightpack {
namespace {

BuildState sampleState() {
    BuildState s;
    s["swell.exr"] = {"k1", "h1", "c1"};
    s["sub/choppy.0001.exr"] = {"k2", "h2", ""};
    s["name with spaces \"and quotes\".exr"] = {"k3", "h3", "c3"};
    return s;
}

TEST(BuildState, WriteThenReadGivesTheSameState) {
    const BuildState state = sampleState();
    EXPECT_EQ(parseBuildState(buildStateText(state)), state);
    EXPECT_TRUE(parseBuildState(buildStateText(BuildState{})).empty());
    test::ScratchDir dir;
    std::ofstream(dir.file("state.json"), std::ios::binary) << buildStateText(state);
    EXPECT_EQ(readBuildState(dir.file("state.json")), state);
    EXPECT_TRUE(readBuildState(dir.file("missing.json")).empty());
}

TEST(BuildState, TheTextIsJsonWithItsFormatAndEndsWithANewline) {
    const std::string text = buildStateText(sampleState());
    EXPECT_EQ(text.front(), '{');
    EXPECT_EQ(text.back(), '\n');
    EXPECT_NE(text.find("\"format\": " + std::to_string(kBuildStateFormat)), std::string::npos);
    EXPECT_EQ(buildStateText(sampleState()), text) << "the same state always gives the same bytes";
}

TEST(BuildState, ADamagedFileIsNoStateAtAll) {
    const std::string good = buildStateText(sampleState());
    // Every truncation: either the whole state or nothing (a JSON prefix is never valid JSON here).
    for (size_t n = 0; n < good.size() - 1; ++n) {
        const BuildState s = parseBuildState(good.substr(0, n));
        EXPECT_TRUE(s.empty()) << "truncated at " << n;
    }
    const char* damaged[] = {
        "",
        "not json",
        "[]",
        "{\"format\": 1}",
        "{\"format\": 2, \"outputs\": {}}",
        "{\"format\": \"1\", \"outputs\": {}}",
        "{\"format\": 1.5, \"outputs\": {}}",
        "{\"format\": 1, \"outputs\": []}",
        "{\"format\": 1, \"outputs\": {\"a.exr\": 1}}",
        "{\"format\": 1, \"outputs\": {\"a.exr\": {\"key\": \"k\", \"hash\": \"h\"}}}",
        "{\"format\": 1, \"outputs\": {\"a.exr\": {\"key\": 1, \"hash\": \"h\", \"checked\": \"\"}}}",
        // One good entry beside a bad one: nothing, not half.
        "{\"format\": 1, \"outputs\": {\"a.exr\": {\"key\": \"k\", \"hash\": \"h\", \"checked\": \"\"}, \"b.exr\": {}}}",
    };
    for (const char* text : damaged) EXPECT_TRUE(parseBuildState(text).empty()) << text;
}

TEST(BuildState, HashesDependOnEveryByteAndOnNothingElse) {
    test::ScratchDir dir;
    std::string bytes(3 << 20, 'x');  // over the 1 MiB read buffer, so the streaming is exercised
    for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>((i * 2654435761u) >> 13);
    std::ofstream(dir.file("a.bin"), std::ios::binary) << bytes;
    auto a = hashFile(dir.file("a.bin"));
    ASSERT_TRUE(a);
    EXPECT_EQ(*a, hashText(bytes)) << "a file hashes as its bytes do";
    EXPECT_EQ(a->size(), 32u);
    bytes[bytes.size() - 1] ^= 1;
    std::ofstream(dir.file("b.bin"), std::ios::binary) << bytes;
    auto b = hashFile(dir.file("b.bin"));
    ASSERT_TRUE(b);
    EXPECT_NE(*a, *b) << "the last byte counts";
    auto missing = hashFile(dir.file("missing.bin"));
    ASSERT_FALSE(missing);
    EXPECT_EQ(missing.error().kind, ErrorKind::BadInput);
    EXPECT_FALSE(hashFile(dir.path().string())) << "a folder is not hashed";
}

}  // namespace
}  // namespace heightpack
