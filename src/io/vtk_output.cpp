// SPDX-License-Identifier: MIT
#include "io/vtk_output.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <numeric>
#include <span>
#include <string_view>
#include <type_traits>

#include <zlib.h>

#include <fmt/format.h>

#include "io/fields_output.hpp"
#include "io/output.hpp"
#include "tumble/core/error.hpp"
#include "tumble/sim/contact_network.hpp"

namespace tumble::io {

namespace fs = std::filesystem;

namespace {

using Buffer = fmt::memory_buffer;

// The VTK name of the element type of an array.
template <class T>
constexpr std::string_view vtk_type() {
    if constexpr (std::is_same_v<T, double>) return "Float64";
    else if constexpr (std::is_same_v<T, std::int64_t>) return "Int64";
    else if constexpr (std::is_same_v<T, std::int32_t>) return "Int32";
    else {
        static_assert(std::is_same_v<T, std::uint8_t>);
        return "UInt8";
    }
}

std::vector<double> components(const std::vector<Vec3>& values) {
    std::vector<double> out;
    out.reserve(3 * values.size());
    for (const Vec3& v : values) out.insert(out.end(), {v.x, v.y, v.z});
    return out;
}

// Blocks of this many bytes are compressed one by one (VTK's own default).
constexpr std::size_t block_size = 32768;

void put_uint64(std::string& out, std::uint64_t v) { out.append(reinterpret_cast<const char*>(&v), sizeof v); }

// A VTK XML file (version 1.0, UInt64 headers) with its data appended in
// binary, each array compressed as vtkZLibDataCompressor reads it: its bytes
// cut into blocks of block_size (the last one may be shorter), each block
// deflated by zlib, preceded by the header [number of blocks][block size]
// [size of the last block if it is shorter, else 0][compressed size of each
// block]. Each <DataArray> names the offset of its header in the appended
// data, counted from the byte after the '_' that opens it.
class VtkFile {
public:
    // attributes: of the dataset's element (ImageData's extent, origin, spacing).
    explicit VtkFile(std::string_view type, std::string_view attributes = {}) : type_(type) {
        fmt::format_to(fmt::appender(xml_),
                       "<?xml version=\"1.0\"?>\n"
                       "<VTKFile type=\"{0}\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\" "
                       "compressor=\"vtkZLibDataCompressor\">\n"
                       "  <{0}{1}>\n",
                       type_, attributes);
    }

    // XML text between the arrays (elements opened and closed).
    void text(std::string_view xml) { xml_.append(xml); }

    // A <DataArray> of `values`, `components` per tuple.
    template <class T>
    void array(std::string_view name, std::span<const T> values, int components = 1) {
        data_array(8, vtk_type<T>(), name, fmt::format("NumberOfComponents=\"{}\"", components), bytes_of(values));
    }
    template <class T>
    void array(std::string_view name, const std::vector<T>& values, int components = 1) {
        array(name, std::span<const T>(values), components);
    }

    // A <DataArray> of one value per tuple, in FieldData.
    template <class T>
    void field(std::string_view name, const std::vector<T>& values) {
        data_array(6, vtk_type<T>(), name, fmt::format("NumberOfTuples=\"{}\"", values.size()),
                   bytes_of(std::span<const T>(values)));
    }

    // A String <DataArray> in FieldData: each string followed by a zero byte.
    void strings(std::string_view name, const std::vector<std::string>& values) {
        std::string bytes;
        for (const std::string& v : values) bytes.append(v).push_back('\0');
        data_array(6, "String", name, fmt::format("NumberOfTuples=\"{}\"", values.size()), bytes);
    }

    // Closes the dataset and writes the XML, then the appended data.
    void write(const fs::path& file) {
        fmt::format_to(fmt::appender(xml_), "    </Piece>\n  </{}>\n  <AppendedData encoding=\"raw\">\n   _", type_);
        const std::string_view parts[] = {{xml_.data(), xml_.size()}, appended_, "\n  </AppendedData>\n</VTKFile>\n"};
        write_file_whole(file, parts);
    }

private:
    template <class T>
    static std::string_view bytes_of(std::span<const T> values) {
        return {reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T)};
    }

    // The element, indented by `indent`, and its data compressed into the appended data.
    void data_array(int indent, std::string_view type, std::string_view name, const std::string& size,
                    std::string_view bytes) {
        fmt::format_to(fmt::appender(xml_),
                       "{:{}}<DataArray type=\"{}\" Name=\"{}\" {} format=\"appended\" offset=\"{}\"/>\n", "", indent,
                       type, name, size, appended_.size());
        append(bytes);
    }

    void append(std::string_view raw) {
        const std::size_t blocks = (raw.size() + block_size - 1) / block_size;
        put_uint64(appended_, blocks);
        put_uint64(appended_, block_size);
        put_uint64(appended_, raw.size() % block_size);
        const std::size_t sizes_at = appended_.size();
        appended_.append(blocks * sizeof(std::uint64_t), '\0');
        for (std::size_t b = 0; b < blocks; ++b) {
            const std::string_view block = raw.substr(b * block_size, block_size);
            uLongf packed = compressBound(static_cast<uLong>(block.size()));
            const std::size_t at = appended_.size();
            appended_.resize(at + packed);
            // zlib's fastest level: the particles' doubles barely compress
            // at any level, and the default one took 2 % of a drum run for
            // 1 % smaller files (studies/performance/LOG.md, "Time by phase").
            if (compress2(reinterpret_cast<Bytef*>(&appended_[at]), &packed,
                          reinterpret_cast<const Bytef*>(block.data()), static_cast<uLong>(block.size()),
                          Z_BEST_SPEED) != Z_OK)
                throw Error("zlib could not compress a block of a VTK array");
            appended_.resize(at + packed);
            const std::uint64_t size = packed;
            std::memcpy(&appended_[sizes_at + b * sizeof size], &size, sizeof size);
        }
    }

    std::string type_;
    Buffer xml_;
    std::string appended_;
};

// The time of the state, which ParaView reads from FieldData "TimeValue",
// and the step.
void time_field(VtkFile& f, const SnapshotData& snapshot) {
    f.field("TimeValue", std::vector<double>{snapshot.time});
    f.field("step", std::vector<std::int64_t>{snapshot.step});
}


// Escapes the five characters XML reserves, for an attribute value.
std::string xml_attribute(std::string_view s) {
    std::string out;
    for (char c : s) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&apos;"; break;
            default: out += c;
        }
    }
    return out;
}

}  // namespace

void write_vtu_snapshot(const fs::path& file, const Simulation& sim) { write_vtu_snapshot(file, snapshot_of(sim)); }

void write_vtu_snapshot(const fs::path& file, const SnapshotData& snapshot) {
    const ParticleStore& p = snapshot.particles;
    const std::vector<std::size_t> by_id = order_by_id(p);
    const std::vector<std::uint32_t>& counts = snapshot.contacts;
    const std::size_t n = p.size();

    std::vector<Vec3> position(n), velocity(n), angular_velocity(n);
    std::vector<double> radius(n);
    std::vector<std::int64_t> id(n);
    std::vector<std::int32_t> material(n), tag(n), contacts(n);
    std::vector<std::uint8_t> kinematic(n);
    for (std::size_t row = 0; row < n; ++row) {
        const std::size_t i = by_id[row];
        position[row] = p.position[i];
        velocity[row] = p.velocity[i];
        angular_velocity[row] = p.angular_velocity[i];
        radius[row] = p.radius[i];
        id[row] = p.id[i];
        material[row] = p.material[i];
        tag[row] = p.tag[i];
        kinematic[row] = p.is_kinematic(i) ? 1 : 0;
        contacts[row] = static_cast<std::int32_t>(counts[static_cast<std::size_t>(p.id[i])]);
    }
    // Cell k is the vertex at point k: connectivity k, end offset k + 1,
    // type 1 (VTK_VERTEX).
    std::vector<std::int64_t> connectivity(n), offsets(n);
    std::iota(connectivity.begin(), connectivity.end(), std::int64_t{0});
    std::iota(offsets.begin(), offsets.end(), std::int64_t{1});
    const std::vector<std::uint8_t> types(n, 1);

    VtkFile f("UnstructuredGrid");
    f.text("    <FieldData>\n");
    time_field(f, snapshot);
    f.strings("material_names", snapshot.material_names);
    f.text(fmt::format("    </FieldData>\n    <Piece NumberOfPoints=\"{0}\" NumberOfCells=\"{0}\">\n", n));
    f.text("      <PointData Scalars=\"radius\" Vectors=\"velocity\">\n");
    f.array("id", id);
    f.array("velocity", components(velocity), 3);
    f.array("angular_velocity", components(angular_velocity), 3);
    f.array("radius", radius);
    f.array("material", material);
    f.array("tag", tag);
    f.array("kinematic", kinematic);
    f.array("contacts", contacts);
    f.text("      </PointData>\n      <Points>\n");
    f.array("position", components(position), 3);
    f.text("      </Points>\n      <Cells>\n");
    f.array("connectivity", connectivity);
    f.array("offsets", offsets);
    f.array("types", types);
    f.text("      </Cells>\n");
    f.write(file);
}

void write_vtp_contact_network(const fs::path& file, const Simulation& sim) {
    write_vtp_contact_network(file, snapshot_of(sim));
}

void write_vtp_contact_network(const fs::path& file, const SnapshotData& snapshot) {
    const std::vector<ContactLink>& links = snapshot.links;
    const ParticleStore& p = snapshot.particles;
    // Array index of each global id, to find the centre of i.
    std::vector<std::size_t> index_of(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) index_of[static_cast<std::size_t>(p.id[i])] = i;

    const std::size_t n = links.size();
    std::vector<Vec3> ends(2 * n), normal(n);
    std::vector<std::int64_t> id_i(n), id_j(n), connectivity(2 * n), offsets(n);
    std::vector<double> normal_force(n), overlap(n);
    for (std::size_t k = 0; k < n; ++k) {
        const ContactLink& c = links[k];
        const std::size_t i = index_of[static_cast<std::size_t>(c.id_i)], j = index_of[static_cast<std::size_t>(c.id_j)];
        // Centre of i, and centre of j seen from i: X_i - (R_i + R_j - h) n.
        ends[2 * k] = p.position[i];
        ends[2 * k + 1] = p.position[i] - (p.radius[i] + p.radius[j] - c.overlap) * c.n;
        connectivity[2 * k] = static_cast<std::int64_t>(2 * k);
        connectivity[2 * k + 1] = static_cast<std::int64_t>(2 * k + 1);
        offsets[k] = static_cast<std::int64_t>(2 * k + 2);
        id_i[k] = c.id_i;
        id_j[k] = c.id_j;
        normal_force[k] = c.normal_force;
        overlap[k] = c.overlap;
        normal[k] = c.n;
    }

    VtkFile f("PolyData");
    f.text("    <FieldData>\n");
    time_field(f, snapshot);
    f.text(fmt::format("    </FieldData>\n    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"{}\" "
                       "NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n",
                       2 * n, n));
    f.text("      <CellData Scalars=\"normal_force\" Vectors=\"normal\">\n");
    f.array("id_i", id_i);
    f.array("id_j", id_j);
    f.array("normal_force", normal_force);
    f.array("overlap", overlap);
    f.array("normal", components(normal), 3);
    f.text("      </CellData>\n      <Points>\n");
    f.array("position", components(ends), 3);
    f.text("      </Points>\n      <Lines>\n");
    f.array("connectivity", connectivity);
    f.array("offsets", offsets);
    f.text("      </Lines>\n");
    f.write(file);
}

void write_vtp_walls(const fs::path& file, const SnapshotData& snapshot) {
    std::vector<Vec3> points;
    std::vector<std::int64_t> connectivity, offsets;
    std::vector<std::int32_t> wall;
    for (std::size_t k = 0; k < snapshot.walls.size(); ++k) {
        const WallSurface& s = snapshot.walls[k];
        const auto first = static_cast<std::int64_t>(points.size());
        points.insert(points.end(), s.vertices.begin(), s.vertices.end());
        for (const auto& t : s.triangles) {
            for (std::uint32_t v : t) connectivity.push_back(first + v);
            offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
            wall.push_back(static_cast<std::int32_t>(k));
        }
    }
    VtkFile f("PolyData");
    f.text("    <FieldData>\n");
    time_field(f, snapshot);
    f.strings("wall_names", snapshot.wall_names);
    f.text(fmt::format("    </FieldData>\n    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"0\" "
                       "NumberOfStrips=\"0\" NumberOfPolys=\"{}\">\n",
                       points.size(), wall.size()));
    f.text("      <CellData Scalars=\"wall\">\n");
    f.array("wall", wall);
    f.text("      </CellData>\n      <Points>\n");
    f.array("position", components(points), 3);
    f.text("      </Points>\n      <Polys>\n");
    f.array("connectivity", connectivity);
    f.array("offsets", offsets);
    f.text("      </Polys>\n");
    f.write(file);
}

void write_vti_fields(const fs::path& file, const analysis::Fields& fields) {
    const analysis::CgGrid& g = fields.grid;
    const Vec3 origin = g.node(0, 0, 0);
    const std::string extent = fmt::format("0 {} 0 {} 0 {}", g.cells[0] - 1, g.cells[1] - 1, g.cells[2] - 1);
    VtkFile f("ImageData", fmt::format(" WholeExtent=\"{}\" Origin=\"{} {} {}\" Spacing=\"{} {} {}\"", extent,
                                       origin.x, origin.y, origin.z, g.spacing(0), g.spacing(1), g.spacing(2)));
    f.text("    <FieldData>\n");
    f.field("samples", std::vector<std::int64_t>{static_cast<std::int64_t>(fields.samples)});
    f.text(fmt::format("    </FieldData>\n    <Piece Extent=\"{}\">\n", extent));
    f.text("      <PointData Scalars=\"solid_fraction\" Vectors=\"velocity\" Tensors=\"stress\">\n");
    for (const FieldColumn& c : field_columns(fields))
        f.array(c.name, c.values, static_cast<int>(c.components.size()));
    f.text("      </PointData>\n");
    f.write(file);
}

PvdIndex::PvdIndex(fs::path file) : file_(std::move(file)) { rewrite(); }

void PvdIndex::add(double time, const fs::path& dataset_relative_path) {
    entries_.emplace_back(time, dataset_relative_path.generic_string());
    rewrite();
}

// <DataSet timestep="t" part="0" file="..."/> per entry; ParaView shows the
// datasets as one time series, stepping through the distinct timesteps.
void PvdIndex::rewrite() const {
    Buffer b;
    fmt::format_to(fmt::appender(b),
                   "<?xml version=\"1.0\"?>\n"
                   "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
                   "  <Collection>\n");
    for (const auto& [time, path] : entries_)
        fmt::format_to(fmt::appender(b), "    <DataSet timestep=\"{}\" group=\"\" part=\"0\" file=\"{}\"/>\n", time,
                       xml_attribute(path));
    fmt::format_to(fmt::appender(b), "  </Collection>\n</VTKFile>\n");

    write_file_whole(file_, {b.data(), b.size()});
}

}  // namespace tumble::io
