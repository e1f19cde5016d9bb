// SPDX-License-Identifier: MIT
#include "io/particle_csv.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <string_view>

#include <fmt/format.h>

#include "io/config.hpp"
#include "io/names.hpp"

namespace tumble::io {

namespace {

enum Column { X, Y, Z, VX, VY, VZ, WX, WY, WZ, RADIUS, MATERIAL, MOTION, TAG, COLUMN_COUNT };
constexpr std::array<std::string_view, COLUMN_COUNT> column_names{"x",  "y",  "z",      "vx",       "vy",
                                                                  "vz", "wx", "wy",     "wz",       "radius",
                                                                  "material", "motion", "tag"};

std::string_view trim(std::string_view s) {
    const auto first = s.find_first_not_of(" \t");
    if (first == std::string_view::npos) return {};
    const auto last = s.find_last_not_of(" \t");
    return s.substr(first, last - first + 1);
}

std::vector<std::string_view> split(std::string_view line) {
    std::vector<std::string_view> fields;
    std::size_t start = 0;
    for (;;) {
        const std::size_t comma = line.find(',', start);
        fields.push_back(trim(line.substr(start, comma == std::string_view::npos ? std::string_view::npos
                                                                                 : comma - start)));
        if (comma == std::string_view::npos) return fields;
        start = comma + 1;
    }
}

// Reads one line (without its '\n') of at most `limit` bytes; false at the
// end of the file. A longer line (a binary or corrupted file) is refused
// before it fills the memory.
bool read_line(std::istream& in, std::string& line, std::size_t limit, std::size_t number,
               const std::filesystem::path& file) {
    line.clear();
    for (int c = in.get(); c != std::char_traits<char>::eof(); c = in.get()) {
        if (c == '\n') return true;
        if (line.size() == limit)
            throw ConfigError(file, "line " + std::to_string(number),
                              "longer than " + std::to_string(limit) + " bytes (not a particle CSV file?)");
        line.push_back(static_cast<char>(c));
    }
    return !line.empty();
}

// A cell for a message: bytes that are not printable ASCII as \xNN.
std::string printable(std::string_view text) {
    std::string out;
    for (unsigned char c : text)
        out += (c >= 0x20 && c < 0x7f) ? std::string(1, static_cast<char>(c)) : fmt::format("\\x{:02x}", c);
    return out;
}

class CsvReader {
public:
    explicit CsvReader(const std::filesystem::path& file) : file_(file) {}

    [[noreturn]] void fail(std::size_t line, std::string_view column, const std::string& reason) const {
        std::string key = "line " + std::to_string(line);
        if (!column.empty()) key += ", column " + std::string(column);
        throw ConfigError(file_, std::move(key), reason);
    }

    double number(std::string_view text, std::size_t line, Column c) const {
        std::string_view digits = text;
        if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
        double value = 0.0;
        const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
        if (ec != std::errc() || end != digits.data() + digits.size())
            fail(line, column_names[c], "expected a number, got \"" + printable(text) + "\"");
        if (!std::isfinite(value)) fail(line, column_names[c], "must be finite, got \"" + std::string(text) + "\"");
        return value;
    }

    std::int32_t integer(std::string_view text, std::size_t line, Column c) const {
        std::string_view digits = text;
        if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
        long long value = 0;
        const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
        if (ec != std::errc() || end != digits.data() + digits.size())
            fail(line, column_names[c], "expected an integer, got \"" + printable(text) + "\"");
        if (value < std::numeric_limits<std::int32_t>::min() || value > std::numeric_limits<std::int32_t>::max())
            fail(line, column_names[c], "integer out of range: " + std::string(text));
        return static_cast<std::int32_t>(value);
    }

private:
    std::filesystem::path file_;
};

}  // namespace

std::vector<ParticleSpec> read_particle_csv(const std::filesystem::path& file, const std::vector<Material>& materials,
                                            const std::vector<std::string>& motion_names, const CsvDefaults& defaults,
                                            std::vector<std::size_t>* line_numbers) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw ConfigError(file, "", "cannot open the particle file");
    const CsvReader reader(file);

    std::vector<std::string> material_names;
    for (const Material& m : materials) material_names.push_back(m.name);

    // Header: which field holds which column (-1: absent).
    std::array<int, COLUMN_COUNT> field_of;
    field_of.fill(-1);
    std::size_t header_fields = 0;
    std::vector<ParticleSpec> out;
    if (line_numbers) line_numbers->clear();

    std::string raw;
    std::size_t line = 0;
    bool have_header = false;
    constexpr std::size_t max_line = 4096;  // bytes; a row of 14 numbers needs under 400
    while (read_line(in, raw, max_line, line + 1, file)) {
        ++line;
        std::string_view text = raw;
        if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
        if (trim(text).empty() || trim(text).front() == '#') continue;
        const std::vector<std::string_view> fields = split(text);

        if (!have_header) {
            have_header = true;
            header_fields = fields.size();
            for (std::size_t f = 0; f < fields.size(); ++f) {
                const std::string name(fields[f]);
                int c = 0;
                while (c < COLUMN_COUNT && column_names[c] != name) ++c;
                if (c == COLUMN_COUNT) {
                    const std::vector<std::string> known(column_names.begin(), column_names.end());
                    reader.fail(line, "", "unknown column \"" + name + "\" in the header" +
                                              detail::did_you_mean(name, known) +
                                              "; known columns: " + detail::quoted_list(known));
                }
                if (field_of[c] >= 0) reader.fail(line, "", "column \"" + name + "\" appears twice in the header");
                field_of[c] = static_cast<int>(f);
            }
            for (Column c : {X, Y, Z})
                if (field_of[c] < 0)
                    reader.fail(line, "", "the header has no column \"" + std::string(column_names[c]) +
                                              "\" (x, y and z are required)");
            if (field_of[MATERIAL] < 0 && !defaults.material)
                reader.fail(line, "",
                            "the header has no column \"material\" (required unless the [[particles]] block "
                            "names a material)");
            continue;
        }

        if (fields.size() != header_fields)
            reader.fail(line, "", "expected " + std::to_string(header_fields) + " fields as in the header, found " +
                                      std::to_string(fields.size()));
        auto cell = [&](Column c) -> std::string_view { return field_of[c] < 0 ? std::string_view{} : fields[field_of[c]]; };

        ParticleSpec p;
        for (Column c : {X, Y, Z})
            if (cell(c).empty()) reader.fail(line, column_names[c], "missing value (positions are required)");
        p.position = {reader.number(cell(X), line, X), reader.number(cell(Y), line, Y),
                      reader.number(cell(Z), line, Z)};
        p.velocity = defaults.velocity;
        p.angular_velocity = defaults.angular_velocity;
        for (int k = 0; k < 3; ++k) {
            const auto v = static_cast<Column>(VX + k), w = static_cast<Column>(WX + k);
            if (!cell(v).empty()) p.velocity[k] = reader.number(cell(v), line, v);
            if (!cell(w).empty()) p.angular_velocity[k] = reader.number(cell(w), line, w);
        }

        if (const std::string_view name = cell(MATERIAL); !name.empty()) {
            const auto found = std::find(material_names.begin(), material_names.end(), name);
            if (found == material_names.end())
                reader.fail(line, "material", "unknown material \"" + std::string(name) + "\"" +
                                                  detail::did_you_mean(name, material_names) +
                                                  "; known materials: " + detail::quoted_list(material_names));
            p.material = static_cast<std::int32_t>(found - material_names.begin());
        } else if (defaults.material) {
            p.material = *defaults.material;
        } else {
            reader.fail(line, "material", "missing value (no default material is given)");
        }

        p.motion = defaults.motion;
        if (const std::string_view name = cell(MOTION); !name.empty()) {
            const auto found = std::find(motion_names.begin(), motion_names.end(), name);
            if (found == motion_names.end())
                reader.fail(line, "motion", "unknown motion \"" + std::string(name) + "\"" +
                                                detail::did_you_mean(name, motion_names) +
                                                "; known motions: " + detail::quoted_list(motion_names));
            p.motion = static_cast<std::int32_t>(found - motion_names.begin());
        }

        p.radius = defaults.radius ? *defaults.radius : materials[static_cast<std::size_t>(p.material)].radius;
        if (!cell(RADIUS).empty()) {
            p.radius = reader.number(cell(RADIUS), line, RADIUS);
            if (!(p.radius > 0.0)) reader.fail(line, "radius", "must be > 0, got " + std::string(cell(RADIUS)));
        }

        p.tag = cell(TAG).empty() ? defaults.tag : reader.integer(cell(TAG), line, TAG);
        if (out.size() == max_scenario_particles)
            reader.fail(line, "", "more than " + std::to_string(max_scenario_particles) + " particles");
        out.push_back(p);
        if (line_numbers) line_numbers->push_back(line);
    }
    if (in.bad()) throw ConfigError(file, "", "read error");
    if (!have_header) throw ConfigError(file, "", "empty file: a header line and at least one particle are required");
    if (out.empty()) throw ConfigError(file, "", "no particles (only a header)");
    return out;
}

}  // namespace tumble::io
