// SPDX-License-Identifier: MIT
#include "io/toml_reader.hpp"

#include <fstream>
#include <sstream>

#include <fmt/format.h>

namespace tumble::io {

namespace fs = std::filesystem;

std::string read_text_file(const fs::path& file, std::size_t max_bytes) {
    std::ifstream in(file, std::ios::binary);
    if (!in) {
        std::error_code ec;
        throw ConfigError(file, "", fs::exists(file, ec) ? "cannot open the file" : "no such file");
    }
    std::string text;
    char buffer[1 << 16];
    while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
        if (text.size() + static_cast<std::size_t>(in.gcount()) > max_bytes)
            throw ConfigError(file, "", fmt::format("larger than {} MiB: not an input file of tumble", max_bytes >> 20));
        text.append(buffer, static_cast<std::size_t>(in.gcount()));
    }
    if (in.bad()) throw ConfigError(file, "", "read error");
    return text;
}

toml::table parse_toml(std::string_view text, const fs::path& name) {
    try {
        return toml::parse(text, name.string());
    } catch (const toml::parse_error& e) {
        const auto& where = e.source().begin;
        throw ConfigError(name, fmt::format("line {}, column {}", where.line, where.column),
                          "TOML syntax error: " + std::string(e.description()));
    }
}

}  // namespace tumble::io
