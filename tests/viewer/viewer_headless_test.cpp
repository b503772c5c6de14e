// heightpack-view with no X server: --screenshot and --bench through EGL (Mesa's surfaceless platform
// here, llvmpipe), the same pictures as under Xvfb.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>

#include "viewer_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

TEST(ViewerHeadless, DrawsWhatXvfbDrawsWithoutAnyDisplay) {
    ScratchDir dir;
    const std::vector<std::string> common = {kExamples + "swell.png", kExamples + "choppy.png", "--size", "160x90",
                                             "--time", "4", "--camera", "3,-2,6,35,-12", "--lookup", "gather", "--grid",
                                             "128", "--segments", "128"};
    const Picture windowed = screenshot(dir, "xvfb.png", common);
    // DISPLAY unset: headless without being asked.
    auto automatic = common;
    automatic.insert(automatic.end(), {"--screenshot", dir.file("auto.png"), "--json"});
    const ViewRun run = viewWithoutDisplay(automatic);
    ASSERT_EQ(run.code, 0) << run.err;
    EXPECT_EQ(run.err, "");  // gather drew: EGL gave a 4.x context
    const auto j = nlohmann::json::parse(run.out);
    EXPECT_EQ(j["context"], "EGL surfaceless");
    EXPECT_EQ(j["lookup"], "gather-trilinear");
    EXPECT_GT(j["gpuBytes"]["gather"].get<long long>(), 0);
    // --headless under an X server: EGL all the same.
    auto asked = common;
    asked.push_back("--headless");
    const Picture headless = screenshot(dir, "headless.png", asked);
    // The same driver draws the same frame into the same kind of framebuffer object.
    for (const Picture& p : {readPicture(dir.file("auto.png")), headless}) {
        const Difference d = compare(windowed, p, 1);
        EXPECT_LE(d.max, 2);
        EXPECT_LT(d.fractionOver, 0.001);
    }
    // And it is a picture of the sea, not a cleared framebuffer.
    const auto [lo, hi] = std::minmax_element(headless.rgb.begin(), headless.rgb.end());
    EXPECT_GT(*hi - *lo, 60);
}
