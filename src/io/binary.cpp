// SPDX-License-Identifier: MIT
#include "io/binary.hpp"

#include <array>
#include <bit>

namespace tumble::io {

// Checkpoints are written as the machine holds numbers; the format says
// little-endian, so refuse to build where that would be a lie.
static_assert(std::endian::native == std::endian::little, "checkpoint format is little-endian");

std::uint32_t crc32(std::string_view bytes) {
    static const std::array<std::uint32_t, 256> table = [] {
        std::array<std::uint32_t, 256> t{};
        for (std::uint32_t n = 0; n < 256; ++n) {
            std::uint32_t c = n;
            for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            t[n] = c;
        }
        return t;
    }();
    std::uint32_t c = 0xFFFFFFFFu;
    for (unsigned char byte : bytes) c = table[(c ^ byte) & 0xFFu] ^ (c >> 8);
    return c ^ 0xFFFFFFFFu;
}

bool ByteReader::get_bool(const char* field) {
    const auto v = get<std::uint8_t>(field);
    if (v > 1) fail(std::string(field) + ": not a boolean");
    return v == 1;
}

std::string ByteReader::get_string(const char* field) {
    const std::size_t n = count(1, field);
    std::string text(bytes_.substr(at_, n));
    at_ += n;
    return text;
}

std::size_t ByteReader::count(std::size_t element_size, const char* field) {
    const auto n = get<std::uint64_t>(field);
    if (n > (bytes_.size() - at_) / element_size)
        fail(std::string(field) + ": claims " + std::to_string(n) + " elements, more than the " +
             std::to_string(bytes_.size() - at_) + " bytes left hold");
    return static_cast<std::size_t>(n);
}

void ByteReader::need(std::size_t n, const char* field) const {
    if (n > bytes_.size() - at_) fail(std::string(field) + ": the data ends early (truncated)");
}

void ByteReader::fail(const std::string& reason) const { throw Error(source_ + ": " + reason); }

}  // namespace tumble::io
