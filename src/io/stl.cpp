// SPDX-License-Identifier: MIT
#include "io/stl.hpp"

#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "io/config.hpp"
#include "io/toml_reader.hpp"

namespace tumble::io {

namespace {

namespace fs = std::filesystem;

// The triangles as read, before placement and welding; for ASCII files the
// line of each "facet" (messages name it).
struct Triangles {
    std::vector<std::array<Vec3, 3>> corners;
    std::vector<std::size_t> lines;
};

constexpr std::array<char, 3> axis_names{'x', 'y', 'z'};

bool finite(const Vec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

// x' = Rot (scale x) + offset. Rot by Rodrigues' formula, k the unit axis:
// Rot v = cos(a) v + sin(a) (k x v) + (1 - cos(a)) (k . v) k, as a matrix.
class Placement {
public:
    Placement(const StlPlacement& p, const fs::path& file)
        : scale_(p.scale), offset_(p.offset), turn_(p.rotation.has_value()) {
        if (!(p.scale > 0.0) || !std::isfinite(p.scale))
            throw ConfigError(file, "scale", fmt::format("must be a positive number, got {}", p.scale));
        if (!finite(p.offset)) throw ConfigError(file, "offset", "must be finite");
        if (!turn_) return;
        const Vec3 a = p.rotation->axis;
        const double length = norm(a);
        if (!finite(a) || !(length > 0.0) || !std::isfinite(length))
            throw ConfigError(file, "rotation", "the axis must be a finite vector of length > 0");
        if (!std::isfinite(p.rotation->angle)) throw ConfigError(file, "rotation", "the angle must be finite");
        const Vec3 k{a.x / length, a.y / length, a.z / length};
        const double c = std::cos(p.rotation->angle), s = std::sin(p.rotation->angle);
        // Row i of Rot: c e_i + s (row i of [k]x) + (1 - c) k_i k.
        const std::array<Vec3, 3> cross_rows{Vec3{0.0, -k.z, k.y}, Vec3{k.z, 0.0, -k.x}, Vec3{-k.y, k.x, 0.0}};
        for (int i = 0; i < 3; ++i) {
            Vec3 e;
            e[i] = 1.0;
            rows_[i] = c * e + s * cross_rows[i] + ((1.0 - c) * k[i]) * k;
        }
    }

    Vec3 operator()(const Vec3& x) const {
        const Vec3 v = scale_ * x;
        return turn_ ? Vec3{dot(rows_[0], v), dot(rows_[1], v), dot(rows_[2], v)} + offset_ : v + offset_;
    }

private:
    double scale_;
    Vec3 offset_;
    bool turn_;
    std::array<Vec3, 3> rows_;
};

// A word of the file for a message: its first 40 bytes, those that are not
// printable ASCII as \xNN.
std::string shown(std::string_view word) {
    std::string out = "\"";
    for (std::size_t i = 0; i < word.size() && i < 40; ++i) {
        const auto c = static_cast<unsigned char>(word[i]);
        out += (c >= 0x20 && c < 0x7f) ? std::string(1, static_cast<char>(c)) : fmt::format("\\x{:02x}", c);
    }
    return out + (word.size() > 40 ? "...\"" : "\"");
}

bool blank(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }

bool same_word(std::string_view word, std::string_view keyword) {
    if (word.size() != keyword.size()) return false;
    for (std::size_t i = 0; i < word.size(); ++i) {
        const char c = word[i];
        if ((c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c) != keyword[i]) return false;
    }
    return true;
}

// The ASCII grammar, word by word, counting lines.
class AsciiReader {
public:
    AsciiReader(std::string_view text, const fs::path& file) : text_(text), file_(file) {}

    Triangles read() {
        Triangles out;
        expect("solid");
        for (;;) {
            skip_line();  // the solid's name
            for (std::string_view word = next(); !same_word(word, "endsolid"); word = next()) {
                if (!same_word(word, "facet")) fail(word, "\"facet\" or \"endsolid\"");
                out.lines.push_back(line_);
                out.corners.push_back(facet(out.corners.size() + 1));
            }
            skip_line();  // the name after endsolid
            const std::string_view word = next();
            if (word.empty()) return out;
            if (!same_word(word, "solid")) fail(word, "\"solid\" or the end of the file after \"endsolid\"");
        }
    }

private:
    // The next word, and line_ its line; at the end of the file an empty
    // word, and line_ that of the last word.
    std::string_view next() {
        std::size_t lines = 0;
        while (at_ < text_.size() && blank(text_[at_])) lines += text_[at_++] == '\n';
        if (at_ == text_.size()) return {};
        line_ += lines;
        const std::size_t begin = at_;
        while (at_ < text_.size() && !blank(text_[at_])) ++at_;
        return text_.substr(begin, at_ - begin);
    }
    void skip_line() {
        while (at_ < text_.size() && text_[at_] != '\n') ++at_;
    }
    [[noreturn]] void fail(std::string_view word, const std::string& expected) const {
        throw ConfigError(file_, "line " + std::to_string(line_),
                          "expected " + expected + ", found " + (word.empty() ? "the end of the file" : shown(word)));
    }
    void expect(std::string_view keyword) {
        const std::string_view word = next();
        if (!same_word(word, keyword)) fail(word, fmt::format("\"{}\"", keyword));
    }
    // A number: coordinate `axis` of corner `corner` (1 to 3; 0: the normal).
    double number(int corner, int axis) {
        const std::string_view word = next();
        std::string_view digits = word;
        if (digits.size() > 1 && digits[0] == '+' && digits[1] != '-' && digits[1] != '+') digits.remove_prefix(1);
        double value = 0.0;
        const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
        if (digits.empty() || end != digits.data() + digits.size())
            fail(word, corner == 0 ? fmt::format("a number (the normal's {})", axis_names[axis])
                                   : fmt::format("a number ({} of corner {})", axis_names[axis], corner));
        // Beyond the doubles: +-HUGE_VAL (refused as not finite) or, below
        // the smallest, about 0, as strtod rounds them.
        if (error == std::errc::result_out_of_range) value = std::strtod(std::string(digits).c_str(), nullptr);
        return value;
    }
    std::array<Vec3, 3> facet(std::size_t triangle) {
        expect("normal");
        for (int a = 0; a < 3; ++a) number(0, a);
        expect("outer");
        expect("loop");
        std::array<Vec3, 3> corners;
        for (int j = 0; j < 3; ++j) {
            expect("vertex");
            for (int a = 0; a < 3; ++a) {
                corners[j][a] = number(j + 1, a);
                if (!std::isfinite(corners[j][a]))
                    throw ConfigError(file_, "line " + std::to_string(line_),
                                      fmt::format("triangle {}, corner {}: {} is not a finite number", triangle, j + 1,
                                                  axis_names[a]));
            }
        }
        expect("endloop");
        expect("endfacet");
        return corners;
    }

    std::string_view text_;
    const fs::path& file_;
    std::size_t at_ = 0;
    std::size_t line_ = 1;
};

float little_endian_float(const char* bytes) {
    std::uint32_t bits = 0;
    for (int i = 3; i >= 0; --i) bits = (bits << 8) | static_cast<unsigned char>(bytes[i]);
    return std::bit_cast<float>(bits);
}

std::uint32_t little_endian_count(std::string_view text) {
    std::uint32_t n = 0;
    for (int i = 83; i >= 80; --i) n = (n << 8) | static_cast<unsigned char>(text[i]);
    return n;
}

Triangles read_binary(std::string_view text, const fs::path& file) {
    if (text.size() < 84)
        throw ConfigError(file, "",
                          fmt::format("{} bytes: too short for a binary STL (84 bytes of header and count), and no "
                                      "ASCII STL (that begins with \"solid\")",
                                      text.size()));
    const std::uint64_t n = little_endian_count(text);
    const std::uint64_t size = 84 + 50 * n;
    if (text.size() < size)
        throw ConfigError(file, fmt::format("triangle {}", (text.size() - 84) / 50 + 1),
                          fmt::format("truncated: the file ends after {} bytes, the {} triangles its header announces "
                                      "need 84 + 50 x {} = {}",
                                      text.size(), n, n, size));
    if (text.size() > size)
        throw ConfigError(file, "",
                          fmt::format("the header announces {} triangles, 84 + 50 x {} = {} bytes, but the file has {} "
                                      "bytes (not a binary STL, or a wrong count)",
                                      n, n, size, text.size()));
    Triangles out;
    out.corners.resize(n);
    for (std::size_t t = 0; t < n; ++t) {
        const char* record = text.data() + 84 + 50 * t + 12;  // after the normal
        for (int j = 0; j < 3; ++j)
            for (int a = 0; a < 3; ++a) {
                out.corners[t][j][a] = little_endian_float(record + 12 * j + 4 * a);
                if (!std::isfinite(out.corners[t][j][a]))
                    throw ConfigError(file, fmt::format("triangle {}", t + 1),
                                      fmt::format("corner {}: {} is not a finite number ({})", j + 1, axis_names[a],
                                                  out.corners[t][j][a]));
            }
    }
    return out;
}

// "solid" at the start (after blanks), in any case.
bool begins_solid(std::string_view text) {
    std::size_t i = 0;
    while (i < text.size() && blank(text[i])) ++i;
    return text.size() - i >= 5 && same_word(text.substr(i, 5), "solid");
}

// An ASCII file by its start: "solid ..." and then "facet" or "endsolid" as
// the first word of the lines after.
bool ascii_start(std::string_view text) {
    if (!begins_solid(text)) return false;
    std::size_t i = text.find('\n');
    if (i == std::string_view::npos) return false;
    while (i < text.size() && blank(text[i])) ++i;
    std::size_t end = i;
    while (end < text.size() && !blank(text[end])) ++end;
    const std::string_view word = text.substr(i, end - i);
    return same_word(word, "facet") || same_word(word, "endsolid");
}

bool text_only(std::string_view text) {
    for (char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        if (!(blank(ch) || (c >= 0x20 && c < 0x7f))) return false;
    }
    return true;
}

bool binary_size(std::string_view text) {
    return text.size() >= 84 && text.size() == 84 + 50 * std::uint64_t{little_endian_count(text)};
}

}  // namespace

TriangleMesh read_stl(const fs::path& file, const StlPlacement& placement) {
    const Placement place(placement, file);
    const std::string text = read_text_file(file, max_stl_file_bytes);
    const bool ascii = ascii_start(text) || (!binary_size(text) && begins_solid(text) && text_only(text));
    Triangles triangles = ascii ? AsciiReader(text, file).read() : read_binary(text, file);
    if (triangles.corners.empty()) throw ConfigError(file, "", "no triangles");

    for (auto& corners : triangles.corners)
        for (Vec3& x : corners) x = place(x);
    TriangleMesh mesh = weld_triangles(triangles.corners);
    try {
        check_mesh(mesh);
    } catch (const MeshError& e) {
        std::string where = "triangle " + std::to_string(e.triangle() + 1);
        if (ascii) where += " (line " + std::to_string(triangles.lines[e.triangle()]) + ")";
        throw ConfigError(file, std::move(where), e.reason());
    }
    return mesh;
}

}  // namespace tumble::io
