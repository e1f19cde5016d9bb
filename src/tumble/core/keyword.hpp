// SPDX-License-Identifier: MIT
// Choices named by keyword in input files and on the command line (the
// shear model, the friction normal): a table of keyword, value and meaning,
// and the look-ups that readers and the command line share.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace tumble {

template <class Value>
struct Keyword {
    std::string_view keyword;
    Value value;
    std::string_view description;
};

// The entry of `table` named `keyword`, or nullptr.
template <class Value, std::size_t N>
const Keyword<Value>* find_keyword(const std::array<Keyword<Value>, N>& table, std::string_view keyword) {
    for (const Keyword<Value>& e : table)
        if (e.keyword == keyword) return &e;
    return nullptr;
}

// The keyword of `value` in `table`.
template <class Value, std::size_t N>
std::string_view keyword_of(const std::array<Keyword<Value>, N>& table, Value value) {
    for (const Keyword<Value>& e : table)
        if (e.value == value) return e.keyword;
    return "?";
}

// Every keyword of `table`, in its order.
template <class Value, std::size_t N>
std::vector<std::string> keywords(const std::array<Keyword<Value>, N>& table) {
    std::vector<std::string> words;
    for (const Keyword<Value>& e : table) words.emplace_back(e.keyword);
    return words;
}

}  // namespace tumble
