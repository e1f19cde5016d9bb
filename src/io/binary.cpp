// SPDX-License-Identifier: MIT
#include "io/binary.hpp"

#include <algorithm>
#include <bit>

#include <zlib.h>

namespace tumble::io {

// Checkpoints are written as the machine holds numbers; the format says
// little-endian, so refuse to build where that would be a lie.
static_assert(std::endian::native == std::endian::little, "checkpoint format is little-endian");

std::uint32_t crc32(std::string_view bytes) {
    // zlib takes at most a uInt (32 bits) of bytes per call.
    uLong c = ::crc32(0L, Z_NULL, 0);
    for (std::size_t done = 0; done < bytes.size();) {
        const auto n = static_cast<uInt>(std::min<std::size_t>(bytes.size() - done, 1u << 30));
        c = ::crc32(c, reinterpret_cast<const Bytef*>(bytes.data() + done), n);
        done += n;
    }
    return static_cast<std::uint32_t>(c);
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
