// heightpack's CPU water sampler against the heights the viewer's GPU computes: the combine pass writes
// the height of every grid vertex (--grid-heights), the test puts each vertex where the shader put it
// and asks loadMaterialSampler's sampler for the same point, time and footprint.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "heightpack/build/material_sampler.hpp"
#include "support/test_support.hpp"
#include "viewer_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

struct GridHeights {
    int segments = 0, rings = 0;
    std::vector<float> heights;  // ring-major
    float cameraX = 0, cameraY = 0, cameraZ = 0, pixelAngle = 0, innerRadius = 0, ringScale = 0, waterLevel = 0, time = 0;
};

GridHeights readGridHeights(const std::string& path) {
    GridHeights g;
    auto in = OIIO::ImageInput::open(path);
    EXPECT_TRUE(in) << path;
    if (!in) return g;
    const OIIO::ImageSpec& spec = in->spec();
    g.segments = spec.width;
    g.rings = spec.height;
    g.heights.resize(size_t(g.segments) * g.rings);
    EXPECT_TRUE(in->read_image(0, 0, 0, 1, OIIO::TypeDesc::FLOAT, g.heights.data()));
    auto number = [&](const char* name) { return spec.get_float_attribute(std::string("heightpack:") + name, NAN); };
    g.cameraX = number("cameraX"), g.cameraY = number("cameraY"), g.cameraZ = number("cameraZ");
    g.pixelAngle = number("pixelAngle"), g.innerRadius = number("gridInnerRadius"), g.ringScale = number("gridRingScale");
    g.waterLevel = number("waterLevel"), g.time = number("time");
    return g;
}

struct Agreement {
    double worst = 0.0;      // metres
    double range = 0.0;      // of the GPU's heights compared, metres
    int compared = 0;
};

// Vertices within maxRadius of the camera, placed as viewer/shaders/combine.frag places them (in float).
Agreement compareWithSampler(const GridHeights& g, const WaterSampler& sampler, float maxRadius) {
    Agreement a;
    float lo = INFINITY, hi = -INFINITY;
    for (int ring = 0; ring < g.rings; ++ring) {
        const float radius = g.innerRadius + g.ringScale * std::pow(float(ring), 4.0f);
        if (radius > maxRadius) break;
        for (int segment = 0; segment < g.segments; ++segment) {
            const float angle = 6.28318530717958647692f * float(segment) / float(g.segments);
            const float x = g.cameraX + std::cos(angle) * radius, y = g.cameraY + std::sin(angle) * radius;
            const float dz = g.waterLevel - g.cameraZ;
            const float d = std::sqrt((x - g.cameraX) * (x - g.cameraX) + (y - g.cameraY) * (y - g.cameraY) + dz * dz);
            const float gpu = g.heights[size_t(ring) * g.segments + segment];
            const float cpu = sampleWaterHeight(sampler, x, y, g.time, d * g.pixelAngle);
            a.worst = std::max(a.worst, double(std::abs(gpu - cpu)));
            lo = std::min(lo, gpu), hi = std::max(hi, gpu);
            ++a.compared;
        }
    }
    a.range = hi - lo;
    return a;
}

}  // namespace

TEST(GridHeights, TheCpuSamplerGivesTheHeightsTheViewerDraws) {
    // A material of a synthesised, looping sequence (blended between frames) and a painted map.
    ScratchDir dir;
    ASSERT_EQ(runProcess({HEIGHTPACK_EXE, "synth", "--wind", "8m/s", "--tile-size", "64m", "--size", "64", "--frames", "4",
                          "--loop", "8s", "-q", "-o", dir.file("sea.exr")})
                  .code,
              0);
    std::ofstream(dir.file("m.toml")) << "format = 1\nname = \"m\"\n"
                                      << "[[displacement]]\nname = \"sea\"\nsource = \"" << dir.file("sea.exr") << "\"\n"
                                      << "tile_size = 64.0\nscroll = [0.010, 0.004]\namplitude = 1.0\n"
                                      << "[[displacement]]\nname = \"choppy\"\nsource = \"" << HEIGHTPACK_SOURCE_DIR
                                      << "/examples/maps/choppy.png\"\n"
                                      << "tile_size = 10.0\nscroll = [-0.006, 0.011]\namplitude = 0.3\n";
    const ProcessResult built = runProcess({HEIGHTPACK_EXE, "build", dir.file("m.toml"), "-q", "-o", dir.file("m")});
    ASSERT_EQ(built.code, 0) << built.err;
    auto sampler = loadMaterialSampler(dir.file("m/material.json"));
    ASSERT_TRUE(sampler) << sampler.error().path << ": " << sampler.error().what;
    ASSERT_EQ(sampler->layers.size(), 2u);
    ASSERT_EQ(sampler->layers[0].frames.size(), 4u);

    for (const char* lookup : {"trilinear", "bilinear"}) {
        sampler->filter = std::string(lookup) == "bilinear" ? LevelFilter::Bilinear : LevelFilter::Trilinear;
        // t = 3.3 s lies between frames 1 and 2 of the 8 s loop; the camera is off the origin and tilted.
        const ViewRun run = view({dir.file("m/material.json"), "--grid-heights", dir.file("grid.exr"), "--time", "3.3",
                                  "--camera", "13,-7,25,30,-20", "--lookup", lookup});
        ASSERT_EQ(run.code, 0) << run.err;
        const GridHeights grid = readGridHeights(dir.file("grid.exr"));
        ASSERT_EQ(grid.segments, 256);
        // Within 100 m of the camera. Farther out the vertex's own position differs by float rounding
        // (the GPU's sin and cos, texture coordinates of tens of tiles): the difference grows by about
        // 1e-7 m per metre of radius, 1.2e-5 m at 300 m here, whatever the sampler does.
        const Agreement a = compareWithSampler(grid, *sampler, 100.0f);
        EXPECT_GT(a.compared, 10000) << lookup;
        EXPECT_GT(a.range, 0.5) << lookup << ": the seas should move the vertices";
        EXPECT_LT(a.worst, 1e-5) << lookup << ": worst of " << a.compared << " vertices";
        std::printf("%s: %d vertices, heights over %.3f m, worst difference %.3g m\n", lookup, a.compared, a.range, a.worst);
    }
}
