// SPDX-License-Identifier: MIT
// The drum (setup/drum.hpp): where the wall spheres sit and how far apart,
// that no grain can pass through the wall (checked here by brute force,
// independently of the library's branch and bound), refusal of impossible
// drums, and the grains: inside their half, not overlapping, equal masses,
// tags, determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "tumble/core/constants.hpp"
#include "tumble/core/error.hpp"
#include "tumble/setup/drum.hpp"
#include "tumble/setup/paper_materials.hpp"

namespace tumble {
namespace {

constexpr double smallest_grain = 2.4e-3;  // material 2

// The message of the tumble::Error that f throws, or "" if none.
template <class F>
std::string error_of(F&& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

double grain_mass(double R) { return 4.0 / 3.0 * pi * 1000.0 * R * R * R; }

TEST(DrumWall, SpheresLieOnTheMantleCylinderOrTheCapPlanes) {
    const DrumGeometry g;
    const DrumWall wall = build_drum_wall(g, 2, 0, smallest_grain);
    EXPECT_EQ(wall.inner_radius, 0.04);
    EXPECT_EQ(wall.inner_length, 0.12);
    const double Rc = 0.043, Zc = 0.063;  // inner radius/half length + wall_radius
    ASSERT_EQ(wall.particles.size(), wall.mantle_particles + wall.cap_particles);
    for (std::size_t i = 0; i < wall.particles.size(); ++i) {
        const ParticleSpec& p = wall.particles[i];
        EXPECT_EQ(p.radius, g.wall_radius);
        EXPECT_EQ(p.material, 2);
        EXPECT_EQ(p.motion, 0);
        EXPECT_EQ(p.tag, -1);
        EXPECT_EQ(p.velocity, Vec3{});
        const double rho = std::hypot(p.position.x, p.position.y);
        // cos/sin of the ring angle are exact to an ulp: 1e-12 relative.
        if (i < wall.mantle_particles) {
            EXPECT_NEAR(rho, Rc, 1e-12 * Rc) << i;
            EXPECT_LE(std::abs(p.position.z), Zc * (1.0 + 1e-12)) << i;
        } else {
            EXPECT_NEAR(std::abs(p.position.z), Zc, 1e-12 * Zc) << i;
            // Cap rings stay one radial step (>= 0.8 x 2 wall_radius) inside the mantle.
            EXPECT_LT(rho, Rc - 0.8 * 2.0 * g.wall_radius) << i;
        }
    }
}

TEST(DrumWall, CountsMatchTheRingLayout) {
    const DrumWall wall = build_drum_wall({}, 2, 0, smallest_grain);
    // The paper: "about 1000" wall particles; the brief allows 1000-1400.
    EXPECT_GE(wall.particles.size(), 1000u);
    EXPECT_LE(wall.particles.size(), 1400u);
    // Mantle: 45 spheres per ring (2 pi 43 mm / 6 mm = 45.03 -> chord
    // 5.9985 mm), 22 rings 6 mm apart over 2 x 63 mm. Caps: 8 radial steps
    // of 5.375 mm (43/6 = 7.17 -> 8), rings of 6, 12, 17, 23, 29, 34, 40
    // spheres and one on the axis: 162 per cap.
    EXPECT_EQ(wall.mantle_rings, 22u);
    EXPECT_NEAR(wall.axial_step, 0.006, 1e-15);
    EXPECT_EQ(wall.mantle_particles, 22u * 45u);
    EXPECT_EQ(wall.cap_particles, 2u * 162u);
}

TEST(DrumWall, NeighboursTouchOrOverlapSlightly) {
    const DrumGeometry g;
    const DrumWall wall = build_drum_wall(g, 2, 0, smallest_grain);
    const double s = 2.0 * g.wall_radius;
    // Every wall sphere's nearest neighbour: at most s (no spacing wider than
    // touching, up to round-off 1e-12 relative); at least 0.89 s, the
    // closest pair being the axis sphere and the first cap ring at 5.375 mm.
    double closest = 1.0, farthest = 0.0;
    for (std::size_t i = 0; i < wall.particles.size(); ++i) {
        double nearest = 1.0;
        for (std::size_t j = 0; j < wall.particles.size(); ++j)
            if (j != i) nearest = std::min(nearest, norm(wall.particles[i].position - wall.particles[j].position));
        closest = std::min(closest, nearest);
        farthest = std::max(farthest, nearest);
    }
    EXPECT_LE(farthest, s * (1.0 + 1e-12));
    EXPECT_GE(closest, 0.89 * s);
    EXPECT_NEAR(closest, 0.043 / 8.0, 1e-12);
}

// Brute force, independent of the library: sample the closed surface S through
// the wall-sphere centres (the cylinder rho = Rc for |z| <= Zc and the discs
// |z| = Zc, rho <= Rc; it contains the seam circles) on a grid of spacing h,
// and at each sample find the nearest wall centre over all wall spheres. A
// grain escaping the drum must at some instant have its centre on S, and
// not overlap any wall sphere there. The distance to the nearest centre is
// 1-Lipschitz and every point of S is within h / sqrt(2) (unrolled on the
// mantle; a chord is never longer than the arc) of a sample (or of the
// projection onto the rim of a cap sample that lies outside it), so max over
// S <= sampled max + h / sqrt(2).
TEST(DrumWall, NoGrainCanPassThroughTheWallBruteForce) {
    const DrumGeometry g;
    const DrumWall wall = build_drum_wall(g, 2, 0, smallest_grain);
    const double Rc = 0.043, Zc = 0.063, h = 0.5e-3;
    std::vector<Vec3> centres;
    for (const ParticleSpec& p : wall.particles) centres.push_back(p.position);
    double sampled = 0.0;  // max over samples of the distance to the nearest centre
    double near_seam = 0.0;
    auto sample = [&](const Vec3& x) {
        double best2 = 1.0;
        for (const Vec3& c : centres) best2 = std::min(best2, norm2(x - c));
        const double f = std::sqrt(best2);
        sampled = std::max(sampled, f);
        if (Zc - std::abs(x.z) < 4.0 * g.wall_radius && Rc - std::hypot(x.x, x.y) < 4.0 * g.wall_radius)
            near_seam = std::max(near_seam, f);
    };
    const int nu = static_cast<int>(std::ceil(2.0 * pi * Rc / h)), nz = static_cast<int>(std::ceil(2.0 * Zc / h));
    const double du = 2.0 * pi * Rc / nu, dz = 2.0 * Zc / nz;
    ASSERT_LE(std::max(du, dz), h);
    for (int i = 0; i < nu; ++i)
        for (int k = 0; k < nz; ++k) {
            const double phi = (i + 0.5) * du / Rc;
            sample({Rc * std::cos(phi), Rc * std::sin(phi), -Zc + (k + 0.5) * dz});
        }
    const int nxy = static_cast<int>(std::ceil(2.0 * Rc / h));
    const double dxy = 2.0 * Rc / nxy;
    for (const double z : {-Zc, Zc})
        for (int i = 0; i < nxy; ++i)
            for (int j = 0; j < nxy; ++j) {
                double x = -Rc + (i + 0.5) * dxy, y = -Rc + (j + 0.5) * dxy;
                const double rho = std::hypot(x, y);
                if (rho > Rc) {
                    // The cell may still reach into the disc: sample the rim.
                    if (rho - dxy / std::sqrt(2.0) > Rc) continue;
                    x *= Rc / rho;
                    y *= Rc / rho;
                }
                sample({x, y, z});
            }
    const double resolution = h / std::sqrt(2.0);
    // A probe of the smallest grain centred anywhere on S overlaps a wall
    // sphere: nearest centre closer than wall_radius + grain radius.
    EXPECT_LT(sampled + resolution, g.wall_radius + smallest_grain);
    EXPECT_LT(wall.largest_gap, smallest_grain);
    // The library's largest_gap is an upper bound (it may not be below a
    // sampled value; 1e-12 m for round-off) and tight to the sampling
    // resolution plus its own tolerance.
    EXPECT_GE(wall.largest_gap, sampled - g.wall_radius - 1e-12);
    EXPECT_LE(wall.largest_gap, sampled - g.wall_radius + resolution + largest_gap_tolerance);
    // The seam is no weaker than the rest: the widest holes are between cap
    // rings (a 5.375 mm x 6 mm cell: half diagonal 4.03 mm -> 1.03 mm gap);
    // near the seam, within the same resolution.
    EXPECT_LE(near_seam - g.wall_radius, wall.largest_gap);
    EXPECT_NEAR(wall.largest_gap, 1.01e-3, 0.05e-3);
}

TEST(DrumWall, RefusesAWallThatLetsTheSmallestGrainThrough) {
    // The widest hole lets a 1.01 mm sphere through: a 1 mm grain would leak.
    const std::string why = error_of([] { build_drum_wall({}, 2, 0, 1.0e-3); });
    EXPECT_NE(why.find("pass between the wall spheres"), std::string::npos) << why;
    EXPECT_NE(why.find("smallest_grain_radius"), std::string::npos) << why;
}

TEST(DrumWall, RefusesImpossibleParametersNamingThem) {
    const auto geometry = [](double length, double diameter, double wall_radius) {
        DrumGeometry g;
        g.length = length;
        g.diameter = diameter;
        g.wall_radius = wall_radius;
        return g;
    };
    auto expect_named = [](const DrumGeometry& g, const std::string& name, std::int32_t motion = 0,
                           double grain = smallest_grain) {
        const std::string why = error_of([&] { build_drum_wall(g, 2, motion, grain); });
        EXPECT_NE(why.find(name), std::string::npos) << "expected '" << name << "' in: '" << why << "'";
    };
    expect_named(geometry(0.0, 0.08, 3e-3), "length");
    expect_named(geometry(-0.12, 0.08, 3e-3), "length");
    expect_named(geometry(NAN, 0.08, 3e-3), "length");
    expect_named(geometry(0.12, 0.0, 3e-3), "diameter");
    expect_named(geometry(0.12, INFINITY, 3e-3), "diameter");
    expect_named(geometry(0.12, 0.08, 0.0), "wall_radius");
    expect_named(geometry(0.12, 0.017, 3e-3), "diameter");  // < 6 wall radii
    expect_named({}, "motion", -1);
    expect_named({}, "smallest_grain_radius", 0, 0.0);
}

void expect_inside_and_apart(const std::vector<ParticleSpec>& grains, double z_lo, double z_hi,
                             const std::vector<ParticleSpec>& others) {
    const DrumGeometry g;
    for (std::size_t a = 0; a < grains.size(); ++a) {
        const ParticleSpec& p = grains[a];
        // Whole sphere inside the inner surface (radius 40 mm, |z| <= 60 mm)
        // and its z range; strict geometry, round-off 1e-15 m.
        EXPECT_LE(std::hypot(p.position.x, p.position.y) + p.radius, 0.5 * g.diameter + 1e-15) << a;
        EXPECT_LE(std::abs(p.position.z) + p.radius, 0.5 * g.length + 1e-15) << a;
        EXPECT_GE(p.position.z - p.radius, z_lo - 1e-15) << a;
        EXPECT_LE(p.position.z + p.radius, z_hi + 1e-15) << a;
        EXPECT_EQ(p.motion, free_motion);
        // No overlap (distance >= sum of radii, no slack).
        for (std::size_t b = a + 1; b < grains.size(); ++b)
            EXPECT_GE(norm(p.position - grains[b].position), p.radius + grains[b].radius) << a << " " << b;
        for (const ParticleSpec& q : others) EXPECT_GE(norm(p.position - q.position), p.radius + q.radius) << a;
    }
}

TEST(DrumFill, PlacesExactCountsInsideTheHalfWithoutOverlap) {
    const DrumGeometry g;
    const DrumWall wall = build_drum_wall(g, 2, 0, smallest_grain);
    const auto left = fill_drum_region(g, -0.06, 0.0, 229, 3.6e-3, 0, 0, 7, wall.particles);
    ASSERT_EQ(left.size(), 229u);
    for (const ParticleSpec& p : left) {
        EXPECT_EQ(p.material, 0);
        EXPECT_EQ(p.tag, 0);
        EXPECT_EQ(p.radius, 3.6e-3);
    }
    expect_inside_and_apart(left, -0.06, 0.0, wall.particles);
    std::vector<ParticleSpec> existing = wall.particles;
    existing.insert(existing.end(), left.begin(), left.end());
    // A region overlapping the left grains' half: the new ones avoid them.
    const auto middle = fill_drum_region(g, -0.02, 0.06, 300, 2.4e-3, 1, 1, 8, existing);
    ASSERT_EQ(middle.size(), 300u);
    expect_inside_and_apart(middle, -0.02, 0.06, existing);
}

TEST(DrumFill, DenseFillBeyondRandomSequentialPlacementStillSeparatesGrains) {
    // 600 material-1 grains in one half: 39 % of its volume, past where
    // random sequential placement stalls; the rest are pushed apart.
    const auto grains = fill_drum_region({}, 0.0, 0.06, 600, 3.6e-3, 0, 1, 3, {});
    ASSERT_EQ(grains.size(), 600u);
    expect_inside_and_apart(grains, 0.0, 0.06, {});
}

TEST(DrumFill, RefusesARegionTooFullOrTooSmall) {
    const std::string full = error_of([] { fill_drum_region({}, 0.0, 0.06, 1000, 3.6e-3, 0, 0, 1, {}); });
    EXPECT_NE(full.find("too full"), std::string::npos) << full;
    const std::string thin = error_of([] { fill_drum_region({}, 0.0, 0.005, 1, 3.6e-3, 0, 0, 1, {}); });
    EXPECT_NE(thin.find("does not fit"), std::string::npos) << thin;
    const std::string order = error_of([] { fill_drum_region({}, 0.01, 0.0, 1, 3.6e-3, 0, 0, 1, {}); });
    EXPECT_NE(order.find("z_lo < z_hi"), std::string::npos) << order;
}

TEST(DrumFill, EqualMassCountBalancesTheMasses) {
    const double m1 = grain_mass(3.6e-3), m2 = grain_mass(2.4e-3);
    for (std::size_t total : {2u, 10u, 999u, 1000u, 1001u, 4375u}) {
        const std::size_t n1 = equal_mass_count(total, m1, m2);
        // The nearer whole number: the masses differ by at most (m1 + m2)/2.
        EXPECT_LE(std::abs(n1 * m1 - (total - n1) * m2), 0.5 * (m1 + m2) * (1.0 + 1e-12)) << total;
    }
    EXPECT_EQ(equal_mass_count(4375, m1, m2), 1000u);  // 1000 x 3.375 = 3375 exactly
}

TEST(DrumScenario, TwoComponentHasEqualMassesInTheirHalves) {
    const DrumSetup d = build_drum_scenario({}, "two-component", 1000, 5);
    const Scenario& s = d.scenario;
    EXPECT_EQ(d.grains_left, 229u);  // 1000 / 4.375 = 228.6
    EXPECT_EQ(d.grains_right, 771u);
    ASSERT_EQ(s.particles.size(), 1000u + d.wall.particles.size());
    ASSERT_EQ(s.materials.size(), 3u);
    EXPECT_EQ(s.materials[0].radius, 3.6e-3);
    EXPECT_EQ(s.materials[1].radius, 2.4e-3);
    EXPECT_EQ(s.gravity, (Vec3{0.0, -9.81, 0.0}));
    ASSERT_EQ(s.motions.size(), 1u);
    EXPECT_EQ(s.motions[0].axis_point, Vec3{});
    EXPECT_EQ(s.motions[0].axis_direction, (Vec3{0.0, 0.0, 1.0}));
    EXPECT_EQ(s.motions[0].angular_velocity, 0.0);
    EXPECT_EQ(s.time_step.dt, 0.0);
    EXPECT_NEAR(s.time_step.reference_speed, std::sqrt(5.0 * 9.81 * 0.04), 1e-12);
    EXPECT_TRUE(scenario_problem(s).empty()) << scenario_problem(s);

    double mass[2] = {0.0, 0.0};
    std::vector<ParticleSpec> grains;
    for (std::size_t i = 0; i < s.particles.size(); ++i) {
        const ParticleSpec& p = s.particles[i];
        for (int k = 0; k < 3; ++k) {
            EXPECT_GE(p.position[k], s.domain.lo[k]);
            EXPECT_LT(p.position[k], s.domain.hi[k]);
        }
        if (i >= 1000) {
            EXPECT_EQ(p.motion, 0);  // the wall follows the drum's motion
            continue;
        }
        grains.push_back(p);
        ASSERT_TRUE(p.tag == 0 || p.tag == 1);
        EXPECT_EQ(p.material, p.tag);  // material-1 left, material-2 right
        EXPECT_EQ(p.position.z < 0.0, p.tag == 0);
        mass[p.tag] += grain_mass(p.radius);
    }
    // Equal masses within one grain of material 1 (equal_mass_count's bound
    // is (m1 + m2)/2 < m1).
    EXPECT_LE(std::abs(mass[0] - mass[1]), grain_mass(3.6e-3));
    EXPECT_NEAR(d.solid_fraction, 2.0 * 229 * grain_mass(3.6e-3) / 1000.0 / (pi * 0.04 * 0.04 * 0.12), 0.002);
    expect_inside_and_apart(grains, -0.06, 0.06, d.wall.particles);
}

TEST(DrumScenario, SelfModeTagsGrainsByTheirStartingHalf) {
    const DrumSetup d = build_drum_scenario({}, "self", 1000, 2);
    EXPECT_EQ(d.grains_left, 500u);
    EXPECT_EQ(d.grains_right, 500u);
    std::size_t per_tag[2] = {0, 0};
    for (std::size_t i = 0; i < 1000; ++i) {
        const ParticleSpec& p = d.scenario.particles[i];
        ASSERT_TRUE(p.tag == 0 || p.tag == 1);
        EXPECT_EQ(p.material, 0);
        EXPECT_EQ(p.position.z < 0.0, p.tag == 0);
        ++per_tag[p.tag];
    }
    EXPECT_EQ(per_tag[0], 500u);
    EXPECT_EQ(per_tag[1], 500u);
    EXPECT_EQ(d.scenario.particles[1000].motion, 0);
}

TEST(DrumScenario, SameSeedSameDrumOtherSeedOtherGrains) {
    const DrumSetup a = build_drum_scenario({}, "two-component", 400, 11);
    const DrumSetup b = build_drum_scenario({}, "two-component", 400, 11);
    const DrumSetup c = build_drum_scenario({}, "two-component", 400, 12);
    ASSERT_EQ(a.scenario.particles.size(), b.scenario.particles.size());
    std::size_t moved = 0;
    for (std::size_t i = 0; i < a.scenario.particles.size(); ++i) {
        EXPECT_EQ(a.scenario.particles[i].position, b.scenario.particles[i].position) << i;
        if (!(a.scenario.particles[i].position == c.scenario.particles[i].position)) ++moved;
    }
    EXPECT_EQ(moved, 400u);  // every grain differs, no wall sphere does
}

TEST(DrumScenario, RefusesAnUnknownModeOrTooFewGrains) {
    const std::string mode = error_of([] { build_drum_scenario({}, "three-component", 1000, 1); });
    EXPECT_NE(mode.find("three-component"), std::string::npos) << mode;
    const std::string few = error_of([] { build_drum_scenario({}, "self", 1, 1); });
    EXPECT_NE(few.find("grains"), std::string::npos) << few;
}

}  // namespace
}  // namespace tumble
