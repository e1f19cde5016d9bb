// SPDX-License-Identifier: MIT
// The free surface of a drum bed and the axial displacement by depth
// (analysis/depth_mobility), and reading grains back from a snapshot file.
#include <gtest/gtest.h>

#include <cmath>

#include "io/drum_output.hpp"
#include "test_support.hpp"
#include "tumble/analysis/depth_mobility.hpp"
#include "tumble/core/constants.hpp"
#include "tumble/core/error.hpp"

namespace tumble::analysis {
namespace {

constexpr double R_drum = 0.04;   // m, inner radius
constexpr double r_grain = 0.001; // m: small grains so that the lattice bed is nearly a continuum
constexpr double reach = R_drum - r_grain;

// Grains on a square lattice (spacing 2 r_grain) filling the part of the
// reachable circle below the chord `up . x = level`, at z = 0.
GrainFrame segment_bed(const Vec3& up, double level) {
    GrainFrame f;
    const double h = 2.0 * r_grain;
    for (double x = -reach; x <= reach; x += h)
        for (double y = -reach; y <= reach; y += h) {
            const Vec3 p{x, y, 0.0};
            if (norm2(p) > reach * reach || dot(p, up) > level) continue;
            f.id.push_back(static_cast<std::int64_t>(f.id.size()));
            f.position.push_back(p);
            f.radius.push_back(r_grain);
            f.tag.push_back(0);
        }
    return f;
}

// The lattice approximates the segment to within about one lattice spacing
// at its rim, so the fitted chord may be off by a fraction of a spacing:
// the tolerance is half a spacing, 1 mm (2.5 % of the radius).
constexpr double lattice_tolerance = r_grain;

TEST(FreeSurface, HalfFullBedHasItsSurfaceThroughTheAxis) {
    const FreeSurface s = find_free_surface(segment_bed({0.0, 1.0, 0.0}, 0.0), R_drum);
    EXPECT_NEAR(s.level, 0.0, lattice_tolerance);
    EXPECT_NEAR(s.up.y, 1.0, 1e-6);  // symmetric bed: the normal is exactly vertical up to rounding
    EXPECT_NEAR(s.mean_diameter, 2.0 * r_grain, 1e-15);
    EXPECT_NEAR(s.depth({0.0, -0.01, 0.0}), 0.01, lattice_tolerance);
}

TEST(FreeSurface, InclinedShallowBedGivesItsChordAndNormal) {
    // A bed filling a quarter of the circle's area, its surface inclined by
    // 35 degrees (a typical dynamic angle of repose).
    const double tilt = 35.0 * pi / 180.0;
    const Vec3 up{-std::sin(tilt), std::cos(tilt), 0.0};
    const double chord = 0.404 * reach;  // segment of central angle 2 acos(0.404), 25 % of the circle
    const FreeSurface s = find_free_surface(segment_bed(up, -chord), R_drum);
    EXPECT_NEAR(s.level, -chord, lattice_tolerance);
    EXPECT_NEAR(std::atan2(-s.up.x, s.up.y) * 180.0 / pi, 35.0, 0.5);  // lattice asymmetry: well under a degree
}

TEST(DepthMobility, AttributesDisplacementsToTheStartingLayer) {
    GrainFrame before = segment_bed({0.0, 1.0, 0.0}, 0.0);
    before.revolutions = 1.0;
    const FreeSurface s = find_free_surface(before, R_drum);
    GrainFrame after = before;
    after.revolutions = 1.5;
    // Grains less than one diameter below the surface move +-a along the
    // axis; all others stay: <dz^2>/dN = a^2 / 0.5 in layer 0, zero below.
    const double a = 0.003;
    std::size_t top = 0;
    for (std::size_t k = 0; k < before.id.size(); ++k)
        if (s.depth(before.position[k]) < s.mean_diameter) {
            after.position[k].z += (top % 2 ? a : -a);
            ++top;
        }
    ASSERT_GT(top, 10u);
    DepthMobility m(1, 4);
    m.add(before, after, R_drum);
    EXPECT_EQ(m.intervals(), 1u);
    EXPECT_EQ(m.samples(0, 0), top);
    EXPECT_DOUBLE_EQ(m.msd_per_revolution(0, 0), a * a / 0.5);
    EXPECT_DOUBLE_EQ(m.msd_per_revolution(0, 1), 0.0);
    EXPECT_DOUBLE_EQ(m.share(0, 0), 1.0);
    EXPECT_DOUBLE_EQ(m.share(0, 2), 0.0);
    EXPECT_NEAR(m.occupancy(0, 0) + m.occupancy(0, 1) + m.occupancy(0, 2) + m.occupancy(0, 3), 1.0, 1e-12);
    EXPECT_NEAR(m.occupancy(0, 0), static_cast<double>(top) / static_cast<double>(before.id.size()), 1e-12);
    // The deepest layer holds everything below 3 diameters (the bed is 19 deep).
    EXPECT_GT(m.occupancy(0, 3), 0.5);
}

// A window of three frames: the bed's grains stay put in the cross-section,
// and one grain in the top layer goes 2 mm along the axis over the window
// (1 revolution): it counts at its mean depth, in layer 0, with
// dz^2 / dN = 4e-6 m^2/rev; nothing else moves.
TEST(DepthMobility, WindowAttributesTheDisplacementToTheMeanDepth) {
    GrainFrame first = segment_bed({0.0, 1.0, 0.0}, 0.0);
    const FreeSurface s = find_free_surface(first, R_drum);
    std::size_t mover = 0;
    while (s.depth(first.position[mover]) >= 0.9 * s.mean_diameter) ++mover;
    ASSERT_LT(mover, first.id.size());
    std::vector<GrainFrame> window(3, first);
    for (std::size_t f = 0; f < 3; ++f) {
        window[f].revolutions = 2.0 + 0.5 * static_cast<double>(f);
        window[f].position[mover].z += 1e-3 * static_cast<double>(f);
    }
    DepthMobility m(1, 4);
    m.add_window(window.data(), window.size(), R_drum);
    EXPECT_EQ(m.intervals(), 1u);
    EXPECT_DOUBLE_EQ(m.share(0, 0), 1.0);
    EXPECT_NEAR(m.msd_per_revolution(0, 0) * static_cast<double>(m.samples(0, 0)), 4e-6, 1e-15);
}

// On a periodic axis (period 0.12 m) a grain that goes from z = 0.059 m
// to -0.059 m has moved +2 mm through the period's end, not -118 mm.
TEST(DepthMobility, TakesTheNearestImageOnAPeriodicAxis) {
    GrainFrame before = segment_bed({0.0, 1.0, 0.0}, 0.0);
    before.revolutions = 1.0;
    for (Vec3& x : before.position) x.z = 0.059;
    GrainFrame after = before;
    after.revolutions = 2.0;
    for (Vec3& x : after.position) x.z = -0.059;
    DepthMobility m(1, 4, 0.12);
    m.add(before, after, R_drum);
    for (int layer = 0; layer < 4; ++layer) EXPECT_NEAR(m.msd_per_revolution(0, layer), 4e-6, 1e-15);
}

TEST(DepthMobility, RefusesMismatchedFramesAndBackwardTime) {
    GrainFrame before = segment_bed({0.0, 1.0, 0.0}, 0.0);
    GrainFrame after = before;
    after.revolutions = before.revolutions;  // no time between them
    DepthMobility m(1, 4);
    EXPECT_THROW(m.add(before, after, R_drum), Error);
    after.revolutions = 1.0;
    after.id.pop_back();
    after.position.pop_back();
    EXPECT_THROW(m.add(before, after, R_drum), Error);
    EXPECT_THROW(DepthMobility(0, 3), Error);
}

class SnapshotGrains : public test_support::ScratchTest {};

TEST_F(SnapshotGrains, ReadsFreeGrainsSortedByIdWithTheirRevolution) {
    const auto file = write("snapshots/000003.csv",
                            "# time = 2.5 s, step = 250000\n"
                            "id,x,y,z,vx,vy,vz,wx,wy,wz,radius,material,tag,kinematic\n"
                            "7,0.01,-0.02,0.03,0,0,0,0,0,0,0.0024,material-2,1,0\n"
                            "2,0.0,0.04,0.0,0,0,0,0,0,0,0.003,material-3,0,1\n"
                            "3,-0.01,-0.03,-0.02,0,0,0,0,0,0,0.0036,material-1,0,0\n");
    // Rotation started at t = 0.5 s at pi rad/s: N = pi (2.5 - 0.5) / 2 pi = 1.
    const GrainFrame f = io::read_snapshot_grains(file, 0.5, pi);
    EXPECT_DOUBLE_EQ(f.revolutions, 1.0);
    ASSERT_EQ(f.id.size(), 2u);  // the wall particle (kinematic) is left out
    EXPECT_EQ(f.id[0], 3);
    EXPECT_EQ(f.id[1], 7);
    EXPECT_DOUBLE_EQ(f.position[1].z, 0.03);
    EXPECT_DOUBLE_EQ(f.radius[0], 0.0036);
    EXPECT_EQ(f.tag[1], 1);
    const auto bad = write("snapshots/000004.csv", "id,x\n1,2\n");
    EXPECT_THROW(io::read_snapshot_grains(bad, 0.0, 1.0), Error);
}

}  // namespace
}  // namespace tumble::analysis
