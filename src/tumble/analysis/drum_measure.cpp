// SPDX-License-Identifier: MIT
#include "tumble/analysis/drum_measure.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tumble/core/constants.hpp"
#include "tumble/core/error.hpp"

namespace tumble::analysis {

namespace {

// Principal axis of the grains' positions in the cross-section (x, y),
// mass-weighted: the inclination of the long axis, degrees.
double principal_axis_angle(const ParticleStore& p, const Vec3& centre) {
    double xx = 0.0, yy = 0.0, xy = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (p.is_kinematic(i)) continue;
        const double dx = p.position[i].x - centre.x, dy = p.position[i].y - centre.y;
        xx += p.mass[i] * dx * dx;
        yy += p.mass[i] * dy * dy;
        xy += p.mass[i] * dx * dy;
    }
    return 0.5 * std::atan2(2.0 * xy, xx - yy) * 180.0 / pi;
}

}  // namespace

DrumState measure_drum(const ParticleStore& p, const DrumFrame& frame) {
    if (frame.components < 1 || frame.profile_bins < 1 || !(frame.inner_length > 0.0))
        throw Error("drum measurement: need at least one component, one bin and a positive length");
    const auto n_components = static_cast<std::size_t>(frame.components);
    const auto bins = static_cast<std::size_t>(frame.profile_bins);
    DrumState state;
    state.components.resize(n_components);
    std::vector<double> sum_z(n_components), sum_z2(n_components);
    std::vector<std::vector<double>> volume(n_components, std::vector<double>(bins));
    std::vector<double> bin_volume(bins);
    double total_mass = 0.0;

    for (std::size_t i = 0; i < p.size(); ++i) {
        if (p.is_kinematic(i)) continue;
        if (p.tag[i] < 0 || p.tag[i] >= frame.components)
            throw Error("drum measurement: grain " + std::to_string(p.id[i]) + " has tag " + std::to_string(p.tag[i]) +
                        ", expected 0 .. " + std::to_string(frame.components - 1));
        const auto c = static_cast<std::size_t>(p.tag[i]);
        ComponentState& s = state.components[c];
        const double z = p.position[i].z;
        ++s.grains;
        s.mass += p.mass[i];
        sum_z[c] += z;
        sum_z2[c] += z * z;
        s.kinetic_energy += 0.5 * p.mass[i] * norm2(p.velocity[i]);
        const double relative = (z + 0.5 * frame.inner_length) / frame.inner_length;
        const auto b = static_cast<std::size_t>(std::clamp(relative * static_cast<double>(bins), 0.0, bins - 1.0));
        const double v = 4.0 / 3.0 * pi * p.radius[i] * p.radius[i] * p.radius[i];
        volume[c][b] += v;
        bin_volume[b] += v;
        state.bed_centre += p.mass[i] * p.position[i];
        total_mass += p.mass[i];
    }
    for (std::size_t c = 0; c < n_components; ++c) {
        ComponentState& s = state.components[c];
        const double n = static_cast<double>(s.grains);
        if (s.grains > 0) {
            s.mean_z = sum_z[c] / n;
            s.kinetic_per_grain = s.kinetic_energy / n;
        }
        if (s.grains > 1) {
            const double variance = std::max(0.0, (sum_z2[c] - n * s.mean_z * s.mean_z) / (n - 1.0));
            s.mean_z_stderr = std::sqrt(variance / n);
        }
        s.concentration.resize(bins);
        for (std::size_t b = 0; b < bins; ++b) s.concentration[b] = bin_volume[b] > 0.0 ? volume[c][b] / bin_volume[b] : -1.0;
    }
    if (total_mass > 0.0) state.bed_centre *= 1.0 / total_mass;
    // With the drum turning counter-clockwise about +z (seen from +z, y up)
    // its bottom moves toward +x and the surface rises there.
    const double direction = frame.rotation < 0.0 ? -1.0 : 1.0;
    state.angle_of_repose = total_mass > 0.0 ? direction * principal_axis_angle(p, state.bed_centre)
                                             : std::numeric_limits<double>::quiet_NaN();
    double mean_radius = 0.0;
    std::size_t grains = 0;
    for (const ComponentState& c : state.components) grains += c.grains;
    for (std::size_t i = 0; i < p.size(); ++i)
        if (!p.is_kinematic(i)) mean_radius += p.radius[i] / static_cast<double>(grains);
    const double reach = frame.inner_radius - mean_radius;  // where grain centres can be
    state.fill_fraction = segment_fill_fraction(std::hypot(state.bed_centre.x, state.bed_centre.y), reach);
    return state;
}

double segment_angle(double centroid_distance, double R) {
    // A segment of central angle theta has its centroid at
    // 4 R sin^3(theta/2) / (3 (theta - sin theta)) from the centre, falling
    // monotonically from R (theta -> 0) to 0 (theta = 2 pi): bisect.
    const double d = std::clamp(centroid_distance, 0.0, R);
    double lo = 0.0, hi = 2.0 * pi;
    for (int k = 0; k < 100; ++k) {
        const double theta = 0.5 * (lo + hi);
        const double s = std::sin(0.5 * theta);
        const double centroid = 4.0 * R * s * s * s / (3.0 * (theta - std::sin(theta)));
        (centroid > d ? lo : hi) = theta;
    }
    return 0.5 * (lo + hi);
}

double segment_fill_fraction(double centroid_distance, double R) {
    const double theta = segment_angle(centroid_distance, R);
    return (theta - std::sin(theta)) / (2.0 * pi);
}

}  // namespace tumble::analysis
