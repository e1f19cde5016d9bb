// SPDX-License-Identifier: MIT
#include "io/vtk_input.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>
#include <vector>

#include <zlib.h>

#include "tumble/core/error.hpp"

namespace tumble::io {

namespace fs = std::filesystem;

namespace {

// A walls file holds a few thousand triangles; anything this large is not one.
constexpr std::uintmax_t max_walls_file_bytes = std::uintmax_t{256} << 20;

// The value of attribute `name` in the XML element `tag` (name="value"), or
// empty if it has none.
std::string_view attribute(std::string_view tag, std::string_view name) {
    std::string key(" ");
    key.append(name).append("=\"");
    const std::size_t at = tag.find(key);
    if (at == std::string_view::npos) return {};
    const std::size_t from = at + key.size(), to = tag.find('"', from);
    return to == std::string_view::npos ? std::string_view{} : tag.substr(from, to - from);
}

class VtpReader {
public:
    explicit VtpReader(const fs::path& file) : file_(file) {
        std::error_code ec;
        const std::uintmax_t size = fs::file_size(file, ec);
        if (ec) fail("cannot read it: " + ec.message());
        if (size > max_walls_file_bytes) fail("too large for a walls file");
        std::ifstream in(file, std::ios::binary);
        bytes_.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
        if (!in && !in.eof()) fail("cannot read it");
        // The XML ends where the appended data begins: after the '_' that follows <AppendedData ...>.
        const std::size_t appended = bytes_.find("<AppendedData");
        const std::size_t underscore = appended == std::string::npos ? appended : bytes_.find('_', appended);
        if (underscore == std::string::npos) fail("no appended data");
        xml_ = std::string_view(bytes_).substr(0, appended);
        data_ = underscore + 1;
        const std::size_t head_end = xml_.find('>', xml_.find("<VTKFile"));
        const std::string_view head = xml_.substr(0, head_end);
        if (attribute(head, "type") != "PolyData" || attribute(head, "header_type") != "UInt64" ||
            attribute(head, "compressor") != "vtkZLibDataCompressor")
            fail("not VTK PolyData with UInt64 headers compressed by zlib, as tumble writes its walls");
    }

    // The values of the <DataArray> named `name`, of VTK type `type` (C++ type T).
    template <class T>
    std::vector<T> array(std::string_view name, std::string_view type) const {
        const std::string key = "Name=\"" + std::string(name) + "\"";
        const std::size_t at = xml_.find(key);
        if (at == std::string_view::npos) fail("no array \"" + std::string(name) + "\"");
        const std::size_t open = xml_.rfind('<', at), close = xml_.find('>', at);
        const std::string_view tag = xml_.substr(open, close - open);
        if (attribute(tag, "type") != type) fail("array \"" + std::string(name) + "\" is not " + std::string(type));
        const std::string_view offset = attribute(tag, "offset");
        const char* end = offset.data() + offset.size();
        std::uint64_t at_byte = 0;
        if (offset.empty() || std::from_chars(offset.data(), end, at_byte).ptr != end)
            fail("array \"" + std::string(name) + "\" has no offset");
        const std::string raw = inflate(at_byte);
        if (raw.size() % sizeof(T) != 0) fail("array \"" + std::string(name) + "\" has a partial value");
        std::vector<T> values(raw.size() / sizeof(T));
        std::memcpy(values.data(), raw.data(), raw.size());
        return values;
    }

    [[noreturn]] void fail(const std::string& why) const { throw Error(file_.string() + ": " + why); }

private:
    std::uint64_t uint64_at(std::size_t at) const {
        if (at + sizeof(std::uint64_t) > bytes_.size()) fail("appended data cut short");
        std::uint64_t v = 0;
        std::memcpy(&v, &bytes_[at], sizeof v);
        return v;
    }

    // The bytes of the array whose header is `offset` bytes into the
    // appended data: [blocks][block size][last block size, 0 if full]
    // [compressed size of each block], then the blocks, each deflated.
    std::string inflate(std::uint64_t offset) const {
        std::size_t at = data_ + offset;
        const std::uint64_t blocks = uint64_at(at), block = uint64_at(at + 8), last = uint64_at(at + 16);
        if (blocks > bytes_.size() || block > max_walls_file_bytes) fail("a broken array header");
        std::size_t packed_at = at + 24 + blocks * 8;
        std::string out;
        for (std::uint64_t b = 0; b < blocks; ++b) {
            const std::uint64_t packed = uint64_at(at + 24 + b * 8);
            const std::uint64_t size = b + 1 == blocks && last != 0 ? last : block;
            if (packed > bytes_.size() - std::min(bytes_.size(), packed_at)) fail("appended data cut short");
            const std::size_t start = out.size();
            out.resize(start + size);
            uLongf unpacked = static_cast<uLongf>(size);
            if (uncompress(reinterpret_cast<Bytef*>(&out[start]), &unpacked,
                           reinterpret_cast<const Bytef*>(&bytes_[packed_at]), static_cast<uLong>(packed)) != Z_OK ||
                unpacked != size)
                fail("a block of an array does not inflate");
            packed_at += packed;
        }
        return out;
    }

    fs::path file_;
    std::string bytes_;
    std::string_view xml_;
    std::size_t data_ = 0;  // where the appended data begins, bytes into the file
};

}  // namespace

WallSurface read_vtp_walls(const fs::path& file) {
    const VtpReader vtp(file);
    const std::vector<double> position = vtp.array<double>("position", "Float64");
    const std::vector<std::int64_t> connectivity = vtp.array<std::int64_t>("connectivity", "Int64");
    const std::vector<std::int64_t> offsets = vtp.array<std::int64_t>("offsets", "Int64");
    WallSurface s;
    if (position.size() % 3 != 0) vtp.fail("points of fewer than 3 coordinates");
    for (std::size_t k = 0; k + 2 < position.size(); k += 3)
        s.vertices.push_back({position[k], position[k + 1], position[k + 2]});
    // Polygon k is connectivity[offsets[k - 1], offsets[k]); tumble writes triangles only.
    std::int64_t begin = 0;
    for (const std::int64_t end : offsets) {
        if (end - begin != 3 || end > static_cast<std::int64_t>(connectivity.size()))
            vtp.fail("a polygon that is not a triangle");
        std::array<std::uint32_t, 3> t{};
        for (int c = 0; c < 3; ++c) {
            const std::int64_t v = connectivity[static_cast<std::size_t>(begin + c)];
            if (v < 0 || v >= static_cast<std::int64_t>(s.vertices.size())) vtp.fail("a triangle's point is missing");
            t[static_cast<std::size_t>(c)] = static_cast<std::uint32_t>(v);
        }
        s.triangles.push_back(t);
        begin = end;
    }
    return s;
}

}  // namespace tumble::io
