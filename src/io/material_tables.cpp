// SPDX-License-Identifier: MIT
#include "io/material_tables.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "io/names.hpp"
#include "io/toml_reader.hpp"

namespace tumble::io {

std::int32_t MaterialTables::index(const Reader& r, const toml::node& n, const std::string& key) const {
    const std::string name = r.string(n, key);
    const auto found = std::find(names.begin(), names.end(), name);
    if (found == names.end())
        r.fail(key,
               "unknown material \"" + name + "\"" + detail::did_you_mean(name, names) +
                   (names.empty() ? std::string("; no [[material]] is defined")
                                  : "; known materials: " + detail::quoted_list(names)),
               &n);
    return static_cast<std::int32_t>(found - names.begin());
}

namespace {

void read_materials(const Reader& r, const toml::table& root, bool required, MaterialTables& out) {
    const auto entries = r.tables(root, "", "material");
    if (entries.empty() && required) r.fail("material", "missing: at least one [[material]] is required");
    for (std::size_t i = 0; i < entries.size(); ++i) {
        const toml::table& t = *entries[i];
        const std::string p = at("material", i);
        r.only_keys(t, p, {"name", "E", "G", "nu", "xi", "eta", "rho", "radius"});
        Material m;
        m.name = r.string(r.required(t, p, "name"), join(p, "name"));
        for (std::size_t j = 0; j < i; ++j)
            if (out.names[j] == m.name)
                r.fail(join(p, "name"), fmt::format("duplicate material name \"{}\" (also material[{}])", m.name, j),
                       t.get("name"));
        m.E = r.required_number(t, p, "E", Bound::positive);
        m.G = r.required_number(t, p, "G", Bound::positive);
        m.nu = r.required_number(t, p, "nu", Bound::any);
        if (!(m.nu > -1.0 && m.nu < 0.5))
            r.fail(join(p, "nu"), "Poisson ratio must lie in (-1, 0.5), got " + show(m.nu), t.get("nu"));
        m.xi = r.required_number(t, p, "xi", Bound::non_negative);
        m.eta = r.required_number(t, p, "eta", Bound::non_negative);
        m.rho = r.required_number(t, p, "rho", Bound::positive);
        m.radius = r.required_number(t, p, "radius", Bound::positive);
        if (const std::string why = material_problem(m); !why.empty()) r.fail(p, why, &t);
        out.materials.push_back(m);
        out.names.push_back(m.name);
    }
}

void read_pairs(const Reader& r, const toml::table& root, MaterialTables& out) {
    const std::size_t n = out.materials.size();
    out.pair_properties.assign(n, std::vector<PairProperties>(n));
    std::vector<std::vector<int>> given(n, std::vector<int>(n, -1));  // which [[pair]] gave it
    const auto entries = r.tables(root, "", "pair");
    for (std::size_t i = 0; i < entries.size(); ++i) {
        const toml::table& t = *entries[i];
        const std::string p = at("pair", i);
        r.only_keys(t, p, {"materials", "mu", "W"});
        const std::string key = join(p, "materials");
        const toml::node& names = r.required(t, p, "materials");
        const toml::array& a = r.array(names, key, 2, "an array of 2 material names [\"a\", \"b\"]");
        const std::int32_t m0 = out.index(r, *a.get(0), at(key, 0));
        const std::int32_t m1 = out.index(r, *a.get(1), at(key, 1));
        if (given[m0][m1] >= 0)
            r.fail(key,
                   fmt::format("duplicate pair \"{}\" - \"{}\" (already given by pair[{}])", out.names[m0],
                               out.names[m1], given[m0][m1]),
                   &names);
        PairProperties props;
        props.mu = r.required_number(t, p, "mu", Bound::non_negative);
        props.W = r.required_number(t, p, "W", Bound::non_negative);
        out.pair_properties[m0][m1] = out.pair_properties[m1][m0] = props;
        given[m0][m1] = given[m1][m0] = static_cast<int>(i);
    }
    for (std::size_t a = 0; a < n; ++a)
        for (std::size_t b = a; b < n; ++b)
            if (given[a][b] < 0)
                r.fail("pair", fmt::format("missing [[pair]] with materials = [\"{}\", \"{}\"] (every pair of "
                                           "materials, including each with itself, needs mu and W)",
                                           out.names[a], out.names[b]));
}

}  // namespace

MaterialTables read_material_tables(const Reader& r, const toml::table& root, bool required) {
    MaterialTables out;
    read_materials(r, root, required, out);
    read_pairs(r, root, out);
    return out;
}

}  // namespace tumble::io
