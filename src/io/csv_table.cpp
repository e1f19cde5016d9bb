// SPDX-License-Identifier: MIT
#include "io/csv_table.hpp"

#include <cctype>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>

#include "tumble/core/error.hpp"

namespace tumble::io {

namespace fs = std::filesystem;

namespace {

std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    std::string cell;
    while (std::getline(s, cell, ',')) cells.push_back(cell);
    return cells;
}

double number(const std::string& cell, const fs::path& file) {
    try {
        std::size_t used = 0;
        const double v = std::stod(cell, &used);
        if (used == cell.size()) return v;
    } catch (const std::exception&) {
    }
    if (cell == "nan") return std::numeric_limits<double>::quiet_NaN();
    throw Error(file.string() + ": \"" + cell + "\" is not a number");
}

}  // namespace

std::string column_name(std::string_view name) {
    std::string out(name);
    for (char& c : out)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') c = '_';
    return out;
}

std::size_t CsvTable::column(const std::string& name) const {
    for (std::size_t k = 0; k < header.size(); ++k)
        if (header[k] == name) return k;
    throw Error(file.string() + ": no column \"" + name + "\"");
}

std::vector<double> CsvTable::numbers(const std::string& name) const {
    const std::size_t k = column(name);
    std::vector<double> out;
    out.reserve(rows.size());
    for (const auto& row : rows) out.push_back(number(row[k], file));
    return out;
}

CsvTable read_csv_table(const fs::path& file, bool growing) {
    std::ifstream whole(file);
    if (!whole) throw Error(file.string() + ": cannot read");
    std::string text{std::istreambuf_iterator<char>(whole), std::istreambuf_iterator<char>()};
    if (growing) text.erase(text.find_last_of('\n') + 1);  // npos + 1 = 0: no whole line yet
    std::istringstream in(text);
    CsvTable csv;
    csv.file = file;
    std::string line;
    std::size_t line_number = 0;
    while (std::getline(in, line)) {
        ++line_number;
        if (line.empty() || line.front() == '#') continue;
        if (csv.header.empty()) {
            csv.header = split(line);
            continue;
        }
        csv.rows.push_back(split(line));
        if (csv.rows.back().size() != csv.header.size())
            throw Error(file.string() + ": line " + std::to_string(line_number) + " has " +
                        std::to_string(csv.rows.back().size()) + " cells, the header " +
                        std::to_string(csv.header.size()));
    }
    if (csv.header.empty()) throw Error(file.string() + ": empty (no header line)");
    return csv;
}

}  // namespace tumble::io
