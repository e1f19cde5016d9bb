// SPDX-License-Identifier: MIT
// tumble render: the sphere rasteriser on a known scene, the drum's cut-away
// views, the caption (clock and legend) and the palette shared with the
// figures, PNG files read back, the smooth walls (outline, cut-away, the
// ring of a smooth drum in its frames) and the command on a tiny drum run
// (frames, and the movie checked by ffprobe where ffmpeg is installed).
#include <gtest/gtest.h>

#include <fmt/format.h>

#include "test_support.hpp"

#include <algorithm>
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

// A square of two triangles, half-width a (m), in the plane z = z0.
tumble::WallSurface square(double a, double z0) {
    tumble::WallSurface s;
    s.vertices = {{-a, -a, z0}, {a, -a, z0}, {a, a, z0}, {-a, a, z0}};
    s.triangles = {{0, 1, 2}, {0, 2, 3}};
    return s;
}

// A smooth wall's outline: the edges that bound it and its creases, not the
// diagonal between two triangles of one plane.
TEST(Scene, WallOutlineIsTheBoundaryAndTheCreases) {
    EXPECT_EQ(wall_outline(square(1.0, 0.0)).size(), 4u);
    tumble::WallSurface folded = square(1.0, 0.0);
    folded.vertices[3].z = 1.0;  // the second triangle folded up 45 degrees along the diagonal
    EXPECT_EQ(wall_outline(folded).size(), 5u);
    folded.vertices[3].z = 0.1;  // 6 degrees: no crease
    EXPECT_EQ(wall_outline(folded).size(), 4u);
}

// The edge of the cut: the plane x = 0.25 crosses both triangles of the
// square, the line x = 0.25 across it in two segments.
TEST(Scene, WallCutIsWhereThePlaneCrossesTheTriangles) {
    const auto lines = wall_cut(square(1.0, 0.0), {0.25, 0.0, 0.0}, {1.0, 0.0, 0.0});
    ASSERT_EQ(lines.size(), 2u);
    double length = 0.0;
    for (const auto& [a, b] : lines) {
        EXPECT_NEAR(a.x, 0.25, 1e-15);
        EXPECT_NEAR(b.x, 0.25, 1e-15);
        length += std::abs(b.y - a.y);
    }
    EXPECT_NEAR(length, 2.0, 1e-12);
    EXPECT_TRUE(wall_cut(square(1.0, 0.0), {2.0, 0.0, 0.0}, {1.0, 0.0, 0.0}).empty());
}

// A grain between two smooth square walls, one behind it and one in front
// in the axial view (seen from +z): the near one is cut away, the far one is
// seen through, behind the grain, with its outline.
TEST(Scene, SmoothWallsInFrontOfTheWallCentreAreCutAway) {
    tumble::io::SnapshotParticles snapshot;
    snapshot.material_names = {"a"};
    snapshot.position = {{0.0, 0.0, 0.0}};
    snapshot.radius = {0.005};
    snapshot.material = {0};
    snapshot.tag = {0};
    snapshot.kinematic = {0};
    const tumble::WallSurface far = square(0.02, -0.02), near = square(0.02, 0.02);
    snapshot.walls = far;
    for (const auto& t : near.triangles) snapshot.walls.triangles.push_back({t[0] + 4, t[1] + 4, t[2] + 4});
    snapshot.walls.vertices.insert(snapshot.walls.vertices.end(), near.vertices.begin(), near.vertices.end());
    Scene scene;
    scene.add(snapshot);
    EXPECT_NEAR(scene.particles.hi.x, 0.02, 1e-15) << "the frame holds the walls";
    EXPECT_NEAR(scene.wall.centre().z, 0.0, 1e-15) << "the cut passes midway between them";
    ASSERT_EQ(scene_legend(scene, ColourBy::material).back().name, "wall");

    const FrameStyle style{200, ColourBy::material, drum_orientation(), {}};
    const Image image = render_frame(snapshot, scene, style, "");
    const View view = frame_layout(scene, style).first;
    auto at = [&](double x, double y) {
        const Vec3 p = view.project({x, y, 0.0});
        return std::pair{static_cast<int>(p.x), static_cast<int>(p.y)};
    };
    // The grain, in front of the far wall and not behind the near one: as
    // it is drawn without the walls.
    tumble::io::SnapshotParticles bare = snapshot;
    bare.walls = {};
    const Image grain_only = render_frame(bare, scene, style, "");
    const auto [grain_x, grain_y] = at(0.0, 0.0);
    EXPECT_EQ(image.at(grain_x, grain_y), grain_only.at(grain_x, grain_y));
    EXPECT_EQ(image.at(grain_x + 20, grain_y), grain_only.at(grain_x + 20, grain_y)) << "the grain's rim";
    // Beside the grain, the far wall (facing the viewer: its colour unshaded)
    // laid over the background: once, the near wall cut away.
    auto over = [](std::uint8_t under, std::uint8_t wall) {
        return static_cast<std::uint8_t>(std::lround((1.0 - wall_opacity) * under + wall_opacity * wall));
    };
    const Rgb seen_through{over(background_colour.r, wall_fill_colour.r), over(background_colour.g, wall_fill_colour.g),
                           over(background_colour.b, wall_fill_colour.b)};
    for (auto [x, y] : {at(0.012, 0.003), at(0.011, 0.011) /* on the diagonal: no line */})
        EXPECT_EQ(image.at(x, y), seen_through) << "pixel " << x << ", " << y;
    // The far wall's four edges, 0.04 m each, in the line colour.
    int outline = 0;
    for (int y = view.y0; y < view.y0 + view.height; ++y)
        for (int x = view.x0; x < view.x0 + view.width; ++x) outline += image.at(x, y) == wall_line_colour;
    EXPECT_GE(outline, 4 * 0.9 * 0.04 * view.pixels_per_metre);
    EXPECT_LE(outline, 4 * 1.1 * 0.04 * view.pixels_per_metre);
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

// A smooth drum's walls in its frames: in the axial view, its mantle's rims
// (projected onto one circle, the drum's inner radius R) are a ring of the
// walls' line colour, hidden only where grains lie in front of it, as at the
// bottom; a drum of wall particles has none there.
TEST_F(RenderCommand, SmoothDrumIsARingInTheAxialView) {
    double radius = 0.0;  // m, the smooth drum's: its farthest wall point from the axis (z)
    for (const std::string walls : {"smooth", "particles"}) {
        const fs::path run = dir_ / walls;
        const auto drum = run_tumble("drum --walls " + walls +
                                     " --grains 100 --revolutions 0.05 --snapshots 40 -q --no-plot --out " +
                                     run.string());
        ASSERT_EQ(drum.exit_code, 0) << drum.output;
        const auto render = run_tumble("render " + run.string() + " --width 160 -j 2 -q --frames-only");
        ASSERT_EQ(render.exit_code, 0) << render.output;

        // The views as the command lays them out: around every snapshot's particles and walls.
        const std::vector<fs::path> snapshots = tumble::io::list_snapshot_csv(run);
        ASSERT_GE(snapshots.size(), 2u);
        Scene scene;
        for (const fs::path& csv : snapshots) {
            tumble::io::SnapshotParticles snapshot = tumble::io::read_snapshot_csv(csv);
            snapshot.walls = tumble::io::read_snapshot_walls(csv);
            if (walls == "smooth") {
                ASSERT_FALSE(snapshot.walls.triangles.empty()) << csv;
                for (const Vec3& v : snapshot.walls.vertices) radius = std::max(radius, std::hypot(v.x, v.y));
            } else {
                EXPECT_TRUE(snapshot.walls.triangles.empty()) << csv;
            }
            scene.add(snapshot);
        }
        const View view = frame_layout(scene, {160, ColourBy::material, drum_orientation(), {}}).first;
        const Vec3 axis = view.project({0.0, 0.0, 0.0});
        const double ring = radius * view.pixels_per_metre;  // pixels

        // The upper half of the ring, above the bed of 100 grains: in every
        // column within 0.9 R of the axis, a pixel of the line colour within
        // 1.5 pixels of the ring.
        const Image frame = tumble::io::read_png(run / "frames" / fmt::format("{:06d}.png", snapshots.size() - 1));
        int columns = 0, drawn = 0;
        for (int x = static_cast<int>(axis.x - 0.9 * ring); x <= static_cast<int>(axis.x + 0.9 * ring); ++x) {
            ++columns;
            bool line = false;
            for (int y = view.y0; y < static_cast<int>(axis.y); ++y)
                line = line || (std::abs(std::hypot(x + 0.5 - axis.x, y + 0.5 - axis.y) - ring) <= 1.5 &&
                                frame.at(x, y) == wall_line_colour);
            drawn += line;
        }
        ASSERT_GT(columns, 80) << "R = " << ring << " pixels";
        if (walls == "smooth")
            EXPECT_EQ(drawn, columns) << "the ring over the top of the drum";
        else
            EXPECT_EQ(drawn, 0);
    }
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
