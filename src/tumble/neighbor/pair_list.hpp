// SPDX-License-Identifier: MIT
// A half neighbour list: each candidate pair once, grouped by its first
// particle, with the periodic image of the second and the contact history.
#pragma once

#include <cstdint>
#include <vector>

#include "tumble/contact/history.hpp"

namespace tumble {

struct PairList {
    std::vector<std::uint32_t> first;    // array index of i
    std::vector<std::uint32_t> second;   // array index of j
    std::vector<std::uint8_t> image;     // periodic image code of j (periodic_images.hpp)
    // The history of the contact between i and j (ContactHistory; zero if
    // none), one array per field, so that the pair loop reads and writes it
    // several contacts per instruction.
    std::vector<Vec3> slip;
    std::vector<double> angular_slip;
    std::vector<double> viscous_force;

    std::size_t size() const { return first.size(); }
    void clear() {
        for (auto* v : {&first, &second}) v->clear();
        image.clear();
        slip.clear();
        angular_slip.clear();
        viscous_force.clear();
    }
    void add(std::uint32_t i, std::uint32_t j, std::uint8_t code) {
        first.push_back(i);
        second.push_back(j);
        image.push_back(code);
        slip.emplace_back();
        angular_slip.push_back(0.0);
        viscous_force.push_back(0.0);
    }

    ContactHistory history(std::size_t k) const {
        ContactHistory h;
        h.slip = slip[k];
        h.angular_slip = angular_slip[k];
        h.viscous_force = viscous_force[k];
        return h;
    }
    void set_history(std::size_t k, const ContactHistory& h) {
        slip[k] = h.slip;
        angular_slip[k] = h.angular_slip;
        viscous_force[k] = h.viscous_force;
    }
    // Every pair's history in list order (checkpoints, tests), and back.
    std::vector<ContactHistory> histories() const {
        std::vector<ContactHistory> all(size());
        for (std::size_t k = 0; k < size(); ++k) all[k] = history(k);
        return all;
    }
    void set_histories(const std::vector<ContactHistory>& all) {
        slip.resize(all.size());
        angular_slip.resize(all.size());
        viscous_force.resize(all.size());
        for (std::size_t k = 0; k < all.size(); ++k) set_history(k, all[k]);
    }
};

}  // namespace tumble
