// SPDX-License-Identifier: MIT
// A CSV file read as text: a header row of column names, then rows of cells,
// split at commas (no quoting). Lines starting with '#' before the header
// and empty lines are skipped. Used to read back what tumble writes
// (drum_series.csv, profiles.csv, snapshots/NNNNNN.csv).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace tumble::io {

struct CsvTable {
    std::filesystem::path file;  // for error messages
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;

    // The index of a column; tumble::Error naming the file if there is none.
    std::size_t column(const std::string& name) const;
    // A column as numbers ("nan" allowed); tumble::Error naming the file and the cell otherwise.
    std::vector<double> numbers(const std::string& name) const;
};

// tumble::Error naming the file if it cannot be read, has no header, or a
// row has not as many cells as the header.
CsvTable read_csv_table(const std::filesystem::path& file);

}  // namespace tumble::io
