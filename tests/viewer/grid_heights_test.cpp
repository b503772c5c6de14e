// heightpack's CPU water sampler against the heights the viewer's GPU computes: the combine pass writes
// the height and horizontal shift of every grid vertex (--grid-heights), the test puts each vertex where
// the shader put it and asks loadMaterialSampler's sampler for the same point, time and footprint; with
// choppy maps, it also asks for the height over the vertex's displaced position, which the sampler finds
// by inverting the shift.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>
#include <nlohmann/json.hpp>

#include "heightpack/bake/material_sampler.hpp"
#include "heightpack/bake/pack_job.hpp"
#include "heightpack/core/sea/cascades.hpp"
#include "support/test_support.hpp"
#include "viewer_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

struct Agreement {
    double worst = 0.0;       // metres: heights at the vertex's undisplaced position
    double worstShift = 0.0;  // metres: either component of the horizontal shift
    double worstOver = 0.0;   // metres: the height over the displaced position (sampleSurfaceHeight)
    double range = 0.0;       // of the GPU's heights compared, metres
    double largestShift = 0.0;
    double largestOfOne = 0.0;  // metres: the largest |height| of the layer compareWithSampler was given alone
    int compared = 0, unconverged = 0, mostSteps = 0;
};

// Vertices within maxRadius of the camera, placed as viewer/shaders/combine.frag places them (in float).
// choppy: also compare the shift, and invert it at the vertex's displaced position. one: a layer of the
// sampler whose own share of the heights to measure (largestOfOne).
Agreement compareWithSampler(const GridHeights& g, const WaterSampler& sampler, float maxRadius, bool choppy = false,
                             const SampledLayer* one = nullptr) {
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
            const size_t at = size_t(ring) * g.segments + segment;
            const float gpu = g.heights[at];
            const float cpu = sampleWaterHeight(sampler, x, y, g.time, d * g.pixelAngle);
            a.worst = std::max(a.worst, double(std::abs(gpu - cpu)));
            lo = std::min(lo, gpu), hi = std::max(hi, gpu);
            ++a.compared;
            if (one)
                a.largestOfOne = std::max(a.largestOfOne, double(std::abs(sampleLayerHeight(sampler, *one, x, y, g.time, d * g.pixelAngle))));
            if (!choppy) continue;
            const std::array<float, 2> shift = sampleWaterShift(sampler, x, y, g.time, d * g.pixelAngle);
            a.worstShift = std::max({a.worstShift, double(std::abs(shift[0] - g.shiftX[at])), double(std::abs(shift[1] - g.shiftY[at]))});
            a.largestShift = std::max(a.largestShift, double(std::hypot(g.shiftX[at], g.shiftY[at])));
            // The vertex lands at xy + shift (grid.vert's vWorld, in float): the surface over that point is
            // the vertex's own height.
            const SurfaceHeight over = sampleSurfaceHeight(sampler, x + g.shiftX[at], y + g.shiftY[at], g.time, d * g.pixelAngle);
            a.unconverged += over.converged ? 0 : 1;
            a.mostSteps = std::max(a.mostSteps, over.iterations);
            a.worstOver = std::max(a.worstOver, double(std::abs(over.height - gpu)));
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
                                  "--camera", "13,-7,25,30,-20", "--lookup", lookup, "--size", "160x120"});
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

TEST(GridHeights, ChoppySeasShiftAndStandWhereTheViewerDrawsThem) {
    // A synthesised choppy sea (two frames, blended) summed with a painted map that is not choppy.
    ScratchDir dir;
    ASSERT_EQ(runProcess({HEIGHTPACK_EXE, "synth", "--wind", "9m/s", "--tile-size", "48m", "--size", "64", "--frames", "2",
                          "--loop", "8s", "--shift", "-q", "-o", dir.file("sea.exr")})
                  .code,
              0);
    std::ofstream(dir.file("m.toml")) << "format = 1\nname = \"m\"\n"
                                      << "[[displacement]]\nname = \"sea\"\nsource = \"" << dir.file("sea.exr") << "\"\n"
                                      << "tile_size = 48.0\nscroll = [0.010, 0.004]\namplitude = 1.0\nchoppiness = 0.8\n"
                                      << "[[displacement]]\nname = \"choppy\"\nsource = \"" << HEIGHTPACK_SOURCE_DIR
                                      << "/examples/maps/choppy.png\"\n"
                                      << "tile_size = 10.0\nscroll = [-0.006, 0.011]\namplitude = 0.3\n";
    const ProcessResult built = runProcess({HEIGHTPACK_EXE, "build", dir.file("m.toml"), "-q", "-o", dir.file("m")});
    ASSERT_EQ(built.code, 0) << built.err;
    auto sampler = loadMaterialSampler(dir.file("m/material.json"));
    ASSERT_TRUE(sampler) << sampler.error().path << ": " << sampler.error().what;
    ASSERT_EQ(sampler->layers.size(), 2u);
    ASSERT_EQ(sampler->layers[0].shiftX.size(), 2u) << "the sea's Dx, Dy, every frame";
    EXPECT_FLOAT_EQ(sampler->layers[0].choppiness, 0.8f);
    EXPECT_FALSE(sampler->layers[1].choppy());

    // A small window: the grid is the same, each pixel's shading (the slow part on llvmpipe) is not wanted.
    const ViewRun run = view({dir.file("m/material.json"), "--grid-heights", dir.file("grid.exr"), "--time", "3.3",
                              "--camera", "13,-7,25,30,-20", "--size", "160x120"});
    ASSERT_EQ(run.code, 0) << run.err;
    const GridHeights grid = readGridHeights(dir.file("grid.exr"));
    ASSERT_EQ(grid.segments, 256);
    const Agreement a = compareWithSampler(grid, *sampler, 100.0f, true);
    EXPECT_GT(a.compared, 10000);
    EXPECT_GT(a.largestShift, 0.2) << "the sea should move the vertices sideways";
    EXPECT_LT(a.worst, 1e-5) << "heights at the undisplaced vertex";
    EXPECT_LT(a.worstShift, 1e-5) << "horizontal shifts";
    EXPECT_EQ(a.unconverged, 0) << "this sea does not fold: every displaced vertex has one point under it";
    EXPECT_LT(a.worstOver, 1e-5) << "heights over the displaced vertex";
    // Each stage of the program reads at most the 16 samplers OpenGL 3.3 promises it, in the gather lookup
    // of a 4.x context as in the others (TheFourthTileShadesThePictureWithinTheSamplerLimits asks the context).
    const ViewRun shot = view({dir.file("m/material.json"), "--screenshot", dir.file("shot.png"), "--size", "160x120", "--time",
                               "3.3", "--lookup", "gather-trilinear", "--json"});
    ASSERT_EQ(shot.code, 0) << shot.err;
    const auto json = nlohmann::json::parse(shot.out);
    EXPECT_GT(json["samplers"]["vertex"].get<int>(), 0);
    EXPECT_LE(json["samplers"]["vertex"].get<int>(), 16);
    EXPECT_LE(json["samplers"]["fragment"].get<int>(), 16);
    std::printf("choppy: %d vertices, heights over %.3f m, shifts up to %.3f m; worst difference: height %.3g m, "
                "shift %.3g m, height over the displaced vertex %.3g m (at most %d fixed-point steps); samplers: vertex %d, "
                "fragment %d\n",
                a.compared, a.range, a.largestShift, a.worst, a.worstShift, a.worstOver, a.mostSteps,
                json["samplers"]["vertex"].get<int>(), json["samplers"]["fragment"].get<int>());
}

// synth --cascades' seas of three and four tiles (issue 25): every tile displaces the grid at its own tile
// size and scroll, and the CPU sampler sums the same tiles, so the two agree as for two maps, in every
// lookup (each binds its own form of the heights to a map's one sampler). The smallest tile's own share
// of the heights is far above that agreement: a viewer that dropped it would fail.
TEST(GridHeights, EveryCascadeOfAThreeOrFourTileSeaDisplacesTheGrid) {
    for (const int cascades : {3, 4}) {
        SCOPED_TRACE(std::to_string(cascades) + " cascades");
        ScratchDir dir;
        std::ofstream(dir.file("m.toml")) << "format = 1\nname = \"m\"\n[[displacement]]\nname = \"sea\"\n"
                                          << "tile_size = 48.0\nscroll = [0.010, 0.004]\nchoppiness = 0.8\n"
                                          << "[displacement.synth]\nspectrum = \"pierson-moskowitz\"\nwind = 9.0\nsize = 64\n"
                                          << "seed = 5\nshift = true\ncascades = " << cascades << "\n";
        const ProcessResult built = runProcess({HEIGHTPACK_EXE, "build", dir.file("m.toml"), "-q", "-o", dir.file("m")});
        ASSERT_EQ(built.code, 0) << built.err;
        auto sampler = loadMaterialSampler(dir.file("m/material.json"));
        ASSERT_TRUE(sampler) << sampler.error().path << ": " << sampler.error().what;
        ASSERT_EQ(sampler->layers.size(), size_t(cascades));
        const std::vector<CascadeBand> bands = cascadeBands(48.0, 64, cascades, 5);
        for (int c = 0; c < cascades; ++c) {
            EXPECT_FLOAT_EQ(sampler->layers[c].tileSize, float(bands[c].tileSize)) << "cascade " << c;
            EXPECT_TRUE(sampler->layers[c].choppy()) << "cascade " << c;
        }

        // Every lookup: each binds its own form of the heights (packed, plain, gather atlas) to a map's sampler.
        for (const std::string lookup : {"trilinear", "bilinear", "reference-trilinear", "reference-bilinear", "gather-trilinear"}) {
            SCOPED_TRACE(lookup);
            const bool bilinear = lookup.ends_with("bilinear");
            sampler->filter = bilinear ? LevelFilter::Bilinear : LevelFilter::Trilinear;
            // Two metres up with a 480-row picture: a pixel near the camera spans a few millimetres, so the
            // trilinear lookup reads the smallest tile's fine levels there (its coarse ones are flat: the
            // mip filter removes its short waves, as it should). The pixel angle follows the rows alone and
            // every vertex is sampled whatever the frustum, so 64 columns give the bytes 640 do, for a tenth
            // of the frame's fragments (3.1 s of Mesa's CPU a run at 640x480, 0.9 s at 64x480).
            const ViewRun run = view({dir.file("m/material.json"), "--grid-heights", dir.file("grid.exr"), "--time", "3.3",
                                      "--camera", "13,-7,2,30,-20", "--lookup", lookup, "--size", "64x480"});
            ASSERT_EQ(run.code, 0) << run.err;
            EXPECT_EQ(run.err.find("instead"), std::string::npos) << "the lookup asked for drew: " << run.err;
            const GridHeights grid = readGridHeights(dir.file("grid.exr"));
            ASSERT_EQ(grid.segments, 256);
            // The smallest tile's own share, at the vertices compared: what the GPU would lack without it.
            const SampledLayer& smallest = sampler->layers.back();
            const Agreement a = compareWithSampler(grid, *sampler, 100.0f, true, &smallest);
            EXPECT_GT(a.compared, 10000);
            EXPECT_LT(a.worst, 1e-5) << "heights at the undisplaced vertex";
            EXPECT_LT(a.worstShift, 1e-5) << "horizontal shifts";
            EXPECT_GT(a.largestOfOne, 100 * 1e-5) << "the smallest tile should move the water more than the agreement";
            std::printf("%d cascades, %s: %d vertices, heights over %.3f m, smallest tile (%.2f m) up to %.4f m; worst "
                        "difference: height %.3g m, shift %.3g m\n",
                        cascades, lookup.c_str(), a.compared, a.range, smallest.tileSize, a.largestOfOne, a.worst, a.worstShift);
        }
    }
}

// The picture of a four-tile sea changes when its smallest tile is flattened (--amplitude 1,1,1,0), so
// the fragment stage, which finds the normals from the heights and shifts, reads the fourth map too; and
// every stage of the program reads no more samplers than the context allows (the viewer asks GL) nor than
// the 16 GL 3.3 promises: the count is the program's, the same whichever lookup draws.
TEST(GridHeights, TheFourthTileShadesThePictureWithinTheSamplerLimits) {
    ScratchDir dir;
    std::ofstream(dir.file("m.toml")) << "format = 1\nname = \"m\"\n[[displacement]]\nname = \"sea\"\ntile_size = 48.0\n"
                                      << "[displacement.synth]\nspectrum = \"pierson-moskowitz\"\nwind = 9.0\nsize = 64\n"
                                      << "seed = 5\nshift = true\ncascades = 4\n";
    const ProcessResult built = runProcess({HEIGHTPACK_EXE, "build", dir.file("m.toml"), "-q", "-o", dir.file("m")});
    ASSERT_EQ(built.code, 0) << built.err;
    // Close to the water: from farther, the fourth tile's metre-long ripples fall into coarse levels.
    const std::vector<std::string> shot = {dir.file("m/material.json"), "--size", "240x160", "--time", "3.3", "--camera",
                                           "13,-7,3,30,-35"};
    auto flattened = shot;
    flattened.insert(flattened.end(), {"--amplitude", "1,1,1,0"});
    const Difference d = compare(screenshot(dir, "all.png", shot), screenshot(dir, "three.png", flattened), 2);
    EXPECT_GT(d.fractionOver, 0.05) << "the fourth tile's waves shade the water";
    // The gather lookup of a 4.x context bound the most textures while each lookup had samplers of its own.
    auto args = shot;
    args.insert(args.end(), {"--lookup", "gather-trilinear", "--json", "--screenshot", dir.file("json.png")});
    const ViewRun run = view(args);
    ASSERT_EQ(run.code, 0) << run.err;
    const auto samplers = nlohmann::json::parse(run.out)["samplers"];
    EXPECT_GT(samplers["vertex"].get<int>(), 0);
    EXPECT_LE(samplers["vertex"].get<int>(), 16);
    EXPECT_LE(samplers["fragment"].get<int>(), 16);
    EXPECT_LE(samplers["vertex"].get<int>(), samplers["vertexLimit"].get<int>());
    EXPECT_LE(samplers["fragment"].get<int>(), samplers["fragmentLimit"].get<int>());
    std::printf("flattening the fourth tile changes %.1f%% of the channel values by more than 2; samplers %s\n",
                100 * d.fractionOver, samplers.dump().c_str());
}

namespace {

// The heights of a float image's channel 0 (read here with OpenImageIO) as the sampler's one layer, packed
// as pack and the viewer pack them, at the given tile size and metres per stored unit; the viewer's
// default scroll for a first map (0.010, 0.004 tiles a second).
WaterSampler seaSampler(const std::string& path, float tileSize, float amplitude) {
    auto in = OIIO::ImageInput::open(path);
    EXPECT_TRUE(in) << path;
    WaterSampler sampler;
    if (!in) return sampler;
    Image heights(in->spec().width, in->spec().height, 1);
    EXPECT_TRUE(in->read_image(0, 0, 0, 1, OIIO::TypeDesc::FLOAT, heights.pixels.data()));
    auto maps = packHeights(std::move(heights), SourceInfo{}, PackOptions{});
    EXPECT_TRUE(maps);
    SampledLayer layer;
    layer.frames = {maps->packed};
    layer.tileSize = tileSize;
    layer.amplitude = amplitude;
    layer.scroll = {0.010f, 0.004f};
    layer.midStored = midStoredOf(layer.frames);
    sampler.layers.push_back(std::move(layer));
    return sampler;
}

}  // namespace

// Issue 35, item 1: a map that records its tile size and the metres of its heights is drawn at them, not
// at the viewer's defaults (64 m, 1.5 m per unit): a synthesised 256 m sea opened as synth wrote it (float
// metres, or 16-bit with heightScale giving metres back), and packed into KTX2 and DDS. The GPU's grid
// heights equal the CPU sampler's at 256 m and the sea's own metres, and are far from them at the
// defaults; --tile-size and --amplitude still override what the file says.
TEST(ViewerUnits, AMapIsDrawnAtTheTileSizeAndMetresItRecordsUnlessAFlagSaysOtherwise) {
    ScratchDir dir;
    const std::vector<std::string> synth = {HEIGHTPACK_EXE, "synth", "--spectrum", "jonswap", "--wind", "12m/s",
                                            "--tile-size", "256m", "--size", "128", "-q", "-o"};
    for (const std::string out : {"sea.exr", "sea.png"}) {
        auto args = synth;
        args.push_back(dir.file(out));
        ASSERT_EQ(runProcess(args).code, 0) << out;
    }
    for (const std::string out : {"sea.ktx2", "sea.dds"})
        ASSERT_EQ(runProcess({HEIGHTPACK_EXE, "pack", dir.file("sea.exr"), "-q", "-o", dir.file(out)}).code, 0) << out;
    // The 16-bit sea's values are heightOffset + heightScale * value metres: heightScale metres a unit.
    auto png = OIIO::ImageInput::open(dir.file("sea.png"));
    ASSERT_TRUE(png);
    const float pngMetres = std::stof(png->spec().get_string_attribute("heightpack:heightScale"));
    png.reset();
    ASSERT_GT(pngMetres, 1.0f);

    auto gridOf = [&](const std::string& map, const std::vector<std::string>& flags) {
        std::vector<std::string> args = {dir.file(map), "--grid-heights", dir.file("grid.exr"), "--time", "2",
                                         "--camera", "13,-7,25,30,-20", "--size", "160x120"};
        args.insert(args.end(), flags.begin(), flags.end());
        const ViewRun run = view(args);
        EXPECT_EQ(run.code, 0) << run.err;
        return readGridHeights(dir.file("grid.exr"));
    };
    for (const std::string map : {"sea.exr", "sea.ktx2", "sea.dds", "sea.png"}) {
        SCOPED_TRACE(map);
        // The packed files hold the float sea's values; the 16-bit sea its own.
        const bool integer = map == "sea.png";
        const std::string values = dir.file(integer ? "sea.png" : "sea.exr");
        const float metres = integer ? pngMetres : 1.0f;
        const GridHeights grid = gridOf(map, {});
        const Agreement own = compareWithSampler(grid, seaSampler(values, 256.0f, metres), 100.0f);
        const Agreement defaults = compareWithSampler(grid, seaSampler(values, 64.0f, 1.5f), 100.0f);
        EXPECT_GT(own.compared, 10000);
        EXPECT_GT(own.range, 1.0) << "a 12 m/s sea moves the vertices by metres";
        EXPECT_LT(own.worst, 1e-5) << "drawn at 256 m and " << metres << " m a unit";
        EXPECT_GT(defaults.worst, 0.5) << "the viewer's defaults would draw another sea";
        std::printf("%s: heights over %.3f m; against 256 m, %.4g m a unit: worst %.3g m; against 64 m, 1.5 m a unit: "
                    "worst %.3g m\n",
                    map.c_str(), own.range, metres, own.worst, defaults.worst);
    }
    // Flags win over the file.
    const GridHeights flagged = gridOf("sea.ktx2", {"--tile-size", "100", "--amplitude", "2"});
    const Agreement asked = compareWithSampler(flagged, seaSampler(dir.file("sea.exr"), 100.0f, 2.0f), 100.0f);
    EXPECT_GT(asked.compared, 10000);
    EXPECT_LT(asked.worst, 2 * 1e-5) << "--tile-size 100 --amplitude 2: float rounding of the stored units, in metres twice";
    EXPECT_GT(asked.range, 2.0);
}
