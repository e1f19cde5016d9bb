// SPDX-License-Identifier: MIT
// Little-endian binary encoding for checkpoints: a writer that appends
// values to a byte string and a reader that takes them back out, checking
// every length against the bytes that remain (so a damaged or hostile file
// can neither read past its end nor make the reader allocate more than the
// file holds). Also the CRC-32 checksum (IEEE 802.3, as PNG), computed by
// zlib.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "tumble/core/error.hpp"

namespace tumble::io {

std::uint32_t crc32(std::string_view bytes);

class ByteWriter {
public:
    // A value as it lies in memory: numbers, or structs of them without
    // padding (padding bytes are undefined and would make two files of the
    // same state differ).
    template <class T>
    void put(const T& value) {
        static_assert(std::is_trivially_copyable_v<T>);
        bytes_.append(reinterpret_cast<const char*>(&value), sizeof(T));
    }
    void put(bool value) { put(static_cast<std::uint8_t>(value)); }
    void put(const std::string& text) {
        put(static_cast<std::uint64_t>(text.size()));
        bytes_ += text;
    }
    // A count, then the elements as they lie in memory (as put()).
    template <class T>
    void put_array(const std::vector<T>& values) {
        static_assert(std::is_trivially_copyable_v<T>);
        put(static_cast<std::uint64_t>(values.size()));
        bytes_.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
    }
    const std::string& bytes() const { return bytes_; }
    std::string take() { return std::move(bytes_); }

private:
    std::string bytes_;
};

// Reads what a ByteWriter wrote; any shortfall throws tumble::Error naming
// `source` and the field being read.
class ByteReader {
public:
    ByteReader(std::string_view bytes, std::string source) : bytes_(bytes), source_(std::move(source)) {}

    template <class T>
    T get(const char* field) {
        static_assert(std::is_trivially_copyable_v<T>);
        need(sizeof(T), field);
        T value;
        std::memcpy(&value, bytes_.data() + at_, sizeof(T));
        at_ += sizeof(T);
        return value;
    }
    bool get_bool(const char* field);
    std::string get_string(const char* field);
    template <class T>
    std::vector<T> get_array(const char* field) {
        const std::size_t n = count(sizeof(T), field);
        std::vector<T> values(n);
        // An empty vector may have no storage, and memcpy from or to a null
        // pointer is undefined even for 0 bytes (scripts/fuzz.sh found it).
        if (n > 0) std::memcpy(values.data(), bytes_.data() + at_, n * sizeof(T));
        at_ += n * sizeof(T);
        return values;
    }
    // A count of elements of at least `element_size` bytes each, checked
    // against what remains.
    std::size_t count(std::size_t element_size, const char* field);
    bool at_end() const { return at_ == bytes_.size(); }
    [[noreturn]] void fail(const std::string& reason) const;

private:
    void need(std::size_t n, const char* field) const;

    std::string_view bytes_;
    std::string source_;
    std::size_t at_ = 0;
};

}  // namespace tumble::io
