// SPDX-License-Identifier: MIT
// JSON in and out, through nlohmann/json (https://json.nlohmann.me). Every
// JSON file and line tumble writes (run.json, summary.json, tumble bench
// --json, tumble contact --json) is built as a Json value and written here,
// so any text (a file name, a material name) is escaped as JSON requires.
//
// Numbers: JSON has no NaN or infinity, so a non-finite double is written as
// null, and the readers take null for "undefined" (NaN). Keys stay in the
// order they were inserted (ordered_json).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace tumble::io {

using Json = nlohmann::ordered_json;

// The text of `value` on one line, without a newline (for --json).
std::string json_line(const Json& value);

// Writes `value` indented by two spaces per level, with a final newline,
// atomically (write_file_atomically); tumble::Error naming the file.
void write_json_file(const std::filesystem::path& file, const Json& value);

// Parses one JSON document (RFC 8259); tumble::Error "NAME: reason" with
// the line and column on malformed text.
Json parse_json(std::string_view text, const std::string& name = "json");

// A number member of an object: nullopt if the object has no such member or
// it is null; tumble::Error if it is of another type.
std::optional<double> json_number(const Json& object, std::string_view key);

}  // namespace tumble::io
