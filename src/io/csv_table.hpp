// SPDX-License-Identifier: MIT
// The CSV files tumble writes load with standard readers as they are
// (numpy.genfromtxt(names=True), pandas.read_csv): the first line is the
// header, column names hold only letters, digits and '_', and there are no
// comment lines.
//
// Reading: a CSV file as text, a header row of column names, then rows of
// cells, split at commas (no quoting). Lines starting with '#' before the
// header (older snapshots) and empty lines are skipped. Used to read back
// what tumble writes (drum_series.csv, profiles.csv, snapshots/NNNNNN.csv).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace tumble::io {

// A name (of a material, a component) as part of a column name: every
// character but a letter, a digit or '_' becomes '_' ("material-1" ->
// "material_1"), as numpy.genfromtxt(names=True) would otherwise drop it.
std::string column_name(std::string_view name);

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
// row has not as many cells as the header. growing: a file another process
// is appending to (a run going on): a last line without its newline, half
// written, is left out.
CsvTable read_csv_table(const std::filesystem::path& file, bool growing = false);

}  // namespace tumble::io
