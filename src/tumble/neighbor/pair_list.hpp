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
    std::vector<ContactHistory> history; // of the contact between i and j, zero if none

    std::size_t size() const { return first.size(); }
    void clear() {
        first.clear();
        second.clear();
        image.clear();
        history.clear();
    }
    void add(std::uint32_t i, std::uint32_t j, std::uint8_t code) {
        first.push_back(i);
        second.push_back(j);
        image.push_back(code);
        history.emplace_back();
    }
};

}  // namespace tumble
