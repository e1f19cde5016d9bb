// SPDX-License-Identifier: MIT
#include "tumble/sim/contact_network.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "tumble/contact/attraction.hpp"
#include "tumble/contact/geometry.hpp"
#include "tumble/contact/hertz.hpp"
#include "tumble/contact/kuwabara_kono.hpp"
#include "tumble/core/mpi.hpp"
#include "tumble/materials/pair_table.hpp"

namespace tumble {


// The same pair test and geometry as the force loop (add_contact_forces in
// simulation.cpp), then only the normal terms of contact_law(): those need
// no history, so nothing is mutated and the result is what the force law
// would give for the present state.
std::vector<ContactLink> contact_network(const Simulation& sim) {
    const Scenario& s = sim.scenario();
    const ParticleStore& p = sim.particles();
    const PairList& pairs = sim.neighbors().pairs();
    const PeriodicImages& images = sim.neighbors().images();
    const ContactModel& model = s.model;

    std::vector<ContactLink> links;
    for (std::size_t k = 0; k < pairs.size(); ++k) {
        std::uint32_t i = pairs.first[k], j = pairs.second[k];
        if (!sim.counts_pair(i, j)) continue;
        Vec3 d = p.position[i] - p.position[j] + images[pairs.image[k]];
        const double distance2 = norm2(d);
        const double reach = p.radius[i] + p.radius[j];
        if (distance2 >= reach * reach) continue;
        ContactHistory history = pairs.history(k);
        if (p.id[i] > p.id[j]) {  // orient lower id first; n and the history flip with the pair
            std::swap(i, j);
            d = -d;
            history = history.swapped();
        }
        const ContactGeometry g =
            make_contact_geometry(d, std::sqrt(distance2), p.radius[i], p.radius[j], p.velocity[i] - p.velocity[j],
                                  p.half_kick[i] - p.half_kick[j], p.angular_velocity[i], p.angular_velocity[j]);
        const std::size_t a = static_cast<std::size_t>(p.material[i]), b = static_cast<std::size_t>(p.material[j]);
        const PairCoefficients c = make_pair_coefficients(s.materials[a], s.materials[b], s.pair_properties[a][b]);

        // Normal force along n, as in contact_law(): elasticity, internal
        // friction, surface attraction.
        double F_n = 0.0;
        if (model.elastic) F_n += hertz_force(c.E_star, g.contact_radius, g.overlap);
        if (model.viscous) F_n += kuwabara_kono_force(c.B_star, g.contact_radius, g.v_n);
        if (model.attraction) F_n += attraction_force(c.attraction, g.contact_radius);

        links.push_back({p.id[i], p.id[j], p.position[i] - g.lever_i * g.n, g.n, g.overlap, F_n, history});
    }
    if (sim.shared()) {  // every rank's links on rank 0
        const char* mine = reinterpret_cast<const char*>(links.data());
        std::vector<ContactLink> all;
        for (const mpi::Bytes& part : mpi::gather(mpi::Bytes(mine, mine + links.size() * sizeof(ContactLink)))) {
            const std::size_t at = all.size();
            all.resize(at + part.size() / sizeof(ContactLink));
            std::copy(part.begin(), part.end(), reinterpret_cast<char*>(all.data() + at));
        }
        links = std::move(all);
    }
    std::sort(links.begin(), links.end(), [](const ContactLink& x, const ContactLink& y) {
        return x.id_i != y.id_i ? x.id_i < y.id_i : x.id_j < y.id_j;
    });
    return links;
}

std::vector<std::uint32_t> contact_counts(const Simulation& sim) {
    const ParticleStore& p = sim.particles();
    const PairList& pairs = sim.neighbors().pairs();
    const PeriodicImages& images = sim.neighbors().images();
    std::vector<std::uint32_t> counts(sim.scenario().particles.size(), 0);
    for (std::size_t k = 0; k < pairs.size(); ++k) {
        const std::uint32_t i = pairs.first[k], j = pairs.second[k];
        if (!sim.counts_pair(i, j)) continue;
        const double reach = p.radius[i] + p.radius[j];
        if (norm2(p.position[i] - p.position[j] + images[pairs.image[k]]) >= reach * reach) continue;
        ++counts[static_cast<std::size_t>(p.id[i])];
        ++counts[static_cast<std::size_t>(p.id[j])];
    }
    if (sim.shared()) {  // the sums of all ranks (exact: small integers in doubles)
        std::vector<double> sums(counts.begin(), counts.end());
        mpi::sum(sums);
        std::transform(sums.begin(), sums.end(), counts.begin(), [](double c) { return static_cast<std::uint32_t>(c); });
    }
    return counts;
}

}  // namespace tumble
