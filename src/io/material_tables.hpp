// SPDX-License-Identifier: MIT
// The [[material]] and [[pair]] tables (docs/SCENARIO.md), read alike by
// the scenario reader (config.cpp) and the drum reader (drum_config.cpp):
// every material's eight parameters, and mu and W of every pair of them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "tumble/materials/material.hpp"

namespace tumble::io {

class Reader;

struct MaterialTables {
    std::vector<Material> materials;                           // in file order
    std::vector<std::vector<PairProperties>> pair_properties;  // [a][b], symmetric
    std::vector<std::string> names;                            // of `materials`

    // The index of the material that the string at `key` names; else a
    // failure naming the key, with the nearest known name and the list.
    std::int32_t index(const Reader& r, const toml::node& n, const std::string& key) const;
};

// The [[material]] tables of `root` and then its [[pair]] tables. Refused,
// naming the key: an unknown or missing key, a value out of range, a
// duplicate name or pair, a pair of an unknown material, and a pair of the
// materials (each with itself included) that no [[pair]] gives. No
// [[material]] at all is refused if `required`; else (nor [[pair]]) it
// gives no materials.
MaterialTables read_material_tables(const Reader& r, const toml::table& root, bool required);

}  // namespace tumble::io
