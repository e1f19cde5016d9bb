// SPDX-License-Identifier: MIT
#include "io/vtk_output.hpp"

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <numeric>
#include <string_view>
#include <system_error>

#include <fmt/format.h>

#include "io/output.hpp"
#include "tumble/core/error.hpp"
#include "tumble/sim/contact_network.hpp"

namespace tumble::io {

namespace fs = std::filesystem;

namespace {

using Buffer = fmt::memory_buffer;

// Array indices of the particles in the order of their global ids.
std::vector<std::size_t> order_by_id(const ParticleStore& p) {
    std::vector<std::size_t> by_id(p.size());
    std::iota(by_id.begin(), by_id.end(), std::size_t{0});
    std::sort(by_id.begin(), by_id.end(), [&](std::size_t a, std::size_t b) { return p.id[a] < p.id[b]; });
    return by_id;
}

// <DataArray> of one value per tuple, `type` a VTK type name (Float64,
// Int64, Int32, UInt8). fmt's "{}" writes a double in the shortest form that
// reads back to the same double; small integers are written as integers.
template <class T>
void scalar_array(Buffer& b, std::string_view type, std::string_view name, const std::vector<T>& values) {
    fmt::format_to(fmt::appender(b), "        <DataArray type=\"{}\" Name=\"{}\" format=\"ascii\">\n", type, name);
    for (const T& v : values) {
        if constexpr (sizeof(T) == 1)
            fmt::format_to(fmt::appender(b), "{}\n", static_cast<int>(v));
        else
            fmt::format_to(fmt::appender(b), "{}\n", v);
    }
    fmt::format_to(fmt::appender(b), "        </DataArray>\n");
}

// <DataArray> of three Float64 components per tuple.
void vector_array(Buffer& b, std::string_view name, const std::vector<Vec3>& values) {
    fmt::format_to(fmt::appender(b),
                   "        <DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"3\" format=\"ascii\">\n", name);
    for (const Vec3& v : values) fmt::format_to(fmt::appender(b), "{} {} {}\n", v.x, v.y, v.z);
    fmt::format_to(fmt::appender(b), "        </DataArray>\n");
}

// The time of the state, which ParaView reads from FieldData "TimeValue".
void time_field(Buffer& b, const Simulation& sim) {
    fmt::format_to(fmt::appender(b),
                   "    <FieldData>\n"
                   "      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">{}</DataArray>\n"
                   "      <DataArray type=\"Int64\" Name=\"step\" NumberOfTuples=\"1\" format=\"ascii\">{}</DataArray>\n"
                   "    </FieldData>\n",
                   sim.time(), sim.step_count());
}

void open_file(Buffer& b, std::string_view type) {
    // Version 0.1 is read by every VTK and ParaView of the last 15 years;
    // byte_order matters only for binary data and is given for completeness.
    fmt::format_to(fmt::appender(b),
                   "<?xml version=\"1.0\"?>\n"
                   "<VTKFile type=\"{0}\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
                   "  <{0}>\n",
                   type);
}

void close_file(Buffer& b, std::string_view type) {
    fmt::format_to(fmt::appender(b), "    </Piece>\n  </{}>\n</VTKFile>\n", type);
}

void write_buffer(const fs::path& file, const Buffer& b) {
    std::ofstream out = open_for_writing(file);
    out.write(b.data(), static_cast<std::streamsize>(b.size()));
    check_written(out, file);
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

void write_vtu_snapshot(const fs::path& file, const Simulation& sim) {
    const ParticleStore& p = sim.particles();
    const std::vector<std::size_t> by_id = order_by_id(p);
    const std::vector<std::uint32_t> counts = contact_counts(sim);
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

    Buffer b;
    open_file(b, "UnstructuredGrid");
    time_field(b, sim);
    fmt::format_to(fmt::appender(b), "    <Piece NumberOfPoints=\"{0}\" NumberOfCells=\"{0}\">\n", n);
    fmt::format_to(fmt::appender(b), "      <PointData Scalars=\"radius\" Vectors=\"velocity\">\n");
    scalar_array(b, "Int64", "id", id);
    vector_array(b, "velocity", velocity);
    vector_array(b, "angular_velocity", angular_velocity);
    scalar_array(b, "Float64", "radius", radius);
    scalar_array(b, "Int32", "material", material);
    scalar_array(b, "Int32", "tag", tag);
    scalar_array(b, "UInt8", "kinematic", kinematic);
    scalar_array(b, "Int32", "contacts", contacts);
    fmt::format_to(fmt::appender(b), "      </PointData>\n      <Points>\n");
    vector_array(b, "position", position);
    fmt::format_to(fmt::appender(b), "      </Points>\n      <Cells>\n");
    scalar_array(b, "Int64", "connectivity", connectivity);
    scalar_array(b, "Int64", "offsets", offsets);
    scalar_array(b, "UInt8", "types", types);
    fmt::format_to(fmt::appender(b), "      </Cells>\n");
    close_file(b, "UnstructuredGrid");
    write_buffer(file, b);
}

void write_vtp_contact_network(const fs::path& file, const Simulation& sim) {
    const std::vector<ContactLink> links = contact_network(sim);
    const ParticleStore& p = sim.particles();
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

    Buffer b;
    open_file(b, "PolyData");
    time_field(b, sim);
    fmt::format_to(fmt::appender(b),
                   "    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"{}\" NumberOfStrips=\"0\" "
                   "NumberOfPolys=\"0\">\n",
                   2 * n, n);
    fmt::format_to(fmt::appender(b), "      <CellData Scalars=\"normal_force\" Vectors=\"normal\">\n");
    scalar_array(b, "Int64", "id_i", id_i);
    scalar_array(b, "Int64", "id_j", id_j);
    scalar_array(b, "Float64", "normal_force", normal_force);
    scalar_array(b, "Float64", "overlap", overlap);
    vector_array(b, "normal", normal);
    fmt::format_to(fmt::appender(b), "      </CellData>\n      <Points>\n");
    vector_array(b, "position", ends);
    fmt::format_to(fmt::appender(b), "      </Points>\n      <Lines>\n");
    scalar_array(b, "Int64", "connectivity", connectivity);
    scalar_array(b, "Int64", "offsets", offsets);
    fmt::format_to(fmt::appender(b), "      </Lines>\n");
    close_file(b, "PolyData");
    write_buffer(file, b);
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

    fs::path temporary = file_;
    temporary += ".tmp";
    write_buffer(temporary, b);
    std::error_code ec;
    fs::rename(temporary, file_, ec);  // atomic on POSIX file systems
    if (ec) throw Error(file_.string() + ": cannot replace the index: " + ec.message());
}

}  // namespace tumble::io
