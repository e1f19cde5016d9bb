// SPDX-License-Identifier: MIT
// Checked reading of TOML files: every value is read through Reader, which
// names the file, the key path (config.hpp describes the convention) and the
// reason when a value is missing, of the wrong type, or out of range.
// Shared by the scenario reader (config.cpp) and the drum reader.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "io/config.hpp"
#include "io/drum_config.hpp"
#include "io/names.hpp"
#include "tumble/core/keyword.hpp"
#include "tumble/core/vec3.hpp"

namespace tumble::io {

// The text of a file; ConfigError naming the file if it cannot be read or
// is larger than `max_bytes` (input files are small: an enormous or endless
// one, /dev/zero, is refused before it fills the memory).
inline constexpr std::size_t max_input_file_bytes = std::size_t{64} << 20;
std::string read_text_file(const std::filesystem::path& file, std::size_t max_bytes = max_input_file_bytes);

// Parses TOML; a syntax error becomes ConfigError "FILE: line L, column C: ...".
toml::table parse_toml(std::string_view text, const std::filesystem::path& name);

// The scenario reader (config.hpp) and the drum reader (drum_config.hpp) on
// a table already parsed or built (the Python module builds one from a
// dict); `name` stands for the file in messages.
RunConfig read_run_config(const toml::table& root, const std::filesystem::path& name,
                          const std::filesystem::path& base_dir, const ParticleCheck& check = {});
DrumSettings read_drum_settings(const toml::table& root, const std::filesystem::path& name);

// Key paths (config.hpp): "a.b", "a[3]".
inline std::string join(const std::string& path, std::string_view key) {
    return path.empty() ? std::string(key) : path + "." + std::string(key);
}
inline std::string at(const std::string& path, std::size_t index) { return path + "[" + std::to_string(index) + "]"; }

inline std::string type_name(const toml::node& n) {
    switch (n.type()) {
        case toml::node_type::string: return "a string";
        case toml::node_type::integer: return "an integer";
        case toml::node_type::floating_point: return "a floating-point number";
        case toml::node_type::boolean: return "a boolean";
        case toml::node_type::array: return "an array";
        case toml::node_type::table: return "a table";
        case toml::node_type::date: return "a date";
        case toml::node_type::time: return "a time";
        case toml::node_type::date_time: return "a date-time";
        default: return "nothing";
    }
}

// Shortest round-tripping form of a number, for messages.
inline std::string show(double v) { return fmt::format("{}", v); }

enum class Bound { any, non_negative, positive };

// Reads typed values out of the parsed TOML tree; every failure names the
// file, the key path and the reason.
class Reader {
public:
    explicit Reader(std::filesystem::path file) : file_(std::move(file)) {}

    const std::filesystem::path& file() const { return file_; }

    [[noreturn]] void fail(const std::string& key, const std::string& reason, const toml::node* at = nullptr) const {
        std::string text = reason;
        if (at && at->source().begin.line > 0) text += fmt::format(" (line {})", at->source().begin.line);
        throw ConfigError(file_, key, std::move(text));
    }

    // Refuses keys of `t` that are not in `known`.
    void only_keys(const toml::table& t, const std::string& path, const std::vector<std::string_view>& known) const {
        for (auto&& [key, value] : t) {
            if (std::find(known.begin(), known.end(), key.str()) != known.end()) continue;
            const std::vector<std::string> names(known.begin(), known.end());
            std::string reason = "unknown key" + detail::did_you_mean(key.str(), names) +
                                 "; known keys here: " + detail::quoted_list(names);
            if (key.source().begin.line > 0) reason += fmt::format(" (line {})", key.source().begin.line);
            throw ConfigError(file_, join(path, key.str()), std::move(reason));
        }
    }

    const toml::node& required(const toml::table& t, const std::string& path, std::string_view key) const {
        const toml::node* n = t.get(key);
        if (!n) {
            std::string reason = "missing required key";
            if (!path.empty() && t.source().begin.line > 0)
                reason += fmt::format(" (in the table at line {})", t.source().begin.line);
            throw ConfigError(file_, join(path, key), std::move(reason));
        }
        return *n;
    }

    // --- single values ---

    // The entry of `table` (a keyword table of the engine, e.g. shear_models)
    // that the string at `key` names; else a failure with the known keywords.
    template <class Value, std::size_t N>
    const Keyword<Value>* keyword(const toml::node& n, const std::string& key,
                                  const std::array<Keyword<Value>, N>& table) const {
        const std::string word = string(n, key);
        if (const Keyword<Value>* e = find_keyword(table, word)) return e;
        const std::vector<std::string> known = keywords(table);
        fail(key, "unknown choice \"" + word + "\"" + detail::did_you_mean(word, known) +
                      "; known: " + detail::quoted_list(known),
             &n);
    }

    double number(const toml::node& n, const std::string& key, Bound bound = Bound::any) const {
        double v = 0.0;
        if (const auto* i = n.as_integer())
            v = static_cast<double>(i->get());
        else if (const auto* f = n.as_floating_point())
            v = f->get();
        else
            fail(key, "expected a number, got " + type_name(n), &n);
        if (!std::isfinite(v)) fail(key, "must be finite, got " + show(v), &n);
        if (bound == Bound::positive && !(v > 0.0)) fail(key, "must be > 0, got " + show(v), &n);
        if (bound == Bound::non_negative && !(v >= 0.0)) fail(key, "must be >= 0, got " + show(v), &n);
        return v;
    }

    std::int64_t integer(const toml::node& n, const std::string& key, std::int64_t min, std::int64_t max) const {
        const auto* i = n.as_integer();
        if (!i) fail(key, "expected an integer, got " + type_name(n), &n);
        const std::int64_t v = i->get();
        if (v < min || v > max) fail(key, fmt::format("must lie in [{}, {}], got {}", min, max, v), &n);
        return v;
    }

    bool boolean(const toml::node& n, const std::string& key) const {
        const auto* b = n.as_boolean();
        if (!b) fail(key, "expected true or false, got " + type_name(n), &n);
        return b->get();
    }

    std::string string(const toml::node& n, const std::string& key) const {
        const auto* s = n.as_string();
        if (!s) fail(key, "expected a string, got " + type_name(n), &n);
        if (s->get().empty()) fail(key, "must not be empty", &n);
        return s->get();
    }

    const toml::array& array(const toml::node& n, const std::string& key, std::size_t size,
                             std::string_view what) const {
        const auto* a = n.as_array();
        if (!a) fail(key, fmt::format("expected {}, got {}", what, type_name(n)), &n);
        if (a->size() != size) fail(key, fmt::format("expected {}, got {} elements", what, a->size()), &n);
        return *a;
    }

    // An array of numbers of any length.
    std::vector<double> numbers(const toml::node& n, const std::string& key) const {
        const auto* a = n.as_array();
        if (!a) fail(key, "expected an array of numbers [a, b, ...], got " + type_name(n), &n);
        std::vector<double> v;
        for (std::size_t k = 0; k < a->size(); ++k) v.push_back(number(*a->get(k), at(key, k)));
        return v;
    }

    Vec3 vec3(const toml::node& n, const std::string& key) const {
        const toml::array& a = array(n, key, 3, "an array of 3 numbers [x, y, z]");
        Vec3 v;
        for (int k = 0; k < 3; ++k) v[k] = number(*a.get(k), at(key, k));
        return v;
    }

    std::array<bool, 3> bool3(const toml::node& n, const std::string& key) const {
        const toml::array& a = array(n, key, 3, "an array of 3 booleans [x, y, z]");
        std::array<bool, 3> v{};
        for (int k = 0; k < 3; ++k) v[k] = boolean(*a.get(k), at(key, k));
        return v;
    }

    // --- keys of a table: absent -> default or nullopt ---

    std::optional<double> number(const toml::table& t, const std::string& path, std::string_view key,
                                 Bound bound = Bound::any) const {
        const toml::node* n = t.get(key);
        return n ? std::optional<double>(number(*n, join(path, key), bound)) : std::nullopt;
    }
    double number(const toml::table& t, const std::string& path, std::string_view key, Bound bound,
                  double fallback) const {
        return number(t, path, key, bound).value_or(fallback);
    }
    double required_number(const toml::table& t, const std::string& path, std::string_view key, Bound bound) const {
        return number(required(t, path, key), join(path, key), bound);
    }
    bool boolean(const toml::table& t, const std::string& path, std::string_view key, bool fallback) const {
        const toml::node* n = t.get(key);
        return n ? boolean(*n, join(path, key)) : fallback;
    }
    std::optional<Vec3> vec3(const toml::table& t, const std::string& path, std::string_view key) const {
        const toml::node* n = t.get(key);
        return n ? std::optional<Vec3>(vec3(*n, join(path, key))) : std::nullopt;
    }
    Vec3 required_vec3(const toml::table& t, const std::string& path, std::string_view key) const {
        return vec3(required(t, path, key), join(path, key));
    }

    // --- sections ---

    // [name]: nullptr if absent and not required.
    const toml::table* table(const toml::table& root, std::string_view name, bool is_required) const {
        const toml::node* n = is_required ? &required(root, "", name) : root.get(name);
        if (!n) return nullptr;
        if (!n->as_table())
            fail(std::string(name), fmt::format("expected a table [{}], got {}", name, type_name(*n)), n);
        return n->as_table();
    }

    // [[name]] (or an array of inline tables): the entries, each checked to be a table.
    std::vector<const toml::table*> tables(const toml::table& parent, const std::string& path,
                                           std::string_view name) const {
        std::vector<const toml::table*> out;
        const toml::node* n = parent.get(name);
        if (!n) return out;
        const std::string key = join(path, name);
        const auto* a = n->as_array();
        if (!a)
            fail(key,
                 path.empty() ? fmt::format("expected an array of tables [[{}]], got {}", key, type_name(*n))
                              : fmt::format("expected an array of tables [{{...}}, ...], got {}", type_name(*n)),
                 n);
        for (std::size_t i = 0; i < a->size(); ++i) {
            const toml::node& e = *a->get(i);
            if (!e.as_table()) fail(at(key, i), "expected a table, got " + type_name(e), &e);
            out.push_back(e.as_table());
        }
        return out;
    }

private:
    std::filesystem::path file_;
};

}  // namespace tumble::io
