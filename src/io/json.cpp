// SPDX-License-Identifier: MIT
#include "io/json.hpp"

#include "io/output.hpp"
#include "tumble/core/error.hpp"

namespace tumble::io {

namespace {

// Text that is not UTF-8 (a file name can be any bytes) is written with
// U+FFFD in place of each bad byte rather than refused.
std::string dump(const Json& value, int indent) {
    return value.dump(indent, ' ', false, Json::error_handler_t::replace);
}

}  // namespace

std::string json_line(const Json& value) { return dump(value, -1); }

void write_json_file(const std::filesystem::path& file, const Json& value) {
    write_file_atomically(file, dump(value, 2) + '\n');
}

Json parse_json(std::string_view text, const std::string& name) {
    try {
        return Json::parse(text);
    } catch (const Json::exception& e) {
        // what() is "[json.exception.parse_error.101] parse error at line L, column C: ..."
        const std::string what = e.what();
        const std::size_t tag_end = what.find("] ");
        throw Error(name + ": " + (tag_end == std::string::npos ? what : what.substr(tag_end + 2)));
    }
}

std::optional<double> json_number(const Json& object, std::string_view key) {
    const auto it = object.find(std::string(key));
    if (it == object.end() || it->is_null()) return std::nullopt;
    if (!it->is_number()) throw Error("json: \"" + std::string(key) + "\" is not a number");
    return it->get<double>();
}

}  // namespace tumble::io
