// SPDX-License-Identifier: MIT
// The drum's frame (tumble/analysis/flowing_layer.hpp) on a bed made to
// order, whose answers are known without coarse-graining: a simple cubic
// lattice of touching grains filling a drum's circle below a plane surface
// at a chosen angle and level, its layers parallel to the surface and its
// top grains touching it, the grains flowing along the surface with a
// velocity linear in depth that turns at a chosen depth.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "tumble/analysis/flowing_layer.hpp"
#include "tumble/core/error.hpp"

namespace {

using tumble::Vec3;
using namespace tumble::analysis;

constexpr double pi = 3.14159265358979323846;

// The bed: grains of diameter a at s = i a, d = a/2 + j a (j >= 0), z = k a
// (k = 0 .. 3) in the drum's coordinates of `truth`, inside the circle of
// radius `reach` about the axis; velocity u(d) = U (1 - d / delta) along t.
constexpr double a = 0.002, reach = 0.037, U = 0.3, delta = 5 * a;  // m, m, m/s, m
constexpr int layers_z = 4;

double u_of(double d) { return U * (1.0 - d / delta); }

GrainState bed(const DrumSurface& truth) {
    GrainState g;
    const double m = 2500.0 * pi / 6.0 * a * a * a;  // kg, rho_s = 2500 kg/m^3
    const Vec3 t = truth.along(), n = truth.normal();
    for (int k = 0; k < layers_z; ++k)
        for (int j = 0; j < 40; ++j)
            for (int i = -40; i <= 40; ++i) {
                const double s = i * a, d = 0.5 * a + j * a;
                const Vec3 r = s * t + (truth.level - d) * n + Vec3{0.0, 0.0, k * a};
                if (std::hypot(r.x, r.y) > reach) continue;
                g.position.push_back(r);
                g.velocity.push_back(u_of(d) * t);
                g.mass.push_back(m);
                g.radius.push_back(0.5 * a);
            }
    return g;
}

// Lucy's kernel in 1-D, c = 3w (its constant cancels in a ratio).
double lucy(double r, double w) {
    const double q = std::abs(r) / (3.0 * w);
    return q < 1.0 ? (1.0 + 3.0 * q) * std::pow(1.0 - q, 3) : 0.0;
}

TEST(FlowingLayer, FindsTheSurfaceAndTheLayerOfABedMadeToOrder) {
    DrumSurface truth;
    truth.angle = 35.0 * pi / 180.0;
    truth.level = -0.01;
    const GrainState g = bed(truth);
    ASSERT_GT(g.position.size(), 1000u);
    const double w = a;  // Lucy at w = a: a lattice looks uniform (docs/FIELDS.md, "Width")

    CgSettings cs;
    cs.kernel = CgKernel::lucy;
    cs.width = w;
    cs.grid.lo = {-0.04, -0.04, -0.5 * a};
    cs.grid.hi = {0.04, 0.04, (layers_z - 0.5) * a};
    cs.grid.cells = {80, 80, 1};
    cs.grid.averaged = {false, false, true};
    const Fields section = coarse_grain(cs, g.grains(), {});
    double far = 0.0;
    for (const Vec3& r : g.position) far = std::max(far, std::hypot(r.x, r.y));
    const DrumSurface found = find_drum_surface(section, far, 0.5);

    // The bed's solid fraction: pi/6 inside, where most of the grains'
    // volume lies; phi_ref is the median of phi weighted by phi. Measured
    // 0.5227 (0.17 % below); tolerance 1 % (the nodes' phi varies by 0.2 % about pi/6 in a
    // lattice at w = a: docs/FIELDS.md, "Width").
    EXPECT_NEAR(found.solid_fraction, pi / 6, 0.01 * pi / 6);
    // phi_ref / 2 lies where the lattice's edge is, at its top grains' tops
    // (the midpoint rule of the layers' sum): measured 0.0028 mm above it
    // (0.0014 a), the angle 34.9998 degrees. Tolerances 0.02 a and 0.01
    // degree (the bilinear interpolation on a 1 mm grid, half a width).
    EXPECT_NEAR(found.angle * 180.0 / pi, 35.0, 0.01);
    EXPECT_NEAR(found.level, truth.level, 0.02 * a);
    EXPECT_NEAR(found.half_length, std::sqrt(far * far - found.level * found.level), 1e-12);
    EXPECT_LT(found.iterations, 100);

    // The profile in the found frame: averaged over the middle half of the
    // surface and the axis; nodes every w/4 from 3w above the surface, one
    // at d = 0.
    CgSettings ps;
    ps.kernel = CgKernel::lucy;
    ps.width = w;
    const double half = 0.5 * found.half_length, cell = 0.25 * w;
    ps.grid.lo = {-half, -3.0 * w - 0.5 * cell, -0.5 * a};
    ps.grid.hi = {half, -3.0 * w - 0.5 * cell + 100 * cell, (layers_z - 0.5) * a};
    ps.grid.cells = {1, 100, 1};
    ps.grid.averaged = {true, false, true};
    const GrainState in_frame = to_drum_frame(g, found);
    const Fields profile = coarse_grain(ps, in_frame.grains(), {});
    const FlowingLayer layer = flowing_layer(profile);

    // The profile's velocity computed directly: at a node D below the found
    // surface, which lies `offset` above the true one (so D - offset below
    // that), the kernel-weighted mean of u over the layers,
    // sum_j u(d_j) W(D - offset - d_j) / sum_j W(D - offset - d_j): the
    // coarse-grained V = j / rho of a profile averaged over whole layers.
    const double offset = found.level - truth.level;
    const auto expected_u = [&](double D) {
        double sum = 0.0, weight = 0.0;
        for (int j = 0; j < 40; ++j) {
            const double d = 0.5 * a + j * a;
            sum += u_of(d) * lucy(D - offset - d, w);
            weight += lucy(D - offset - d, w);
        }
        return sum / weight;
    };
    // u turns at delta below the true surface, delta + offset below the
    // found one: measured 10.003 mm (10.0028 expected); tolerance 0.02 a (the kernel's mean
    // of a linear u over evenly spaced layers is u at the node to 1e-3 a
    // for Lucy's kernel at w = a).
    EXPECT_NEAR(layer.thickness, delta + offset, 0.02 * a);
    // At the surface the kernel sees only the grains below: V(0) is the
    // mean of u over the layers under it. Measured 0.25273 m/s, as expected
    // to 1e-5; tolerance 1e-3 of U (the node at d = 0 is interpolated exactly;
    // the angle's error rotates u by less than 0.01 degree).
    EXPECT_NEAR(layer.surface_velocity, expected_u(0.0), 1e-3 * U);
    EXPECT_NEAR(layer.diameter, a, 1e-12 * a);  // every grain's
    // Inside the bed the shear rate is |du/dd| of that mean: U / delta = 30
    // 1/s for u itself, 30.2 for its mean over the layers (Lucy's sum over
    // layers one third of its reach apart is not quite linear). Measured
    // 30.271 1/s, as expected to 1e-5; tolerance 1e-3 (the angle's error).
    const std::size_t inside = 28;  // d = -3w + 28 w/4 = 4w
    const double d_inside = profile.grid.node(0, inside, 0).y;
    ASSERT_NEAR(d_inside, 4.0 * w, 1e-12);
    const double slope = (expected_u(d_inside - cell) - expected_u(d_inside + cell)) / (2.0 * cell);
    EXPECT_NEAR(profile.shear_rate[inside], slope, 1e-3 * slope);
    EXPECT_NEAR(profile.shear_rate[inside], U / delta, 0.02 * U / delta);
    EXPECT_NEAR(profile.velocity[inside].x, expected_u(d_inside), 1e-3 * U);
    EXPECT_NEAR(profile.velocity[inside].y, 0.0, 1e-3 * U);  // no flow across the surface
    std::printf("  [measured] phi_ref %.5f, angle %.4f degrees, level offset %.4g mm, thickness %.5g mm, surface "
                "velocity %.5g (expected %.5g) m/s, shear rate %.5g (expected %.5g) 1/s\n",
                found.solid_fraction, found.angle * 180.0 / pi, offset * 1e3, layer.thickness * 1e3,
                layer.surface_velocity, expected_u(0.0), profile.shear_rate[inside], slope);
}

TEST(FlowingLayer, RefusesACrossSectionWithoutASurface) {
    CgSettings s;
    s.width = a;
    s.grid.lo = {-0.04, -0.04, 0.0};
    s.grid.hi = {0.04, 0.04, 0.01};
    s.grid.cells = {40, 40, 1};
    s.grid.averaged = {false, false, true};
    const std::vector<Vec3> none;
    const std::vector<double> nothing;
    const Fields empty = coarse_grain(s, {none, none, nothing, nothing}, {});
    EXPECT_THROW(find_drum_surface(empty, 0.037, 0.5), tumble::Error);  // no grains
    s.grid.averaged = {false, false, false};
    s.grid.cells = {40, 40, 2};
    EXPECT_THROW(find_drum_surface(coarse_grain(s, {none, none, nothing, nothing}, {}), 0.037, 0.5),
                 tumble::Error);  // not a cross-section
}

}  // namespace

// The profile's shear rate is the strain rate of the whole gradient in the
// plane (s, d): a bed turning as a solid has none, where |du_s/dd| alone
// reads its angular velocity; a layer sheared along the surface keeps its
// |du_s/dd|.
TEST(FlowingLayer, ABedTurningAsASolidHasNoShearRateAndAShearedLayerKeepsIts) {
    DrumSurface truth;
    truth.angle = 35.0 * pi / 180.0;
    truth.level = -0.01;
    const double w = a, omega = 5.0;  // m; rad/s about +z
    CgSettings ps;
    ps.kernel = CgKernel::lucy;
    ps.width = w;
    const double half = 0.5 * std::sqrt(reach * reach - truth.level * truth.level), cell = 0.25 * w;
    ps.grid.lo = {-half, -3.0 * w - 0.5 * cell, -0.5 * a};
    ps.grid.hi = {half, -3.0 * w - 0.5 * cell + 100 * cell, (layers_z - 0.5) * a};
    ps.grid.cells = {1, 100, 1};
    ps.grid.averaged = {true, false, true};
    CgSettings two = ps;
    two.grid.cells[0] = 2;
    two.grid.averaged[0] = false;
    const std::size_t inside = 28;  // d = 4w, in the bed at both points across (s = +-half / 2)

    // The whole bed turning with the drum: v = omega z x r.
    GrainState turning = bed(truth);
    for (std::size_t i = 0; i < turning.position.size(); ++i)
        turning.velocity[i] = omega * Vec3{-turning.position[i].y, turning.position[i].x, 0.0};
    const GrainState turned = to_drum_frame(turning, truth);
    Fields profile = coarse_grain(ps, turned.grains(), {});
    // |du_s/dd| of a rotation is omega: measured 5.045 1/s, 0.9 % high as the
    // first test's 30.27 for 30 (Lucy's sum over layers a third of its reach
    // apart); tolerance 2 %.
    EXPECT_NEAR(profile.shear_rate[inside], omega, 0.02 * omega);
    const double before = profile.shear_rate[inside];
    use_in_plane_shear_rate(profile, coarse_grain(two, turned.grains(), {}));
    // du_d/ds = -omega cancels it, up to that 0.9 % (the gradient along s,
    // between two points half the span apart, has no layers to sum): measured
    // 0.045 1/s; tolerance 3 % of omega, against the 100 % before.
    EXPECT_LT(profile.shear_rate[inside], 0.03 * omega);
    EXPECT_DOUBLE_EQ(profile.inertial_number[inside],
                     inertial_number_at(profile, inside, profile.shear_rate[inside]));

    // The layer sheared along the surface (u(d) along t, the same at every
    // s): the gradient along s is zero and the shear rate stays |du_s/dd|,
    // 30.27 1/s (the first test): measured the same to 1e-9; tolerance 1e-6.
    const GrainState sheared = to_drum_frame(bed(truth), truth);
    Fields layer = coarse_grain(ps, sheared.grains(), {});
    const double along_d = layer.shear_rate[inside];
    use_in_plane_shear_rate(layer, coarse_grain(two, sheared.grains(), {}));
    EXPECT_NEAR(layer.shear_rate[inside], along_d, 1e-6 * along_d);
    std::printf("  [measured] turning bed: |du_s/dd| %.5g 1/s, in-plane %.3g 1/s; sheared layer: %.6g -> %.6g 1/s\n",
                before, profile.shear_rate[inside], along_d, layer.shear_rate[inside]);

    // A grid other than the profile's depth nodes at two points is refused.
    EXPECT_THROW(use_in_plane_shear_rate(layer, layer), tumble::Error);
}

// A profile carried from a cross-section averaged in the lab (fields taken
// during a run: drum_profile_of) against what the drum's frame gives.
namespace {

// The cross-section's settings: x and y resolved on cells of `cell`, z
// averaged over the bed's four layers.
CgSettings cross_section_settings(CgKernel kernel, double w, double cell) {
    CgSettings cs;
    cs.kernel = kernel;
    cs.width = w;
    const auto cells = static_cast<std::size_t>(std::lround(0.08 / cell));
    cs.grid.lo = {-0.04, -0.04, -0.5 * a};
    cs.grid.hi = {0.04, 0.04, (layers_z - 0.5) * a};
    cs.grid.cells = {cells, cells, 1};
    cs.grid.averaged = {false, false, true};
    return cs;
}

// The depth profile's grid below a surface, as the drum frame of tumble
// fields lays it: s from -half to half, `depths` nodes every `cell` from 3w
// above the surface.
CgSettings profile_settings(double half, double w, double cell, std::size_t across, std::size_t depths) {
    CgSettings ps;
    ps.kernel = CgKernel::gaussian;
    ps.width = w;
    ps.grid.lo = {-half, -3.0 * w, -0.5 * a};
    ps.grid.hi = {half, -3.0 * w + static_cast<double>(depths) * cell, (layers_z - 0.5) * a};
    ps.grid.cells = {across, depths, 1};
    ps.grid.averaged = {across == 1, false, true};
    return ps;
}

}  // namespace

// Fields linear in the plane are carried exactly: a bed of uniform density
// turning as a solid under a uniform stress. Its velocity along the surface
// is omega (level - d) (omega z x r = omega (h t - s n) for r = s t + h n),
// none across it on the span's mean, no shear rate; the stress is turned
// into the frame, Q sigma Q^T.
TEST(FlowingLayer, ACrossSectionTurningAsASolidCarriesItsRotationAndStressIntoTheFrame) {
    DrumSurface surface;
    surface.angle = 27.0 * pi / 180.0;
    surface.level = -0.01;
    const double omega = 1.2, rho = 1500.0, cell = 0.001;  // rad/s, kg/m^3, m
    const CgSettings cs = cross_section_settings(CgKernel::gaussian, a, cell);
    // sigma, Pa: a pressure with a shear in the plane and one out of it.
    const std::array<double, 9> sigma{300.0, 40.0, 5.0, 40.0, 250.0, -7.0, 5.0, -7.0, 280.0};
    std::vector<double> sums;
    for (std::size_t b = 0; b < cs.grid.cells[1]; ++b)
        for (std::size_t i = 0; i < cs.grid.cells[0]; ++i) {
            const Vec3 r = cs.grid.node(i, b, 0);
            const Vec3 j = rho * omega * Vec3{-r.y, r.x, 0.0};
            sums.insert(sums.end(), {rho, 0.6, rho * a, j.x, j.y, j.z});
            sums.insert(sums.end(), 9, 0.0);  // no kinetic stress
            sums.insert(sums.end(), sigma.begin(), sigma.end());
        }
    FieldAccumulator sum(cs);
    sum.restore(sums, 1);
    const Fields section = std::move(sum).finish();

    // 25 mm deep: every point of the profile's lines lies within the
    // cross-section's nodes (|r| < 38 mm), where a linear field is bilinear.
    const double half = 0.5 * std::sqrt(reach * reach - surface.level * surface.level);  // the chord's middle half
    const CgSettings ps = profile_settings(half, a, cell, 1, 25);
    Fields profile = drum_profile_of(section, surface, ps);
    use_in_plane_shear_rate(profile, drum_profile_of(section, surface, profile_settings(half, a, cell, 2, 25)));
    const Vec3 t = surface.along(), n = surface.normal();
    const std::array<Vec3, 3> e{t, -1.0 * n, Vec3{0.0, 0.0, 1.0}};
    // Tolerances 1e-9 of each scale: the bilinear interpolation of a linear
    // field is exact, the rest is rounding.
    for (std::size_t k = 0; k < ps.grid.cells[1]; ++k) {
        const double d = ps.grid.node(0, k, 0).y;
        EXPECT_NEAR(profile.density[k], rho, 1e-9 * rho);
        EXPECT_NEAR(profile.solid_fraction[k], 0.6, 1e-9);
        EXPECT_NEAR(profile.diameter[k], a, 1e-9 * a);
        EXPECT_NEAR(profile.velocity[k].x, omega * (surface.level - d), 1e-9 * omega * reach);
        EXPECT_NEAR(profile.velocity[k].y, 0.0, 1e-9 * omega * reach);
        EXPECT_NEAR(profile.shear_rate[k], 0.0, 1e-6 * omega);  // differences of velocities: 1e-9 of omega reach / cell
        for (int u = 0; u < 3; ++u)
            for (int v = 0; v < 3; ++v) {
                double turned = 0.0;
                for (int p = 0; p < 3; ++p)
                    for (int q = 0; q < 3; ++q)
                        turned += e[static_cast<std::size_t>(u)][p] * sigma[static_cast<std::size_t>(3 * p + q)] *
                                  e[static_cast<std::size_t>(v)][q];
                EXPECT_NEAR(profile.contact_stress[k](u, v), turned, 1e-9 * 300.0) << u << v;
            }
        EXPECT_NEAR(profile.pressure[k], (300.0 + 250.0 + 280.0) / 3.0, 1e-9 * 300.0);  // a trace: the same in any frame
    }
    // A profile grid resolved along z, or a section that is not one, is refused.
    CgSettings along_z = ps;
    along_z.grid.cells[2] = 2;
    along_z.grid.averaged[2] = false;
    EXPECT_THROW(drum_profile_of(section, surface, along_z), tumble::Error);
    EXPECT_THROW(drum_profile_of(profile, surface, ps), tumble::Error);
}

// The bed made to order (its layers parallel to the surface, sheared): the
// profile carried from its cross-section against its grains carried into
// the frame and coarse-grained there, with the Gaussian kernel (whose
// mean along s over a 2-D Gaussian is the 1-D one).
TEST(FlowingLayer, AProfileCarriedFromTheCrossSectionIsTheFramesOwn) {
    DrumSurface truth;
    truth.angle = 35.0 * pi / 180.0;
    truth.level = -0.01;
    const GrainState g = bed(truth);
    const double w = a, cell = 0.5e-3;
    const Fields section = coarse_grain(cross_section_settings(CgKernel::gaussian, w, cell), g.grains(), {});
    // s over whole columns of the lattice, 17 of them (-8.5 a to 8.5 a): the
    // frame's own profile counts the grains whose s lies in it, and a span
    // cut elsewhere miscounts the columns (by 4.5 % at the chord's middle half).
    const CgSettings ps = profile_settings(8.5 * a, w, cell, 1, 40);
    const Fields carried = drum_profile_of(section, truth, ps);
    const GrainState in_frame = to_drum_frame(g, truth);
    const Fields own = coarse_grain(ps, in_frame.grains(), {});
    double worst_phi = 0.0, worst_u = 0.0, worst_at = 0.0;
    for (std::size_t k = 0; k < ps.grid.cells[1]; ++k) {
        if (own.solid_fraction[k] < 0.05) continue;  // above the surface's edge
        const double dphi = std::abs(carried.solid_fraction[k] - own.solid_fraction[k]);
        if (dphi > worst_phi) worst_phi = dphi, worst_at = ps.grid.node(0, k, 0).y;
        worst_u = std::max(worst_u, std::abs(carried.velocity[k].x - own.velocity[k].x));
    }
    const FlowingLayer a_layer = flowing_layer(carried), b_layer = flowing_layer(own);
    std::printf("  [measured] carried against own: phi %.3g (at d = %.3g mm), u %.3g m/s at worst; thickness %.6g against %.6g mm, "
                "surface velocity %.6g against %.6g m/s\n",
                worst_phi, worst_at * 1e3, worst_u, a_layer.thickness * 1e3, b_layer.thickness * 1e3, a_layer.surface_velocity,
                b_layer.surface_velocity);
    // Measured: phi within 0.0011, u within 0.0024 U, the thickness the
    // same to 1e-4 a, the surface velocity within 0.0008 U. Tolerances a few
    // times those, what the interpolation between nodes 0.5 mm apart (a
    // quarter of w) and the kernel's cut at 3w (a disc in the cross-section,
    // a segment in the frame) can make of a field that changes over w.
    EXPECT_LT(worst_phi, 0.005);
    EXPECT_LT(worst_u, 0.005 * U);
    EXPECT_NEAR(a_layer.thickness, b_layer.thickness, 0.01 * a);
    EXPECT_NEAR(a_layer.surface_velocity, b_layer.surface_velocity, 0.004 * U);
}
