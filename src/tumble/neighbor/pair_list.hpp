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
    std::vector<double> integrated_slip;
    std::vector<double> integrated_angular_slip;
    std::vector<Vec3> tangential_spring;

    std::size_t size() const { return first.size(); }
    void clear() {
        for (auto* v : {&first, &second}) v->clear();
        image.clear();
        for (auto* v : {&integrated_slip, &integrated_angular_slip}) v->clear();
        tangential_spring.clear();
    }
    void add(std::uint32_t i, std::uint32_t j, std::uint8_t code) {
        first.push_back(i);
        second.push_back(j);
        image.push_back(code);
        integrated_slip.push_back(0.0);
        integrated_angular_slip.push_back(0.0);
        tangential_spring.emplace_back();
    }

    ContactHistory history(std::size_t k) const {
        ContactHistory h;
        h.integrated_slip = integrated_slip[k];
        h.integrated_angular_slip = integrated_angular_slip[k];
        h.tangential_spring = tangential_spring[k];
        return h;
    }
    void set_history(std::size_t k, const ContactHistory& h) {
        integrated_slip[k] = h.integrated_slip;
        integrated_angular_slip[k] = h.integrated_angular_slip;
        tangential_spring[k] = h.tangential_spring;
    }
    // Every pair's history in list order (checkpoints, tests), and back.
    std::vector<ContactHistory> histories() const {
        std::vector<ContactHistory> all(size());
        for (std::size_t k = 0; k < size(); ++k) all[k] = history(k);
        return all;
    }
    void set_histories(const std::vector<ContactHistory>& all) {
        integrated_slip.resize(all.size());
        integrated_angular_slip.resize(all.size());
        tangential_spring.resize(all.size());
        for (std::size_t k = 0; k < all.size(); ++k) set_history(k, all[k]);
    }
};

}  // namespace tumble
