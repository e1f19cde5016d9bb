// SPDX-License-Identifier: MIT
// Helpers for error messages about names: the closest known name to a
// misspelt one, and a list of the known ones. The input readers of tumble_io
// use them, and the command line (src/cli/main.cpp) for its commands and
// options.
#pragma once

#include <algorithm>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tumble::io {

namespace detail {

// Edit distance counting insertions, deletions, substitutions and swaps of
// two neighbouring letters ("rnu" is one swap from "run"), case-blind: the
// optimal string alignment distance.
inline std::size_t edit_distance(std::string_view a, std::string_view b) {
    auto same = [](char x, char y) {
        auto lower = [](char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; };
        return lower(x) == lower(y);
    };
    // d[i][j]: the distance between the first i letters of a and the first j of b.
    std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
    for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
    for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i)
        for (std::size_t j = 1; j <= b.size(); ++j) {
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (same(a[i - 1], b[j - 1]) ? 0 : 1)});
            if (i > 1 && j > 1 && same(a[i - 1], b[j - 2]) && same(a[i - 2], b[j - 1]))
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    return d[a.size()][b.size()];
}

}  // namespace detail

// The candidate closest to a misspelt word if it is close (at most a third
// of the word's letters wrong, and at least 1 allowed), else none.
inline std::optional<std::string> closest_name(std::string_view word, const std::vector<std::string>& candidates) {
    std::optional<std::string> best;
    std::size_t best_distance = std::max<std::size_t>(1, word.size() / 3) + 1;
    for (const std::string& c : candidates) {
        const std::size_t d = detail::edit_distance(word, c);
        if (d < best_distance) {
            best_distance = d;
            best = c;
        }
    }
    return best;
}

namespace detail {

// " (did you mean "x"?)" for the closest candidate if it is close, else "".
inline std::string did_you_mean(std::string_view word, const std::vector<std::string>& candidates) {
    const std::optional<std::string> best = closest_name(word, candidates);
    return best ? " (did you mean \"" + *best + "\"?)" : std::string();
}

// "a", "b", "c"
inline std::string quoted_list(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "\"" : ", \"") + n + "\"";
    return out.empty() ? "none" : out;
}

}  // namespace detail

}  // namespace tumble::io
