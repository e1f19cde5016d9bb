// SPDX-License-Identifier: MIT
// tumble render: the sphere rasteriser on a known scene, the drum's cut-away
// views, the caption (clock and legend) and the palette shared with the
// figures, PNG files read back, and the command on a tiny drum run (frames,
// and the movie checked by ffprobe where ffmpeg is installed).
#include <gtest/gtest.h>

#include "test_support.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "io/png.hpp"
#include "io/render/raster.hpp"
#include "io/render/scene.hpp"
#include "io/render/text.hpp"
#include "io/snapshots.hpp"
#include "tumble/core/error.hpp"

namespace fs = std::filesystem;

namespace {

using namespace tumble::io::render;
using tumble::Vec3;
using tumble::test_support::run_command;

constexpr Rgb red{255, 0, 0}, blue{0, 0, 255}, black{0, 0, 0};

// A 101 x 61 pixel view of the x-y plane seen from +z, 10 pixels per metre,
// centred on the origin: the world point (x, y) with 10x, 10y whole numbers
// falls on the centre of pixel (50 + 10x, 30 - 10y).
View test_view() {
    View view;
    view.pixels_per_metre = 10.0;
    view.width = 101;
    view.height = 61;
    return view;
}

// Where a sphere's centre falls on a pixel centre, the surface there faces
// the viewer, where the shading is defined to give exactly the sphere's
// colour; 1 of 255 allows for rounding the shading factor to 8 bits.
void expect_colour(const Image& image, int x, int y, Rgb expected) {
    const Rgb c = image.at(x, y);
    EXPECT_NEAR(c.r, expected.r, 1) << "pixel " << x << ", " << y;
    EXPECT_NEAR(c.g, expected.g, 1) << "pixel " << x << ", " << y;
    EXPECT_NEAR(c.b, expected.b, 1) << "pixel " << x << ", " << y;
}

TEST(Raster, EachSphereShowsItsColourAtItsProjectedCentre) {
    Image image(101, 61, black);
    draw_spheres(image, test_view(), {{{-2.0, 0.0, 0.0}, 1.5, red}, {{2.0, 1.0, -3.0}, 1.0, blue}});
    expect_colour(image, 30, 30, red);   // (-2, 0)
    expect_colour(image, 70, 20, blue);  // (2, 1)
    // The red disc is 15 pixels in radius: pixel 44's centre is 14.5 pixels
    // from the sphere's centre, pixel 46's 15.5.
    EXPECT_GT(image.at(44, 30).r, 0);
    EXPECT_EQ(image.at(46, 30), black);
    for (auto [x, y] : {std::pair{0, 0}, std::pair{100, 60}, std::pair{50, 30}})
        EXPECT_EQ(image.at(x, y), black) << "background at " << x << ", " << y;
}

TEST(Raster, TheNearerSphereWinsWhereTheyOverlap) {
    // Both discs (radius 15 pixels, centres 10 pixels apart) cover pixel
    // (50, 30); the blue sphere is 1 m nearer to the viewer (+z), in either
    // order of drawing, then 1 m farther.
    const Sphere r{{-0.5, 0.0, 0.0}, 1.5, red};
    for (double blue_z : {1.0, -1.0}) {
        const Sphere b{{0.5, 0.0, blue_z}, 1.5, blue};
        for (const std::vector<Sphere>& order : {std::vector<Sphere>{r, b}, std::vector<Sphere>{b, r}}) {
            Image image(101, 61, black);
            draw_spheres(image, test_view(), order);
            const Rgb c = image.at(50, 30);
            // Shading scales a pure colour, so the losing colour is exactly absent.
            if (blue_z > 0)
                EXPECT_TRUE(c.r == 0 && c.b > 0) << "blue in front: " << int(c.r) << ", " << int(c.b);
            else
                EXPECT_TRUE(c.b == 0 && c.r > 0) << "red in front: " << int(c.r) << ", " << int(c.b);
        }
    }
}

TEST(Raster, SpheresOutsideTheViewDrawNothing) {
    Image image(101, 61, black);
    draw_spheres(image, test_view(), {{{40.0, 0.0, 0.0}, 1.0, red}, {{0.0, -40.0, 0.0}, 1.0, red}});
    for (int y = 0; y < 61; ++y)
        for (int x = 0; x < 101; ++x) ASSERT_EQ(image.at(x, y), black) << x << ", " << y;
}

// Two wall particles around a grain: in each view, the wall particle nearer
// to the viewer than the wall's centre (the origin) is cut away.
TEST(Scene, WallParticlesInFrontOfTheWallCentreAreCutAway) {
    tumble::io::SnapshotParticles snapshot;
    snapshot.material_names = {"material-1", "material-3"};
    auto add = [&](Vec3 x, int material, bool kinematic) {
        snapshot.position.push_back(x);
        snapshot.radius.push_back(0.005);
        snapshot.material.push_back(material);
        snapshot.tag.push_back(kinematic ? -1 : 0);
        snapshot.kinematic.push_back(kinematic);
    };
    add({0.0, 0.0, 0.0}, 0, false);       // grain
    add({-0.02, 0.0, 0.02}, 1, true);     // in front in both views (seen from +z and from -x)
    add({0.02, 0.0, -0.02}, 1, true);     // behind in both
    Scene scene;
    scene.add(snapshot);
    const FrameStyle style{200, ColourBy::material, drum_orientation(), {}};
    const Image image = render_frame(snapshot, scene, style, "");
    const FrameLayout layout = frame_layout(scene, style);
    for (const View& view : {layout.first, layout.second}) {
        auto pixel = [&](const Vec3& x) {
            const Vec3 p = view.project(x);
            return image.at(static_cast<int>(p.x), static_cast<int>(p.y));
        };
        EXPECT_EQ(pixel(snapshot.position[1]), background_colour) << "the near wall particle is cut away";
        EXPECT_GT(pixel(snapshot.position[2]).r, background_colour.r) << "the far wall particle is drawn";
        const Rgb grain = pixel(snapshot.position[0]);
        EXPECT_GT(grain.b, grain.r) << "the grain has the first grain colour (blue)";
    }
}

// The grains' colours are those of the figures: tools/palette.txt, in order.
TEST(Scene, GrainColoursAreThePaletteOfTheFigures) {
    std::ifstream in(fs::path(TUMBLE_SOURCE_DIR) / "tools" / "palette.txt");
    std::vector<Rgb> palette;
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || line[0] == '#') continue;
        const unsigned long v = std::stoul(line.substr(0, line.find(' ')), nullptr, 16);
        palette.push_back({static_cast<std::uint8_t>(v >> 16), static_cast<std::uint8_t>(v >> 8 & 0xff),
                           static_cast<std::uint8_t>(v & 0xff)});
    }
    ASSERT_GE(palette.size(), 2u);
    ASSERT_EQ(palette_size(), palette.size());
    for (std::size_t k = 0; k < 2 * palette.size(); ++k) EXPECT_EQ(grain_colour(k), palette[k % palette.size()]) << k;
}

// Under the views, the caption: the clock on its first line, and the legend
// (a square of each species' colour, then its name) on the second; a label
// in the corner of each view.
TEST(Scene, FrameHasTheClockAndTheLegend) {
    tumble::io::SnapshotParticles snapshot;
    snapshot.material_names = {"b", "a"};
    for (int k = 0; k < 2; ++k) {
        snapshot.position.push_back({k == 0 ? -0.01 : 0.01, 0.0, 0.0});
        snapshot.radius.push_back(0.005);
        snapshot.material.push_back(k);
        snapshot.tag.push_back(k);
        snapshot.kinematic.push_back(0);
    }
    Scene scene;
    scene.add(snapshot);
    FrameStyle style{320, ColourBy::material, drum_orientation(), {}};
    style.legend = scene_legend(scene, ColourBy::material);
    ASSERT_EQ(style.legend.size(), 2u);
    EXPECT_EQ(style.legend[0].name, "a");  // sorted names, palette order
    EXPECT_EQ(style.legend[0].colour, grain_colour(0));
    EXPECT_EQ(scene_legend(scene, ColourBy::tag, {"left"})[1].name, "tag 1");

    const FrameLayout layout = frame_layout(scene, style);
    EXPECT_EQ(layout.height % 2, 0);
    EXPECT_GE(layout.caption_top, layout.first.height);
    const Image with_clock = render_frame(snapshot, scene, style, "t = 0.5 s");
    const Image without = render_frame(snapshot, scene, style, "");
    ASSERT_EQ(with_clock.height(), layout.height);
    auto count = [&](const Image& image, int from, int to, Rgb colour) {
        int n = 0;
        for (int y = from; y < to; ++y)
            for (int x = 0; x < image.width(); ++x) n += image.at(x, y) == colour;
        return n;
    };
    const int line = text_height(layout.text_scale) + 4 * layout.text_scale;
    const int clock_rows = layout.caption_top + line, end = layout.height;
    EXPECT_GT(count(with_clock, layout.caption_top, clock_rows, text_colour), 0) << "the clock is written";
    EXPECT_EQ(count(without, layout.caption_top, clock_rows, text_colour), 0);
    EXPECT_GT(count(with_clock, clock_rows, end, text_colour), 0) << "the legend's names";
    EXPECT_GT(count(with_clock, 0, line, text_colour), 0) << "each view says where it is seen from";
    for (const LegendEntry& entry : style.legend)
        EXPECT_GE(count(with_clock, clock_rows, end, entry.colour),
                  text_height(layout.text_scale) * text_height(layout.text_scale))
            << "the legend's square of " << entry.name;
}

// A scenario's views have "up" against gravity; the drum's its own frame.
TEST(Scene, ViewsOfAScenarioHaveUpAgainstGravity) {
    const Orientation down_z = orientation_against({0.0, 0.0, -9.81});
    EXPECT_EQ(down_z.up.z, 1.0);
    EXPECT_EQ(down_z.right_first.x, 1.0);
    EXPECT_EQ(down_z.right_second.y, 1.0);
    const Orientation up_x = orientation_against({9.81, 0.0, 0.1});
    EXPECT_EQ(up_x.up.x, -1.0);
    EXPECT_EQ(orientation_against({0.0, 0.0, 0.0}).up.z, 1.0) << "no gravity: z up";
    EXPECT_EQ(drum_orientation().up.y, 1.0);
}

TEST(Text, GlyphsAreDrawnWhereAsked) {
    Image image(40, 12, black);
    draw_text(image, 2, 3, "T!", red, 1);
    EXPECT_EQ(text_width("T!", 1), 11);
    for (int x = 2; x < 7; ++x) EXPECT_EQ(image.at(x, 3), red) << "the bar of T, x = " << x;
    EXPECT_EQ(image.at(4, 9), red) << "the stem of T";
    EXPECT_EQ(image.at(2, 9), black);
    EXPECT_EQ(image.at(10, 9), red) << "the dot of !";
    EXPECT_EQ(image.at(10, 8), black);
    draw_text(image, 38, 10, "W", red, 2);  // mostly outside: clipped, no crash
}

class Png : public tumble::test_support::ScratchTest {};

TEST_F(Png, RoundTripKeepsSizeAndPixels) {
    Image image(7, 5, Rgb{10, 20, 30});
    image.set(0, 0, Rgb{255, 0, 0});
    image.set(6, 4, Rgb{0, 255, 1});
    image.set(3, 2, Rgb{128, 64, 200});
    const fs::path file = dir_ / "image.png";
    for (bool fast : {false, true}) {
        tumble::io::write_png(file, image, fast);
        const Image back = tumble::io::read_png(file);
        ASSERT_EQ(back.width(), 7);
        ASSERT_EQ(back.height(), 5);
        for (auto [x, y] : {std::pair{0, 0}, std::pair{6, 4}, std::pair{3, 2}, std::pair{1, 1}})
            EXPECT_EQ(back.at(x, y), image.at(x, y)) << x << ", " << y << (fast ? " (fast)" : "");
    }
}

TEST_F(Png, NotAPngIsAnErrorNamingTheFile) {
    const fs::path file = write("not.png", "hello");
    try {
        tumble::io::read_png(file);
        FAIL() << "no error";
    } catch (const tumble::Error& e) {
        EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
    }
}

class RenderCommand : public tumble::test_support::ScratchTest {
protected:
    tumble::test_support::CommandResult run_tumble(const std::string& arguments, const std::string& env = "") {
        return run_command(env + std::string(TUMBLE_BINARY) + " " + arguments);
    }
};

bool have(const std::string& program) { return run_command(program + " -version").exit_code == 0; }

TEST_F(RenderCommand, TinyDrumRunGivesAFramePerSnapshotAndTheMovie) {
    const fs::path run = dir_ / "run";
    const auto drum = run_tumble("drum --grains 150 --omega 8 --revolutions 0.25 --snapshots 12 --no-plot -q --out " +
                             run.string());
    ASSERT_EQ(drum.exit_code, 0) << drum.output;
    const std::size_t snapshots = tumble::io::list_snapshot_csv(run).size();
    ASSERT_GE(snapshots, 3u);

    const bool movie = have("ffmpeg") && have("ffprobe");
    const auto render = run_tumble("render " + run.string() + " --width 80 -j 2 -q" + (movie ? "" : " --frames-only"));
    ASSERT_EQ(render.exit_code, 0) << render.output;
    if (movie) {
        EXPECT_NE(render.output.find("warning: the movie lasts only"), std::string::npos)
            << "a few snapshots make a short movie, and the command says so: " << render.output;
    }
    std::size_t frames = 0;
    for (const auto& entry : fs::directory_iterator(run / "frames")) frames += entry.path().extension() == ".png";
    EXPECT_EQ(frames, snapshots);
    const Image first = tumble::io::read_png(run / "frames" / "000000.png");
    EXPECT_EQ(first.width(), 160);
    EXPECT_EQ(first.height() % 2, 0);
    if (!movie) GTEST_SKIP() << "ffmpeg or ffprobe not installed: frames only";

    const auto probe = run_command("ffprobe -v error -select_streams v:0 -count_frames -show_entries "
                                   "stream=width,height,nb_read_frames -of csv=p=0 " + (run / "run.mp4").string());
    ASSERT_EQ(probe.exit_code, 0) << probe.output;
    EXPECT_EQ(probe.output, "160," + std::to_string(first.height()) + "," + std::to_string(snapshots) + "\n");
}

TEST_F(RenderCommand, ErrorsNameThePathAndTheReason) {
    const auto missing = run_tumble("render " + (dir_ / "nowhere").string());
    EXPECT_NE(missing.exit_code, 0);
    EXPECT_NE(missing.output.find((dir_ / "nowhere").string() + ": no such run directory"), std::string::npos)
        << missing.output;

    const auto empty = run_tumble("render " + dir_.string());
    EXPECT_NE(empty.exit_code, 0);
    EXPECT_NE(empty.output.find((dir_ / "snapshots").string() + ": no particle snapshots"), std::string::npos)
        << empty.output;

    // A run of two grains (no drum): without ffmpeg on PATH the movie is
    // refused before any frame is drawn; --frames-only needs no ffmpeg.
    write("snapshots/000000.csv", "# time = 0 s, step = 0\nid,x,y,z,radius,material,tag,kinematic\n"
                                  "0,-0.01,0,0,0.005,a,0,0\n1,0.01,0,0,0.005,b,0,0\n");
    const auto no_ffmpeg = run_tumble("render " + dir_.string(), "PATH=/nonexistent ");
    EXPECT_NE(no_ffmpeg.exit_code, 0);
    EXPECT_NE(no_ffmpeg.output.find("install ffmpeg"), std::string::npos) << no_ffmpeg.output;
    EXPECT_FALSE(fs::exists(dir_ / "frames"));
    const auto frames_only = run_tumble("render " + dir_.string() + " --frames-only -q", "PATH=/nonexistent ");
    EXPECT_EQ(frames_only.exit_code, 0) << frames_only.output;
    EXPECT_TRUE(fs::exists(dir_ / "frames" / "000000.png"));
}

}  // namespace
